"""Controller ▸ Error History names the program of each error and a double-click shows the line in that program
(issue 23 item 7): before, it jumped to line N of whichever tab was in front."""

from __future__ import annotations

from PySide6.QtCore import Qt

from motiontool.ui.error_history import COLUMNS, ErrorHistoryDialog
from tests.modal import answering
from tests.ui.test_user_defects import FAILING


def run_saved(window, qtbot, path):
    path.write_text(FAILING, encoding="utf-8")   # error 171 (array index) in line 5
    editor = window.open_file(path)
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    qtbot.waitUntil(lambda: "program ended with" in window.messages.toPlainText(), timeout=10000)
    return editor


def double_click_row(qtbot, dialog: ErrorHistoryDialog, row: int) -> None:
    table = dialog.table
    rect = table.visualRect(table.model().index(row, COLUMNS.index("Message")))
    qtbot.mouseClick(table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
    qtbot.mouseDClick(table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())


def cell(dialog: ErrorHistoryDialog, row: int, column: str) -> str:
    return dialog.table.item(row, COLUMNS.index(column)).text()


def test_the_program_column_names_the_file_and_a_double_click_opens_it_at_the_line(window, qtbot, tmp_path):
    failing = run_saved(window, qtbot, tmp_path / "feeder.m")
    window.tabs.setCurrentWidget(failing)
    window.actions_by_text["Close"].trigger()                 # File ▸ Close: its tab closed since
    assert failing not in window.editors()
    other = window.new_file()                                 # another program in front, longer than 5 lines
    other.setPlainText("\n".join(f"x{i} = {i}" for i in range(20)))
    other.goto_line(1)
    seen = {}

    def jump(dialog):
        assert isinstance(dialog, ErrorHistoryDialog)
        seen["program"], seen["line"] = cell(dialog, 0, "Program"), cell(dialog, 0, "Line")
        double_click_row(qtbot, dialog, 0)

    with answering(qtbot, jump):
        window.actions_by_text["Error History..."].trigger()
    assert seen == {"program": "feeder.m", "line": "5"}
    editor = window.current_editor()
    assert editor is not other and editor.property("path") == str((tmp_path / "feeder.m").resolve())
    assert editor.textCursor().blockNumber() + 1 == 5
    assert other.textCursor().blockNumber() == 0               # the program in front was not moved


def test_a_double_click_brings_the_programs_tab_to_the_front(window, qtbot, tmp_path):
    failing = run_saved(window, qtbot, tmp_path / "feeder.m")
    other = window.new_file()
    other.setPlainText("\n".join(f"x{i} = {i}" for i in range(20)))

    def jump(dialog):
        double_click_row(qtbot, dialog, 0)

    with answering(qtbot, jump):
        window.actions_by_text["Error History..."].trigger()
    assert window.current_editor() is failing and failing.textCursor().blockNumber() + 1 == 5
    assert len(window.editors()) == 2                          # the open tab, not a second copy
