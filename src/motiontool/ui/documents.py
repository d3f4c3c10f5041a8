"""Which window opens a file (File → Open, the command line): a program opens in an edit tab, a controller
configuration (.zbc, .cnf) in the CAM-Editor, an oscilloscope file (.zbo) or an old Testrun .txt in an
oscilloscope window, an array definition file (.zba) in the Array Editor (DG 2213-2221, 3483, 4515, 5349)."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QWidget

from motiontool.ui import tool_windows

OPEN_FILTER = ("motiontool files (*.m *.dpl *.zbc *.cnf *.zbo *.zba *.txt);;APOSS programs (*.m);;"
               "DPL programs (*.dpl);;CAM configuration (*.zbc *.cnf);;Oscilloscope files (*.zbo);;"
               "Array definition (*.zba);;Old Testrun files (*.txt);;All files (*)")


def open_dialog(w) -> QWidget | None:
    """File → Open: any file the IDE knows, each into its window."""
    chosen = w.prompts.open_path("Open", "", OPEN_FILTER)
    return open_document(w, chosen) if chosen is not None else None


def open_document(w, path: Path) -> QWidget | None:
    """Open `path` in the window that handles it; a file that cannot be read is reported (by that window, or
    here for programs and oscilloscope files) and nothing else changes."""
    path = Path(path)
    suffix = path.suffix.lower()
    try:
        if suffix in (".zbc", ".cnf"):
            return _cam(w, path)
        if suffix == ".zbo":
            return _scope(w, path)
        if suffix == ".zba":
            return _arrays(w, path)
        if suffix == ".txt":
            from motiontool.scope.testrun import NotTestrun

            try:
                return _scope(w, path)
            except NotTestrun:  # an ordinary text file: the program editor (DG 5357-5376)
                pass
        return w.open_file(path)
    except (OSError, ValueError) as exc:
        text = f"{path}: {exc.strerror if isinstance(exc, OSError) and exc.strerror else exc}"
        w.messages.ide(f"Open: {text}")
        w.prompts.warn("Open", text)
        return None


def show_location(w, file: str, line: int, col: int, controller_id: int | None) -> bool:
    """A click on a message with a place (messages.py): bring its program to the front with the caret on the
    line. A controller's error names the program last run on that controller from this window; a compiler
    message names its file (a saved program, an include file, or an unsaved buffer's label)."""
    editor = None
    if controller_id is not None:  # the program that ran there, else the one in front (DG 3023)
        editor = w.development.ran.get(controller_id) or w.current_editor()
    else:
        for candidate in w.editors():
            if file in (candidate.property("path"), w.program_label(candidate)):
                editor = candidate
                break
        if editor is None and file and Path(file).is_file():
            editor = w.open_file(Path(file))
    if editor is None or editor not in w.editors():
        w.statusBar().showMessage(f"The program of line {line} is not open", 5000)
        return False
    w.tabs.setCurrentWidget(editor)
    editor.goto_line(line, col=col)
    editor.setFocus()
    return True


def _cam(w, path: Path) -> QWidget | None:
    editor = tool_windows.cam_editor(w)
    if editor._discard_ok():
        editor.open_file(path)  # a file it cannot read: its message line names the place
    return editor


def _scope(w, path: Path) -> QWidget:
    from motiontool.scope.ui import open_scope_file

    window = open_scope_file(path, parent=w, prompts=w.prompts)
    window.setWindowFlag(Qt.WindowType.Window, True)
    tool_windows.keep_scope(w, window)
    window.show()
    return window


def _arrays(w, path: Path) -> QWidget:
    editor = tool_windows.array_editor(w)
    editor.open_file(path=path)  # a file it cannot read: it says why
    return editor
