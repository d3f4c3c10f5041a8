"""Development menu (DG 2366-2607): Execute, Break, Continue, Syntax Check, Compile to file, Command List.

What runs on the controller (Execute, Break, Continue, Execute now) is the window session's ProgramCommands
(session/program.py); this adds the editor: it compiles the current program and marks its errors."""

from __future__ import annotations

from pathlib import Path

from motiontool.aposs.driver import CompileResult, compile_source
from motiontool.dpl.driver import CheckResult
from motiontool.dpl.image import DplImage
from motiontool.fileio import atomic_write_bytes, write_error
from motiontool.session.compiling import CheckOutcome, CompilerSettings, compile_program
from motiontool.session.controllers import APC_SIM, InterfaceConfig
from motiontool.session.program import Program, ProgramCommands
from motiontool.ui.link_jobs import waiting

DEFAULT_CONTROLLER = ("embedded", 1)
MAX_NOTED_ERRORS = 1000  # a controller keeps its last 50; this bounds a window that runs for days


class Development:
    """The Development commands of one main window."""

    def __init__(self, window) -> None:
        self.w = window
        self._commands: ProgramCommands | None = None
        # (controller ID, time_ms, error number) → (editor, program label) of the program that raised it: the
        # controller's error history has no program, so the IDE notes it as each error arrives (I19)
        self.error_programs: dict[tuple[int, int, int], tuple[object, str]] = {}

    @property
    def commands(self) -> ProgramCommands:
        """Execute's steps on the window's session (session/program.py): requests off the GUI thread, questions
        through the window's prompts, what happened in the Communication pane."""
        if self._commands is None:
            self._commands = ProgramCommands(self.w.connection.session, self.w.prompts, self.w.messages.ide,
                                             lambda doing, work: waiting(self.w, doing, work))
        return self._commands

    @property
    def ran(self) -> dict[int, object]:
        """Controller ID → the editor whose program was last started there."""
        return self.commands.ran

    @property
    def images(self) -> dict[int, object]:
        """Controller ID → the image downloaded there (Error History's Offset)."""
        return self.commands.images

    def note_error(self, controller_id: int, time_ms: int, number: int) -> None:
        """An error event: remember which program ran there (the editor may be closed later; its label stays)."""
        editor = self.ran.get(controller_id)
        if editor is None or editor not in self.w.editors():
            return  # not started from this window: the IDE cannot tell which program it was
        self.error_programs[(controller_id, int(time_ms), int(number))] = (editor, self.w.program_label(editor))
        while len(self.error_programs) > MAX_NOTED_ERRORS:
            del self.error_programs[next(iter(self.error_programs))]

    def error_program(self, controller_id: int, time_ms: int, number: int) -> tuple[object, str] | None:
        return self.error_programs.get((controller_id, int(time_ms), int(number)))

    # --- connection (ui/connection.py) ------------------------------------------------------------------
    def connect_default(self) -> bool:
        """DG 2054-2062: commands that need a controller connect first — to the controller this window had
        (after a lost connection, DG 2064-2066), else to the default one."""
        return self.w.connection.connect_default()

    def select_controller(self, controller_id: int, *, interface: str | None = None) -> bool:
        """Select Controller (DG 2536-2546): the window moves to another controller; the one it leaves keeps
        running its program."""
        return self.w.connection.select(controller_id, interface=interface)

    def break_all(self) -> None:
        self.w.connection.break_all()

    def start_all(self) -> None:
        self.w.connection.start_all()

    def delete_programs_all(self) -> None:
        self.w.connection.delete_programs_all()

    # --- compile ---------------------------------------------------------------------------------------
    def compile_current(self, *, debug: bool = False) -> CheckOutcome | None:
        editor = self.w.current_editor()
        if editor is None:
            return None
        path = editor.property("path") or None
        name = Path(path).name if path else (editor.property("sample") or "Untitled.m")
        outcome = compile_program(editor.toPlainText(), path, name, dpl=editor.language == "dpl", debug=debug,
                                  settings=self.compiler_settings())
        self.w.show_diagnostics(editor, outcome.result)
        return outcome

    def compiler_settings(self) -> CompilerSettings:
        return CompilerSettings.load(self.w.settings)

    def goto_first_error(self, outcome: CheckOutcome) -> None:
        line, col = outcome.first_error
        self.w.current_editor().goto_line(line, col=col)

    def syntax_check(self) -> bool:
        """F4 (DG 2479-2483): test-compile; messages name line and text; the caret goes to the error."""
        outcome = self.compile_current()
        if outcome is None:
            return False
        messages = self.w.messages
        for d in outcome.result.diagnostics:
            messages.ide(d.format())
        xref = self.write_cross_reference(outcome) if isinstance(outcome.result, CompileResult) \
            and self.compiler_settings().cross_reference else None
        if xref is not None:
            messages.ide(f"Cross reference: {xref}")
        if outcome.result.ok:
            warnings = len(outcome.result.diagnostics)
            messages.ide("Syntax check: no errors" + (f", {warnings} warning(s)" if warnings else ""))
            return True
        messages.ide(f"Syntax check: {len(outcome.result.errors)} error(s)")
        self.goto_first_error(outcome)
        return False

    def write_cross_reference(self, outcome: CheckOutcome) -> Path | None:
        """Syntax Check's cross reference file `<name>.ad$` (DG 2483; `temp.ad$` for an unsaved program)."""
        from motiontool.aposs.xref import write_xref, xref_path

        editor = self.w.current_editor()
        saved = editor.property("path")
        path = xref_path(Path(saved) if saved else None, Path(self.w._config_dir()))
        try:
            write_xref(path, outcome.result, self.w.program_label(editor))
        except OSError as exc:
            self.w.messages.ide(f"Cross reference {path}: {exc.strerror or exc}")
            return None
        return path

    def compile_to_file(self, *, target: Path | None = None) -> bool:
        outcome = self.compile_current()
        if outcome is None or not outcome.result.ok:
            if outcome is not None:
                for d in outcome.result.errors:
                    self.w.messages.ide(d.format())
            return False
        if isinstance(outcome.result, CheckResult):  # the simulated APC takes DPL source (docs/dpl.md)
            self.w.messages.ide("A DPL program is downloaded as it is (Execute); it has no program image file")
            return False
        if target is None:
            editor = self.w.current_editor()
            default = Path(editor.property("path") or "program.m").with_suffix(".bin")
            target = self.w.prompts.save_path("Compile to file", str(default), "Program image (*.bin)")
            if target is None:
                return False
        try:
            atomic_write_bytes(target, outcome.result.image.to_bytes())
        except OSError as exc:
            from motiontool.ui.file_errors import save_failed

            self.w.messages.ide(f"Compile to file: {write_error(target, exc)}")
            save_failed(self.w, "Compile to file", target, exc, "The program was compiled but not written.")
            return False
        self.w.messages.ide(f"Compiled to {target}")
        return True

    # --- run -------------------------------------------------------------------------------------------
    def execute(self, *, ask: bool = True) -> bool:
        """F5 (DG 2380-2391): connect, stop a running program (after asking), compile, download to temporary
        memory, start (session/program.py). A DPL program runs on the simulated APC, an APOSS program on the
        default interface."""
        if not self._controller_for_language():
            return False
        if not self.connect_default():
            return False
        debugger = getattr(self.w, "debugger", None)
        if debugger is not None and debugger.active:  # F5 runs the normal build: leave the debug session
            debugger.end()
        return self.commands.execute(self._build, self._test_settings, ask=ask)

    def _build(self) -> Program | None:
        """Execute's compile step: the current editor's program, its errors marked there."""
        outcome = self.compile_current()
        if outcome is None:
            return None
        if not outcome.result.ok:
            for d in outcome.result.diagnostics:
                self.w.messages.ide(d.format())
            self.w.messages.ide("Compilation error(s): program not executed")
            self.goto_first_error(outcome)
            return None
        editor = self.w.current_editor()
        if isinstance(outcome.result, CompileResult):
            image = outcome.result.image
            return Program(image, self.compiler_settings().stack_size, [(v.name, v.dims) for v in image.dims],
                           origin=editor, listing=image)
        # a DPL program goes as its source; the watch offers its variables and arrays
        symbols = outcome.result.symbols
        self.w.debugger.watch.set_variables(sorted(symbols.variables), sorted(symbols.arrays.items()))
        return Program(DplImage(editor.property("path") or "Untitled.dpl", outcome.result.source), origin=editor)

    def _test_settings(self):
        """Offer a header's test settings (ui/io_panel.py); what is to be applied, None for a header that cannot
        be read when they are (said in the Communication window)."""
        from motiontool.program_header import HeaderError
        from motiontool.ui.io_panel import armed_test_settings, offer_test_settings

        editor = self.w.current_editor()
        label = Path(self.w.program_label(editor)).name
        offer_test_settings(self.w, editor, label)
        try:
            return armed_test_settings(self.w, editor, label)
        except HeaderError as exc:
            self.w.messages.ide(f"{exc}: program not executed")
            return None

    def _controller_for_language(self) -> bool:
        """Move the window to the simulated APC for a DPL program, and back to the default interface for APOSS."""
        editor = self.w.current_editor()
        dpl = editor is not None and editor.language == "dpl"
        apc = InterfaceConfig(kind=APC_SIM, first=1, last=1)
        on_apc = self.w.connection.interface_key == apc.key
        watch = getattr(getattr(self.w, "debugger", None), "watch", None)
        if watch is not None:  # the watch offers what the controller has: APC read parameters or MCO data
            watch.controller_kind = "APC" if dpl else "MCO"
        if dpl and not on_apc:
            self.w.controllers.open_interface(config=apc)
            return self.select_controller(1, interface=apc.key)
        if on_apc and not dpl:
            return self.select_controller(DEFAULT_CONTROLLER[1])
        return True

    def break_program(self) -> None:
        """Esc (DG 2054-2062): without a controller it connects; with one it aborts the running program."""
        self.commands.break_program()

    def continue_program(self) -> None:
        self.commands.continue_program()

    def execute_line(self, line: str) -> None:
        """Command List → Execute now: the line runs as a one-line temporary program."""
        if not self.connect_default():
            return
        result = compile_source(line + "\n", "command.m")
        if not result.ok:
            for d in result.errors:
                self.w.messages.ide(d.format())
            return
        self.commands.execute_line(result.image)
