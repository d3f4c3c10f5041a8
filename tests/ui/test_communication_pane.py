"""The Communication pane as a user reads it (issue 23 item 6): a long PRINT line does not hide the start of
the later messages sideways, Ctrl+C copies what the mouse selected, and the context menu's Clear empties it."""

from __future__ import annotations

from PySide6.QtCore import QPoint, Qt, QTimer
from PySide6.QtGui import QContextMenuEvent, QTextCursor
from PySide6.QtWidgets import QApplication, QMenu

LONG = "A" * 40 + " " + "B" * 160
LATER = "c" * 44  # wider than half the pane: the view centred the caret of each such line, cutting its start
# the program stays running: its end message is short and scrolled the view back, which hid the defect
# (messages one by one, as a program prints over time: lines arriving together came in one append)
PROGRAM = (f'PRINT "{LONG}"\nDELAY 5000\nPRINT "short one {LATER}"\nDELAY 5000\nPRINT "last one {LATER}"\n'
           'DELAY 100000\n')


def run(window, qtbot, program: str) -> None:
    editor = window.new_file()
    editor.setPlainText(program)
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    qtbot.waitUntil(lambda: "last one" in window.messages.toPlainText(), timeout=10000)
    qtbot.wait(50)


def block_with(pane, fragment: str):
    block = pane.document().begin()
    while block.isValid() and fragment not in block.text():
        block = block.next()
    assert block.isValid(), fragment
    return block


def point_of(pane, position: int) -> QPoint:
    cursor = QTextCursor(pane.document())
    cursor.setPosition(position)
    return pane.cursorRect(cursor).center()


def test_a_long_line_leaves_the_start_of_later_messages_in_view(window, qtbot):
    pane = window.messages
    window.resize(640, window.height())
    qtbot.wait(50)
    run(window, qtbot, PROGRAM)
    for fragment in ("short one", "last one"):
        start = point_of(pane, block_with(pane, fragment).position())
        assert pane.viewport().rect().contains(start), (fragment, start, pane.horizontalScrollBar().value())
    assert pane.horizontalScrollBar().value() == 0


def test_ctrl_c_copies_the_selection_and_clear_empties_the_pane(window, qtbot):
    pane = window.messages
    run(window, qtbot, PROGRAM)
    block = block_with(pane, "short one")
    start = block.position() + block.text().index("short")
    pane.setFocus()
    qtbot.mouseDClick(pane.viewport(), Qt.MouseButton.LeftButton, pos=point_of(pane, start + 1))  # the word
    QApplication.clipboard().clear()
    qtbot.keyClick(pane, Qt.Key.Key_C, Qt.KeyboardModifier.ControlModifier)
    assert QApplication.clipboard().text() == "short"
    pane.ide("a message arrives while the user selects")
    assert pane.textCursor().selectedText() == "short"         # the selection stays for the copy

    chosen = []

    def choose_clear() -> None:  # the menu is open: the user clicks its Clear entry
        menu = QApplication.activePopupWidget()
        assert isinstance(menu, QMenu)
        action = next(a for a in menu.actions() if a.text() == "Clear")
        chosen.append(action.isEnabled())
        action.trigger()
        menu.close()

    QTimer.singleShot(200, choose_clear)
    at = pane.viewport().rect().center()
    QApplication.sendEvent(pane.viewport(), QContextMenuEvent(QContextMenuEvent.Reason.Mouse, at,
                                                              pane.viewport().mapToGlobal(at)))
    assert chosen == [True]
    assert pane.toPlainText() == ""
