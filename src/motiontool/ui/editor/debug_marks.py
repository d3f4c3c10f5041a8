"""What the program editor shows while debugging (ide-spec 3.1-3.9): a blue dot before every executable
statement, red dots for breakpoints, the next statement to run in yellow, variable values on click.

Breakpoints live on the text blocks (like bookmarks) so they move with the lines when the program is edited
between debug runs; they are kept after End Debug (DG L3390-3392).  The editor knows nothing about the
controller: the debug session gives it the executable lines and a `variable_value` callback. A part of the
CodeEditor, ``editor.debug``, which declares the signals breakpointsChanged and variableEditRequested.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING

from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QColor, QTextBlock, QTextBlockUserData, QTextCursor, QTextFormat
from PySide6.QtWidgets import QApplication, QLabel, QTextEdit, QToolTip, QWidget

if TYPE_CHECKING:
    from motiontool.ui.editor.code_editor import CodeEditor

MAX_BREAKPOINTS = 10  # DG L3414, L3430
DOT_BLUE, DOT_RED, NEXT_STATEMENT = "#2a6fdb", "#d62828", "#fff36b"
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\s*\[\s*\d+\s*\])?")
AWAY_PX = 12  # the value popup closes when the mouse is this far from where it was clicked


class ValuePopup(QLabel):
    """The yellow value popup of a left click on a variable (DG L3440-3444): it stays after the button is
    released, until the mouse moves away (a QToolTip closed on the release). It sits above the clicked line,
    so the line below stays readable, and goes when the focus moves anywhere (a dialog, another window): a
    tool-tip window would otherwise float over the dialog."""

    def __init__(self, parent: QWidget) -> None:
        super().__init__(parent, Qt.WindowType.ToolTip)
        self.setStyleSheet("background: #ffffc0; color: black; border: 1px solid #8a8a5c; padding: 2px 5px;")
        self.anchor = QPoint()
        QApplication.instance().focusChanged.connect(self._focus_changed)

    def show_at(self, global_pos: QPoint, text: str, *, line_top: int | None = None) -> None:
        """At the click, its bottom on the top of the clicked line (`line_top`, global); below the line only
        where there is no room above it on the screen."""
        self.setText(text)
        self.adjustSize()
        self.anchor = QPoint(global_pos)
        top = (global_pos.y() if line_top is None else line_top) - self.height() - 1
        screen = QApplication.screenAt(global_pos)
        if screen is not None and top < screen.availableGeometry().top():
            top = global_pos.y() + 14
        self.move(global_pos.x() + 10, top)
        self.show()

    def _focus_changed(self, _old, _new) -> None:
        if self.isVisible():
            self.hide()

    def mouse_moved(self, global_pos: QPoint) -> None:
        if self.isVisible() and (global_pos - self.anchor).manhattanLength() > AWAY_PX:
            self.hide()


class BlockData(QTextBlockUserData):
    """Per-line data that moves with the line as text is edited."""

    def __init__(self) -> None:
        super().__init__()
        self.bookmark = False
        self.breakpoint = False


def block_data(block: QTextBlock, create: bool = False) -> BlockData | None:
    data = block.userData()
    if not isinstance(data, BlockData) and create:
        data = BlockData()
        block.setUserData(data)
    return data if isinstance(data, BlockData) else None


class DebugMarks:
    """The debug marks of one CodeEditor; it reaches the editor only through ``self.editor``."""

    def __init__(self, editor: CodeEditor) -> None:
        self.editor = editor
        self.debug_lines: frozenset[int] = frozenset()  # 1-based executable lines of the debug build; empty = none
        self.debug_current: int | None = None           # 1-based line of the next statement to run
        self.variable_value: Callable[[str], str | None] | None = None
        self.value_popup: ValuePopup | None = None

    # --- state -----------------------------------------------------------------------------------------
    @property
    def debugging(self) -> bool:
        return bool(self.debug_lines)

    def set_debug_lines(self, lines: Iterable[int]) -> None:
        """Prepare Singlestep: blue dots on these lines; the buffer becomes read-only (decision in
        docs/decisions.md: editing during a debug session would put the IDE out of step with the controller)."""
        self.debug_lines = frozenset(lines)
        self.editor.setReadOnly(True)
        self._debug_changed()

    def end_debug(self) -> None:
        """End Debug: remove the blue dots and the yellow line; breakpoints stay."""
        if self.value_popup is not None:
            self.value_popup.hide()
        self.debug_lines = frozenset()
        self.debug_current = None
        self.variable_value = None
        self.editor.setReadOnly(False)
        self._debug_changed()

    def set_debug_current(self, line: int | None) -> None:
        if line != self.debug_current:
            self.debug_current = line
            if line is not None:
                self.editor.goto_line(line)
            self._debug_changed()

    def _debug_changed(self) -> None:
        self.editor.gutter.update()
        self.editor.update_extra_selections()

    # --- breakpoints -----------------------------------------------------------------------------------
    @staticmethod
    def has_breakpoint(block: QTextBlock) -> bool:
        data = block_data(block)
        return data is not None and data.breakpoint

    def breakpoints(self) -> list[int]:
        lines, block = [], self.editor.document().begin()
        while block.isValid():
            if self.has_breakpoint(block):
                lines.append(block.blockNumber() + 1)
            block = block.next()
        return lines

    def toggle_breakpoint(self, line: int) -> str | None:
        """Toggle a breakpoint on an executable line; returns why it was refused, or None."""
        if line not in self.debug_lines:
            return f"line {line} has no executable statement: breakpoints go on lines with a blue dot"
        block = self.editor.document().findBlockByNumber(line - 1)
        on = not self.has_breakpoint(block)
        if on and len(self.breakpoints()) >= MAX_BREAKPOINTS:
            return f"at most {MAX_BREAKPOINTS} breakpoints can be set"
        block_data(block, create=True).breakpoint = on
        self.editor.gutter.update()
        self.editor.breakpointsChanged.emit()
        return None

    # --- painting helpers (called by the gutter and update_extra_selections) ---------------------------
    def debug_dot(self, block: QTextBlock) -> str | None:
        """The colour of the dot in front of `block`, or None."""
        if self.has_breakpoint(block) and (not self.debugging or block.blockNumber() + 1 in self.debug_lines):
            return DOT_RED
        if block.blockNumber() + 1 in self.debug_lines:
            return DOT_BLUE
        return None

    def debug_selection(self) -> QTextEdit.ExtraSelection | None:
        if self.debug_current is None:
            return None
        sel = QTextEdit.ExtraSelection()
        sel.format.setBackground(QColor(NEXT_STATEMENT))
        sel.format.setProperty(QTextFormat.Property.FullWidthSelection, True)
        sel.cursor = QTextCursor(self.editor.document().findBlockByNumber(self.debug_current - 1))
        return sel

    # --- variables (ide-spec 3.8, 3.9) -----------------------------------------------------------------
    def variable_at(self, pos: QPoint) -> str | None:
        """The variable or array element (`name` or `name[3]`) on or just after `pos`, if any."""
        cursor = self.editor.cursorForPosition(pos)
        block, col = cursor.block(), cursor.positionInBlock()
        for m in _WORD.finditer(block.text()):
            if m.start() <= col <= m.end():
                return re.sub(r"\s+", "", m.group(0))
        return None

    def show_variable_value(self, pos: QPoint) -> bool:
        """Left click while debugging: the value in a yellow popup until the mouse moves away."""
        if self.variable_value is None:
            return False
        name = self.variable_at(pos)
        value = self.variable_value(name) if name else None
        if value is None:
            return False
        if self.value_popup is None:
            self.value_popup = ValuePopup(self.editor.viewport())
        line_top = self.editor.cursorRect(self.editor.cursorForPosition(pos)).top()
        self.value_popup.show_at(self.editor.viewport().mapToGlobal(pos), f"{name} = {value}",
                                 line_top=self.editor.viewport().mapToGlobal(QPoint(0, line_top)).y())
        return True

    def debug_mouse_move(self, event) -> None:
        if self.value_popup is not None:
            self.value_popup.mouse_moved(event.globalPosition().toPoint())

    def debug_mouse_press(self, event) -> bool:
        if event.button() == Qt.MouseButton.LeftButton and self.variable_value is not None:
            self.show_variable_value(event.position().toPoint())
        return False

    def debug_double_click(self, event) -> bool:
        """Double-clicking an executable statement toggles its breakpoint (DG L3408-3418)."""
        if not self.debugging or event.button() != Qt.MouseButton.LeftButton:
            return False
        line = self.editor.cursorForPosition(event.position().toPoint()).blockNumber() + 1
        if line not in self.debug_lines:
            return False
        refused = self.toggle_breakpoint(line)
        if refused:
            view = self.editor.viewport()
            QToolTip.showText(view.mapToGlobal(event.position().toPoint()), refused, view)
        return True
