"""Development → Prepare Singlestep / Go / Singlestep / End Debug and the watch (ide-spec 3.1-3.14).

The debug session compiles the current program in debug mode (statement stops), downloads it, starts it
stopped before its first statement and then follows the controller's status: whenever the program stands in
"break" the editor shows the next statement in yellow.  Breakpoints are sent to the controller whenever they
change.  Everything goes through the window's LinkBridge; each request runs on a thread while the window paints
and says what it waits for (ui/link_jobs.waiting, decision I34).
"""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QObject, QTimer
from PySide6.QtWidgets import QInputDialog

from motiontool.comms.protocol import LinkError
from motiontool.ui.compiler_settings import NO_XREF
from motiontool.ui.link_jobs import waiting
from motiontool.ui.watch import WatchPane

WATCH_INTERVAL_MS = 250


def parse_value(text: str) -> int | float:
    """A typed value: a DOUBLE with a point or exponent, else a LONG (0x… hexadecimal); ValueError if neither."""
    text = text.strip()
    try:
        return float(text) if any(c in text for c in ".eE") and not text.lower().startswith("0x") else int(text, 0)
    except ValueError:
        raise ValueError(f"{text!r} is not a number") from None


def format_value(value) -> str:
    if isinstance(value, float):
        text = f"{value:.6f}".rstrip("0")
        return text + "0" if text.endswith(".") else text
    return str(value)


