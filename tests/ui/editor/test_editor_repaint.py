"""What the editor repaints per keystroke (benchmarks/editor_latency.py; goal: at most 5 ms per keystroke).

A keystroke inside one line repaints that line only (not the whole view, not the margin); the screen
always shows exactly what a full repaint shows, also after edits that re-colour or move other lines.
"""

from __future__ import annotations

import pytest
from PySide6.QtCore import QEvent, QObject, QRect, Qt
from PySide6.QtGui import QImage, QTextCursor
from PySide6.QtWidgets import QApplication

from motiontool.ui.editor import CodeEditor

PROGRAM = "\n".join(f"pos_{i} = {i} * 10 // step {i}\nPOSA pos_{i}\nfoo bar {i}" for i in range(80))


@pytest.fixture(autouse=True)
def steady_caret(qapp):
    """The caret does not blink in these tests. A blink flips the caret between two paints, so a screen grab
    and a fresh rendering taken a moment apart differ by the caret alone (a 1 px x 15 px column at the caret,
    every failure seen at load 12-14), which says nothing about what an edit or a caret move repaints. With
    the blink off the caret is always drawn, and the comparisons stay pixel for pixel."""
    flash = QApplication.cursorFlashTime()
    QApplication.setCursorFlashTime(0)
    yield
    QApplication.setCursorFlashTime(flash)


class Paints(QObject):
    def __init__(self) -> None:
        super().__init__()
        self.rects: list[QRect] = []

    def eventFilter(self, obj, event) -> bool:  # noqa: N802 (Qt override)
        if event.type() == QEvent.Type.Paint:
            self.rects.append(event.rect())
        return False


def shown(editor: CodeEditor) -> QImage:
    """The pixels on the (offscreen) screen: what the last repaints left there."""
    QApplication.processEvents()
    fresh = editor.grab().toImage()
    return editor.screen().grabWindow(editor.winId()).toImage().convertToFormat(fresh.format())


def test_typing_in_a_line_repaints_that_line_only(qtbot, editor):
    editor.setPlainText(PROGRAM)
    editor.goto_line(30)
    editor.moveCursor(QTextCursor.MoveOperation.EndOfLine)
    QApplication.processEvents()
    line = editor.cursorRect()
    requests: list[QRect] = []
    editor.updateRequest.connect(lambda rect, _dy: requests.append(rect))
    margin = Paints()
    editor.gutter.installEventFilter(margin)
    for ch in "x = abc + 12":
        qtbot.keyClick(editor, ch)
        QApplication.processEvents()
    assert requests
    assert all(r.top() >= line.top() - 2 and r.bottom() <= line.bottom() + 2 for r in requests)
    assert margin.rects == []  # the line number and marks of the caret line do not change
    assert editor.document().findBlockByNumber(29).text().endswith("x = abc + 12")


def test_return_and_a_caret_move_repaint_the_margin(qtbot, editor):
    editor.setPlainText(PROGRAM)
    editor.goto_line(30)
    QApplication.processEvents()
    margin = Paints()
    editor.gutter.installEventFilter(margin)
    qtbot.keyClick(editor, Qt.Key.Key_Down)  # the bold caret-line number moves from line 30 to 31
    QApplication.processEvents()
    for number in (29, 30):  # 0-based
        y = editor.blockBoundingGeometry(editor.document().findBlockByNumber(number)).translated(
            editor.contentOffset()).center().y()
        assert any(r.top() <= y <= r.bottom() for r in margin.rects), f"line {number + 1}"
    margin.rects.clear()
    qtbot.keyClick(editor, Qt.Key.Key_Return)  # the numbers below the caret change
    QApplication.processEvents()
    assert any(r.height() >= editor.gutter.height() - 2 for r in margin.rects)


def test_an_opened_comment_recolours_and_repaints_the_lines_below(qtbot, editor):
    editor.setPlainText(PROGRAM)
    editor.goto_line(4)
    QApplication.processEvents()
    requests: list[QRect] = []
    editor.updateRequest.connect(lambda rect, _dy: requests.append(rect))
    qtbot.keyClicks(editor, "/*")
    QApplication.processEvents()
    assert any(r.contains(editor.viewport().rect()) for r in requests)
    comment = editor.highlighter.format_for("comment").foreground().color()
    below = editor.document().findBlockByNumber(10).layout().formats()
    assert below and all(r.format.foreground().color() == comment for r in below)


def test_the_screen_always_shows_what_a_full_repaint_shows(qtbot, editor):
    editor.setPlainText(PROGRAM)
    editor.bookmarks.toggle_bookmark(line=12)
    editor.goto_line(10)
    QApplication.processEvents()
    doc = editor.document()

    def replace(first: int, last: int, text: str) -> None:  # characters of block 9, block 9 + 1
        cursor = QTextCursor(doc)
        cursor.setPosition(doc.findBlockByNumber(9).position() + first)
        cursor.setPosition(doc.findBlockByNumber(10).position() + last, QTextCursor.MoveMode.KeepAnchor)
        cursor.insertText(text)

    steps = [
        lambda: qtbot.keyClicks(editor, "abc"),
        lambda: qtbot.keyClick(editor, Qt.Key.Key_Backspace),
        lambda: qtbot.keyClick(editor, Qt.Key.Key_End),
        lambda: qtbot.keyClicks(editor, " /* open"),
        lambda: qtbot.keyClick(editor, Qt.Key.Key_Down),
        lambda: qtbot.keyClicks(editor, "x */ y"),
        lambda: qtbot.keyClick(editor, Qt.Key.Key_Return),
        lambda: qtbot.keyClicks(editor, "POSA"),
        lambda: qtbot.keyClick(editor, Qt.Key.Key_Up),
        lambda: qtbot.keyClick(editor, Qt.Key.Key_Delete),
        lambda: replace(2, 3, "Q\n"),  # a line break removed and one typed: the line count stays
        lambda: replace(1, 1, "ZZ\nYY"),
        lambda: qtbot.keyClicks(editor, "#define A 1 \\"),
        lambda: qtbot.keyClick(editor, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier),
        lambda: qtbot.keyClick(editor, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier),
    ]
    for number, step in enumerate(steps):
        step()
        QApplication.processEvents()
        assert shown(editor) == editor.grab().toImage(), f"step {number}: stale pixels on the screen"


def test_a_jump_to_a_visible_line_repaints_both_line_numbers(qtbot, editor):
    """goto_line, Find Next, the outline and bookmarks move the caret with setTextCursor: Qt asks to repaint the
    old and the new caret line before it reports the move. The margin must still show the new caret line's
    number (and no longer the old one's) as a full repaint does."""
    editor.setPlainText(PROGRAM)
    editor.show()
    qtbot.waitExposed(editor)
    editor.goto_line(3)
    assert shown(editor) == editor.grab().toImage()
    for target in (12, 5, 20):  # all on screen
        editor.goto_line(target)
        assert shown(editor) == editor.grab().toImage(), f"line {target}: stale line numbers in the margin"
