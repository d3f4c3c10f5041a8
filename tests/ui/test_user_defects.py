"""Defects a new user hit in the APOSS window (issue 16: 2e-2i, 2m), each driven through the widgets' own
signals: mouse clicks, keys, menu actions, dialogs answered."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QColor
from PySide6.QtWidgets import QAbstractItemView, QLineEdit

from motiontool.ui.watch import WatchAddDialog
from tests.modal import answering, ok_reply
from tests.ui.test_debugger import HELLO, _point_at, _prepare

FAILING = 'DIM a[2]\nPRINT "go"\nx = 0\nDELAY 100\nx = a[5]\nPRINT "after"\n'


def click_message(qtbot, window, fragment: str, double: bool = False) -> None:
    """Click (or double-click) the Communication pane's line that contains `fragment`."""
    pane = window.messages
    block = pane.document().begin()
    while block.isValid() and fragment not in block.text():
        block = block.next()
    assert block.isValid(), f"no message with {fragment!r}"
    pane.centerCursor()
    cursor = pane.textCursor()
    cursor.setPosition(block.position() + 2)
    pos = pane.cursorRect(cursor).center()
    if double:
        qtbot.mouseDClick(pane.viewport(), Qt.MouseButton.LeftButton, pos=pos)
    else:
        qtbot.mouseClick(pane.viewport(), Qt.MouseButton.LeftButton, pos=pos)


def run_failing(window, qtbot):
    editor = window.new_file()
    editor.setPlainText(FAILING)
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    qtbot.waitUntil(lambda: "program ended with" in window.messages.toPlainText(), timeout=10000)
    return editor


# --- 2e ----------------------------------------------------------------------------------------------------
def test_the_value_popup_stays_after_the_click_until_the_mouse_moves_away(window, qtbot):
    """DG L3440-3444: "the current value of the variable is shown in a yellow popup … until the mouse is moved
    away". It vanished as the button was released."""
    editor = _prepare(window, qtbot)
    qtbot.keyClick(editor, Qt.Key.Key_F9)                     # i = 1 has run
    qtbot.waitUntil(lambda: editor.debug.debug_current == 4, timeout=5000)
    at = _point_at(editor, 3, 1)                              # the `i` of `i = 1`
    qtbot.mouseClick(editor.viewport(), Qt.MouseButton.LeftButton, pos=at)
    popup = editor.debug.value_popup
    qtbot.wait(100)
    assert popup is not None and popup.isVisible() and popup.text() == "i = 1"
    qtbot.mouseMove(editor.viewport(), at + QPoint(3, 1))     # a small move keeps it
    assert popup.isVisible()
    qtbot.mouseMove(editor.viewport(), at + QPoint(80, 40))   # away: it goes
    qtbot.waitUntil(lambda: not popup.isVisible(), timeout=2000)
    window.debugger.end()


# --- 2f ----------------------------------------------------------------------------------------------------
def test_clicking_a_compiler_error_jumps_to_its_line_and_syntax_check_writes_the_ad_file(window, qtbot, tmp_path):
    """DG 2479-2483 / ide-spec S10: F4 names the line in the Communication pane and writes `<name>.ad$`; a click
    on the message puts the caret on that line (in its program's tab)."""
    program = tmp_path / "conveyor.m"
    program.write_text("VEL 100\nACC 100\nDEC 100\nx = 1\ny = 2\nz = 3\nFOO 12\nPOSA 1000\n", encoding="utf-8")
    editor = window.open_file(program)
    qtbot.keyClick(editor, Qt.Key.Key_F4)
    assert f"{program.resolve()}:7:1: error:" in window.messages.toPlainText()
    xref = program.with_suffix(".ad$")
    assert xref.exists() and "error" in xref.read_text() and ":7:1:" in xref.read_text()
    other = window.new_file()
    assert window.current_editor() is other
    click_message(qtbot, window, ":7:1: error:")
    assert window.current_editor() is editor and editor.caret_line_col() == (7, 1)
    editor.goto_line(1)
    window.tabs.setCurrentWidget(other)
    click_message(qtbot, window, ":7:1: error:", double=True)
    assert window.current_editor() is editor and editor.caret_line_col()[0] == 7
    untitled = window.new_file()
    untitled.setPlainText("POSA\n")
    qtbot.keyClick(untitled, Qt.Key.Key_F4)
    assert (Path(window._config_dir()) / "temp.ad$").exists()   # an unsaved program's (DG 6268)


# --- 2g ----------------------------------------------------------------------------------------------------
def _mark_pixels(editor, line: int) -> list[QColor]:
    gutter = editor.gutter
    image = gutter.grab().toImage()
    cursor = editor.textCursor()
    cursor.setPosition(editor.document().findBlockByNumber(line - 1).position())
    rect = editor.cursorRect(cursor)
    return [image.pixelColor(x, y) for x in range(0, 15) for y in range(rect.top(), rect.bottom())]


def test_a_syntax_error_mark_does_not_look_like_a_breakpoint(window, qtbot):
    """ide-spec 3.5: breakpoints are red dots; an error's mark is a red square with a white cross."""
    editor = _prepare(window, qtbot)
    qtbot.mouseDClick(editor.viewport(), Qt.MouseButton.LeftButton, pos=_point_at(editor, 5, 4))
    assert editor.debug.breakpoints() == [5]
    window.actions_by_text["End Debug"].trigger()
    cursor = editor.textCursor()
    cursor.setPosition(editor.document().findBlockByNumber(6).position())
    editor.setTextCursor(cursor)
    qtbot.keyClicks(editor, "POSA")                           # line 7 becomes a syntax error
    qtbot.keyClick(editor, Qt.Key.Key_Return)
    qtbot.keyClick(editor, Qt.Key.Key_F4)
    assert any(d[0] == 7 and d[2] == "error" for d in editor.diagnostics())
    breakpoint_mark, error_mark = _mark_pixels(editor, 5), _mark_pixels(editor, 7)

    def white(c):
        return c.red() > 250 and c.green() > 250 and c.blue() > 250

    def red(c):
        return c.red() > 150 and c.green() < 90 and c.blue() < 90

    assert sum(map(red, breakpoint_mark)) > 10 and sum(map(red, error_mark)) > 10
    assert sum(map(white, error_mark)) > 3 and sum(map(white, breakpoint_mark)) == 0
    assert breakpoint_mark != error_mark


