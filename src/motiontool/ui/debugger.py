"""Development → Prepare Singlestep / Go / Singlestep / End Debug and the watch (ide-spec 3.1-3.14).

The debug session compiles the current program in debug mode (statement stops), downloads it, starts it
stopped before its first statement and then follows the controller's status: whenever the program stands in
"break" the editor shows the next statement in yellow.  Breakpoints are sent to the controller whenever they
change.  The requests and the debug run's state are the session's (session/debug.py DebugSession, on the
window's controller); each request runs on a thread while the window paints and says what it waits for
(ui/link_jobs.waiting, decision I34). This adds the editor: its marks, the yellow line, the value popup, the Watch.
"""

from __future__ import annotations

from PySide6.QtCore import QObject, QTimer

from motiontool.comms.protocol import LinkError
from motiontool.session.debug import DebugSession
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
        self.editor = None   # the editor whose program is being debugged
        # the debug run's requests and state (session/debug.py); it says what went wrong in the Communication pane
        self.debug = DebugSession(window.connection.session, window.messages.ide,
                                lambda doing, work: waiting(window, doing, work), window.prompts)
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
        messages.ide(f"Compiling debug ok ({len(image.to_bytes())} bytes)")
        editor = self.w.current_editor()

        def loaded(lines) -> list[int]:
            editor.debug.set_debug_lines(set(lines))
            return [n for n in editor.debug.breakpoints() if n in editor.debug.debug_lines]

        if not self.debug.prepare(image, dev.compiler_settings().stack_size, loaded):
            editor.debug.end_debug()
            return False
        self.editor = editor
        dev.ran[self.w.bridge.controller_id] = editor
        dev.images[self.w.bridge.controller_id] = image
        editor.debug.variable_value = self.read_value
        editor.breakpointsChanged.connect(self._send_breakpoints)
        editor.variableEditRequested.connect(self.change_value)
        self.watch.set_variables(program_variables(image), program_arrays(image))
        messages.ide("Prepare stepping ok")
        self.w.bridge.poll()
        return True

    def go(self) -> None:
        """Go (DG L2436-2438): run to the next breakpoint."""
        if self.active:
            self.debug.go()
            self.w.bridge.poll()

    def step(self) -> None:
        """Singlestep F9 (DG L2440-2442): run the yellow statement, stop before the next one."""
        if self.active:
            self.editor.debug.set_debug_current(None)
            self.debug.step()
            self.w.bridge.poll()

    def end(self) -> None:
        """End Debug (DG L2448-2450): leave debug mode; breakpoints stay for the next run."""
        if not self.active:
            return
        editor, self.editor = self.editor, None
        editor.breakpointsChanged.disconnect(self._send_breakpoints)
        editor.variableEditRequested.disconnect(self.change_value)
        editor.debug.end_debug()
        self.debug.end()
        self.w.messages.ide("Debug ended")

    def _send_breakpoints(self) -> None:
        self.debug.set_breakpoints(self.editor.debug.breakpoints())
        self.w.bridge.poll()

    def _status_changed(self, status) -> None:
        if not self.active:
            return
        if status.program_state == "break" and status.line:
            self.editor.debug.set_debug_current(status.line)
        elif status.program_state in ("ended", "error", "idle"):
            self.editor.debug.set_debug_current(None)
        else:
            self.editor.debug.set_debug_current(None)

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
        value = self.debug.read_value(name)
        return None if value is None else format_value(value)

    def change_value(self, name: str) -> None:
        """Right-click → change the variable on the controller (DG L3457-3459)."""
        current = self.read_value(name) or "0"
        text = self.w.prompts.text("Change value", f"New value of {name}:", default=current)
        if text is not None:
            self.write_value(name, text)

    def write_value(self, name: str, text: str) -> bool:
        try:
            value = parse_value(text)
        except ValueError:
            self.w.messages.ide(f"Change value: {text!r} is not a number")
            return False
        if not self.debug.write_value(name, value):
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
