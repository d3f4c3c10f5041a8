"""The left margin of the CodeEditor: line numbers, bookmark triangles, error/warning marks.

A click in the margin selects the whole line; dragging selects several lines (ide-spec 1.11).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from PySide6.QtCore import QPoint, QPointF, QRect, QSize, Qt
from PySide6.QtGui import QColor, QFont, QMouseEvent, QPainter, QPaintEvent, QPen, QPolygonF, QTextCursor
from PySide6.QtWidgets import QWidget

if TYPE_CHECKING:
    from motiontool.ui.editor.code_editor import CodeEditor

MARK_WIDTH = 14  # the column of bookmark and diagnostic marks, left of the numbers


class LineNumberArea(QWidget):
    def __init__(self, editor: CodeEditor) -> None:
        super().__init__(editor)
        self.editor = editor
        self._anchor_block: int | None = None
        self.setCursor(Qt.CursorShape.ArrowCursor)
        self.setAttribute(Qt.WidgetAttribute.WA_OpaquePaintEvent)  # paintEvent fills its area: no parent paint

    def area_width(self) -> int:
        digits = len(str(max(1, self.editor.blockCount())))
        return MARK_WIDTH + 6 + self.editor.fontMetrics().horizontalAdvance("9") * max(3, digits) + 8

    def sizeHint(self) -> QSize:  # noqa: N802 (Qt override)
        return QSize(self.area_width(), 0)

    # --- painting --------------------------------------------------------------------------------------
    def paintEvent(self, event: QPaintEvent) -> None:  # noqa: N802 (Qt override)
        editor = self.editor
        colors = editor.settings.colors
        painter = QPainter(self)
        area = event.rect()
        painter.fillRect(area, QColor(colors.gutter))
        painter.setPen(QColor("#e3e3e3"))
        painter.drawLine(self.width() - 1, area.top(), self.width() - 1, area.bottom())
        marks = editor.diagnostic_marks()
        current = editor.textCursor().blockNumber()
        line_h = editor.fontMetrics().height()
        number_right = self.width() - 6
        align = int(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
        plain_pen, current_pen = QColor(colors.gutter_text), QColor(colors.text)
        font = painter.font()
        bold = QFont(font)
        bold.setBold(True)
        painter.setPen(plain_pen)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        block = editor.firstVisibleBlock()
        top = editor.blockBoundingGeometry(block).translated(editor.contentOffset()).top()
        step = editor.blockBoundingRect(block).height()
        if step > 0 and area.top() - top > step:  # no line wrap: equal heights, jump to the first line to paint
            skip = int((area.top() - top) // step)
            target = editor.document().findBlockByNumber(block.blockNumber() + skip)
            if target.isValid():
                block, top = target, top + skip * step
        bottom_limit = area.bottom()
        while block.isValid() and top <= bottom_limit:
            height = editor.blockBoundingRect(block).height()
            if block.isVisible() and top + height >= area.top():
                number = block.blockNumber()
                y = int(top)
                if number == current:
                    painter.setFont(bold)
                    painter.setPen(current_pen)
                painter.drawText(QRect(0, y, number_right, line_h), align, str(number + 1))
                if number == current:
                    painter.setFont(font)
                    painter.setPen(plain_pen)
                severity = marks.get(number)
                if severity is not None:  # a square or triangle, never a dot: dots are the debugger's
                    mark = self._error_mark if severity == "error" else self._warning_mark
                    mark(painter, y, line_h, QColor(getattr(colors, severity)))
                    painter.setPen(plain_pen)
                if editor.bookmarks.has_bookmark(block):
                    self._bookmark_mark(painter, y, line_h, QColor(colors.bookmark))
                    painter.setPen(plain_pen)
                dot = editor.debug.debug_dot(block)
                if dot is not None:  # blue: executable statement, red: breakpoint (ide-spec 3.1, 3.5)
                    self._dot(painter, y, line_h, QColor(dot))
                    painter.setPen(plain_pen)
            top += height
            block = block.next()
        painter.end()

    @staticmethod
    def _bookmark_mark(painter: QPainter, top: int, height: int, color: QColor) -> None:
        """The manual's blue triangle in the left margin [DG L2306]."""
        mid = top + height / 2
        half = min(5.0, height / 2 - 1)
        painter.setPen(color.darker(130))
        painter.setBrush(color)
        painter.drawPolygon(QPolygonF([QPointF(3, mid - half), QPointF(3, mid + half), QPointF(3 + 1.6 * half, mid)]))

    @staticmethod
    def _dot(painter: QPainter, top: int, height: int, color: QColor) -> None:
        """The debugger's dots: blue before an executable statement, red on a breakpoint (DG L3364-3418)."""
        size = min(9, height - 4)
        painter.setPen(color.darker(120))
        painter.setBrush(color)
        painter.drawEllipse(QRect(MARK_WIDTH - size + 1, top + (height - size) // 2, size, size))

    @staticmethod
    def _error_mark(painter: QPainter, top: int, height: int, color: QColor) -> None:
        """A syntax error: a square with a white cross, so it is not taken for a breakpoint's red dot."""
        size = min(10, height - 3)
        box = QRect(MARK_WIDTH - size + 1, top + (height - size) // 2, size, size)
        painter.setPen(color.darker(130))
        painter.setBrush(color)
        painter.drawRect(box)
        painter.setPen(QPen(QColor("white"), 1.6))
        inset = box.adjusted(3, 3, -2, -2)
        painter.drawLine(inset.topLeft(), inset.bottomRight())
        painter.drawLine(inset.bottomLeft(), inset.topRight())

    @staticmethod
    def _warning_mark(painter: QPainter, top: int, height: int, color: QColor) -> None:
        """A warning: a triangle with an exclamation mark."""
        size = min(11, height - 2)
        left, bottom = MARK_WIDTH - size + 1, top + (height + size) // 2
        painter.setPen(color.darker(140))
        painter.setBrush(color)
        painter.drawPolygon(QPolygonF([QPointF(left, bottom), QPointF(left + size, bottom),
                                       QPointF(left + size / 2, bottom - size)]))
        painter.setPen(QPen(QColor("black"), 1.4))
        middle = left + size / 2
        painter.drawLine(QPointF(middle, bottom - size + 4), QPointF(middle, bottom - 4))
        painter.drawPoint(QPointF(middle, bottom - 2))

    # --- line selection with the mouse -----------------------------------------------------------------
    def _block_at(self, y: int) -> int:
        """The block number at height `y` (the margin and the viewport share their y coordinates)."""
        return self.editor.cursorForPosition(QPoint(0, y)).blockNumber()

    def _select_blocks(self, first: int, last: int) -> None:
        doc = self.editor.document()
        lo, hi = sorted((first, last))
        cursor = QTextCursor(doc.findBlockByNumber(lo))
        end_block = doc.findBlockByNumber(hi)
        if end_block.next().isValid():
            cursor.setPosition(end_block.next().position(), QTextCursor.MoveMode.KeepAnchor)
        else:
            cursor.setPosition(end_block.position() + end_block.length() - 1, QTextCursor.MoveMode.KeepAnchor)
        if last < first:  # dragging upwards: caret at the top
            anchor, pos = cursor.position(), cursor.anchor()
            cursor.setPosition(anchor)
            cursor.setPosition(pos, QTextCursor.MoveMode.KeepAnchor)
        self.editor.setTextCursor(cursor)

    def mousePressEvent(self, event: QMouseEvent) -> None:  # noqa: N802 (Qt override)
        if event.button() == Qt.MouseButton.LeftButton:
            self._anchor_block = self._block_at(int(event.position().y()))
            self._select_blocks(self._anchor_block, self._anchor_block)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:  # noqa: N802 (Qt override)
        if self._anchor_block is not None and event.buttons() & Qt.MouseButton.LeftButton:
            self._select_blocks(self._anchor_block, self._block_at(int(event.position().y())))

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:  # noqa: N802 (Qt override)
        self._anchor_block = None
        self.editor.setFocus()