# --- 2h ----------------------------------------------------------------------------------------------------
def test_a_controller_error_names_its_program_line_and_a_click_goes_there(window, qtbot):
    """A program that fails says where, as `motiontool run` does, in the Communication pane and the status bar;
    clicking the message puts the caret on that line of the program that ran."""
    editor = run_failing(window, qtbot)
    text = window.messages.toPlainText()
    assert "[01] error 171: Array too small (line 5)" in text
    assert "[01] program ended with error 171: Array too small (line 5)" in text
    qtbot.waitUntil(lambda: "line 5" in window.controller_label.text(), timeout=3000)
    other = window.new_file()
    assert window.current_editor() is other
    click_message(qtbot, window, "program ended with error 171")
    assert window.current_editor() is editor and editor.caret_line_col()[0] == 5


# --- 2i ----------------------------------------------------------------------------------------------------
def test_the_error_shows_in_the_title_of_its_program_only_and_goes_when_cleared(window, qtbot):
    editor = run_failing(window, qtbot)
    qtbot.waitUntil(lambda: "error 171" in window.windowTitle(), timeout=3000)
    other = window.new_file()
    assert "error" not in window.windowTitle()
    window.tabs.setCurrentWidget(editor)
    assert "error 171" in window.windowTitle()
    editor.setPlainText('ERRCLR\nPRINT "cleared"\nmain:\nDELAY 10\nGOTO main\n')
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    qtbot.waitUntil(lambda: "cleared" in window.messages.toPlainText(), timeout=5000)
    qtbot.waitUntil(lambda: "error" not in window.windowTitle(), timeout=3000)
    window.tabs.setCurrentWidget(other)
    assert "error" not in window.windowTitle()


# --- 2m ----------------------------------------------------------------------------------------------------
def test_watch_value_cells_can_be_edited_and_a_variable_and_a_parameter_are_added_together(window, qtbot):
    """DG L2452-2467: Watch Add with several items selected adds them all; a value typed into the Value cell
    is written to the controller (a parameter checked against its range first)."""
    editor = window.new_file()
    editor.setPlainText("i = 0\nagain:\ni = i + 1\nDELAY 10\nGOTO again\n")
    window.actions_by_text["Prepare Singlestep"].trigger()
    assert window.debugger.active

    def choose(dialog):
        assert isinstance(dialog, WatchAddDialog)
        dialog.program.item(0).setSelected(True)                                   # i
        kprop = next(dialog.system.topLevelItem(1).child(k) for k in range(dialog.system.topLevelItem(1)
                                                                                  .childCount())
                     if dialog.system.topLevelItem(1).child(k).text(0) == "KPROP")
        kprop.setSelected(True)
        dialog.add_button.click()

    with answering(qtbot, ok_reply(choose)):
        window.actions_by_text["Watch Add"].trigger()
    pane = window.debugger.watch
    assert [(e.kind, e.key) for e in pane.entries] == [("variable", "i"), ("parameter", "KPROP")]
    window.actions_by_text["Watch Start"].trigger()
    qtbot.waitUntil(lambda: pane.values()[1] != "", timeout=3000)

    def type_value(row, text):
        table = pane.table
        rect = table.visualItemRect(table.item(row, 1))
        qtbot.mouseClick(table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
        qtbot.mouseDClick(table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
        line = next(w for w in table.findChildren(QLineEdit) if w.isVisible())
        line.selectAll()
        qtbot.keyClicks(line, text)
        qtbot.keyClick(line, Qt.Key.Key_Return)

    type_value(1, "55")
    qtbot.waitUntil(lambda: window.bridge.link.read_parameter("KPROP") == 55, timeout=3000)
    type_value(1, "-4")
    qtbot.waitUntil(lambda: "outside" in pane.table.item(1, 1).toolTip(), timeout=3000)   # refused, with why
    assert "Watch: KPROP: " in window.messages.toPlainText()                                # and logged
    assert window.bridge.link.read_parameter("KPROP") == 55
    type_value(0, "1000")
    qtbot.waitUntil(lambda: window.bridge.link.call("read_variables", names=["i"])[0] == 1000, timeout=3000)
    assert pane.table.editTriggers() != QAbstractItemView.EditTrigger.NoEditTriggers
    window.actions_by_text["Watch Stop"].trigger()
    window.debugger.end()


def test_single_step_from_the_end_of_a_while_body_stops_at_the_while_test(window, qtbot):
    """DG L3400-3402: F9 stops before the next statement to run; after `i = i + 1` (line 7) that is the WHILE
    test on line 4, not the print inside the loop (line 5)."""
    editor = _prepare(window, qtbot)
    lines = [editor.debug.debug_current]
    for _ in range(5):
        qtbot.keyClick(editor, Qt.Key.Key_F9)
        qtbot.waitUntil(lambda: editor.debug.debug_current not in (None, lines[-1]), timeout=5000)
        lines.append(editor.debug.debug_current)
    assert lines == [3, 4, 5, 6, 7, 4]
    assert HELLO.splitlines()[3].startswith("while")
    window.debugger.end()