class Debugger(QObject):
    def __init__(self, window) -> None:
        super().__init__(window)
        self.w = window
        self.editor = None
        self.watch = WatchPane(window)
        self.watch.set_reader(self.read_watch)
        self.watch.set_writer(self.write_watch)
        self.watch.refused.connect(lambda key, why: self.w.messages.ide(f"Watch: {key}: {why}"))
        self._watch_timer = QTimer(self, interval=WATCH_INTERVAL_MS, timeout=self.refresh_watch)
        window.bridge.status_changed.connect(self._status_changed)

    @property
    def active(self) -> bool:
        return self.editor is not None

    def _link(self):
        return self.w.bridge.link

    def _report(self, exc: Exception) -> None:
        self.w.messages.ide(f"Controller {self.w.bridge.controller_id}: {exc}")

    def _wait(self, doing: str, work):
        """`work()` (link requests only, no widget) on a thread; user input waits, so no command starts twice."""
        return waiting(self.w, f"Controller {self.w.bridge.controller_id}: {doing} …", work)

    # --- session ---------------------------------------------------------------------------------------
    def prepare(self) -> bool:
        """Prepare Singlestep (DG L2432-2434, L3364-3382): compile in debug mode, download, do not run."""
        dev = self.w.development
        if self.active:
            self.end()
        if not dev.compiler_settings().cross_reference:
            self.w.messages.ide(NO_XREF)
            return False
        if not dev.connect_default():
            return False
        outcome = dev.compile_current(debug=True)
        if outcome is None:
            return False
        messages = self.w.messages
        if not outcome.result.ok:
            for d in outcome.result.diagnostics:
                messages.ide(d.format())
            messages.ide("Compiling debug failed: no debug session")
            dev.goto_first_error(outcome)
            return False
        image = outcome.result.image
        size = len(image.to_bytes())
        messages.ide(f"Compiling debug ok ({size} bytes)")
        editor = self.w.current_editor()
        link = self._link()
        stack = dev.compiler_settings().stack_size

        def send() -> None:
            if link.status().program_state == "running":
                link.break_program()
            link.download(image.to_bytes(), name=image.name, stack_size=stack)

        try:
            self._wait(f"downloading {Path(image.name).name} for debugging", send)
            messages.ide(f"Loading {size} bytes ok")
            editor.set_debug_lines({e.line for e in image.lines if e.file == 0})
            marks = [n for n in editor.breakpoints() if n in editor.debug_lines]
            self._wait("starting it before its first statement",
                       lambda: (link.set_breakpoints(marks), link.start(step=True)))
        except LinkError as exc:
            editor.end_debug()
            self._report(exc)
            return False
        self.editor = editor
        dev.ran[self.w.bridge.controller_id] = editor
        dev.images[self.w.bridge.controller_id] = image
        editor.variable_value = self.read_value
        editor.breakpointsChanged.connect(self._send_breakpoints)
        editor.variableEditRequested.connect(self.change_value)
        self.watch.set_variables(program_variables(image), program_arrays(image))
        messages.ide("Prepare stepping ok")
        self.w.bridge.poll()
        return True

    def go(self) -> None:
        """Go (DG L2436-2438): run to the next breakpoint."""
        if self.active:
            self._call("running to the next breakpoint", lambda link: link.continue_program())

    def step(self) -> None:
        """Singlestep F9 (DG L2440-2442): run the yellow statement, stop before the next one."""
        if self.active:
            self.editor.set_debug_current(None)
            self._call("stepping", lambda link: link.step())

    def end(self) -> None:
        """End Debug (DG L2448-2450): leave debug mode; breakpoints stay for the next run."""
        if not self.active:
            return
        editor, self.editor = self.editor, None
        editor.breakpointsChanged.disconnect(self._send_breakpoints)
        editor.variableEditRequested.disconnect(self.change_value)
        editor.end_debug()
        link = self._link()
        if link is not None:
            def stop() -> None:
                if link.status().program_state in ("running", "break"):
                    link.break_program()
                link.set_breakpoints([])

            try:
                self._wait("ending the debug session", stop)
            except LinkError as exc:
                self._report(exc)
        self.w.messages.ide("Debug ended")

    def _call(self, doing: str, action) -> None:
        link = self._link()
        if link is None:
            self._report(LinkError("not connected"))
            return
        try:
            self._wait(doing, lambda: action(link))
        except LinkError as exc:
            self._report(exc)
        self.w.bridge.poll()

    def _send_breakpoints(self) -> None:
        marks = [n for n in self.editor.breakpoints() if n in self.editor.debug_lines]
        self._call("setting the breakpoints", lambda link: link.set_breakpoints(marks))

    def _status_changed(self, status) -> None:
        if not self.active:
            return
        if status.program_state == "break" and status.line:
            self.editor.set_debug_current(status.line)
        elif status.program_state in ("ended", "error", "idle"):
            self.editor.set_debug_current(None)
        else:
            self.editor.set_debug_current(None)

    # --- variables -------------------------------------------------------------------------------------
    def read_watch(self, kind: str, key: str):
        link = self._link()
        if link is None:
            return "not connected"
        if kind == "parameter":
            return link.read_parameter(key)
        if kind == "signal":
            return link.read_signals([key])[0]
        return link.read_variables([key])[0]

    def write_watch(self, kind: str, key: str, text: str) -> str | None:
        """A value typed into the Watch pane: a program variable or a parameter (checked against its range
        first); None when written, else why not. Called on the pane's link-jobs thread: no widget here."""
        link = self._link()
        if link is None:
            return "not connected"
        try:
            if kind == "parameter":
                from motiontool.paramdb import database

                parameter = database().get(key)
                link.write_parameter(key, parameter.to_raw(parameter.validate(text)))
            elif kind == "variable":
                link.write_variable(key, parse_value(text))
            else:
                return f"{key} is read from the controller and cannot be set"
        except (ValueError, KeyError, LinkError) as exc:
            return str(exc)             # the pane says it (and logs it through `refused`)
        return None

    def read_value(self, name: str) -> str | None:
        """The value for the editor's click popup (DG L3440-3444), None when `name` is not a variable."""
        link = self._link()
        if link is None:
            return None
        try:
            return format_value(self._wait(f"reading {name}", lambda: link.read_variables([name])[0]))
        except LinkError:
            return None

    def change_value(self, name: str) -> None:
        """Right-click → change the variable on the controller (DG L3457-3459)."""
        current = self.read_value(name) or "0"
        text, ok = QInputDialog.getText(self.w, "Change value", f"New value of {name}:", text=current)
        if ok:
            self.write_value(name, text)

    def write_value(self, name: str, text: str) -> bool:
        try:
            value = parse_value(text)
        except ValueError:
            self.w.messages.ide(f"Change value: {text!r} is not a number")
            return False
        link = self._link()
        if link is None:
            self._report(LinkError("not connected"))
            return False
        try:
            self._wait(f"writing {name}", lambda: link.write_variable(name, value))
        except LinkError as exc:
            self._report(exc)
            return False
        self.refresh_watch()
        return True

    # --- watch (ide-spec 3.12, 3.13) -------------------------------------------------------------------
    def watch_add(self) -> None:
        if not self.w.development.compiler_settings().cross_reference:
            self.w.messages.ide(NO_XREF)
            return
        self.watch.show_add_dialog()

    def watch_start(self) -> None:
        self.watch.show()
        self.refresh_watch()
        self._watch_timer.start()

    def watch_stop(self) -> None:
        self._watch_timer.stop()

    @property
    def watching(self) -> bool:
        return self._watch_timer.isActive()

    def refresh_watch(self) -> None:
        if self._link() is not None:
            self.watch.refresh()


def program_variables(image) -> list[str]:
    """The program's scalar variables (the cross-reference), without the compiler's temporaries."""
    return [v.name for v in image.globals if not v.name.startswith("$")]


def program_arrays(image) -> list[tuple[str, int]]:
    out = []
    for v in image.dims + image.arrays:
        size = 1
        for d in v.dims:
            size *= d
        out.append((v.name, size))
    return out
