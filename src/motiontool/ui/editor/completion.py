"""The completion list of the CodeEditor: a model of names with hints and a delegate that draws the hints.

Each row shows the name, and in grey on the right its hint: the syntax of a command ("POSA p"), the number
and description of a parameter, or the kind of a program symbol.
"""

from __future__ import annotations

from PySide6.QtCore import QModelIndex, QPersistentModelIndex, QSize, Qt
from PySide6.QtGui import QColor, QPalette, QStandardItem, QStandardItemModel
from PySide6.QtWidgets import QStyle, QStyledItemDelegate, QStyleOptionViewItem

from motiontool.ui.editor.lang import CompletionItem

HINT_ROLE = Qt.ItemDataRole.UserRole + 1
KIND_ROLE = Qt.ItemDataRole.UserRole + 2
_HINT_GAP = 24
_MAX_HINT_CHARS = 60


class CompletionModel(QStandardItemModel):
    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self._key: tuple[str, ...] = ()

    def set_items(self, items: list[CompletionItem]) -> bool:
        """Replace the rows; skipped (returns False) when the names did not change."""
        key = tuple(f"{i.name}\0{i.kind}" for i in items)
        if key == self._key:
            return False
        self._key = key
        self.clear()
        root = self.invisibleRootItem()
        rows = []
        for item in items:
            row = QStandardItem(item.name)
            hint = item.hint if len(item.hint) <= _MAX_HINT_CHARS else item.hint[: _MAX_HINT_CHARS - 1] + "…"
            row.setData(hint if hint != item.name else "", HINT_ROLE)
            row.setData(item.kind, KIND_ROLE)
            if item.help:
                row.setToolTip(item.help)
            row.setEditable(False)
            rows.append(row)
        root.appendRows(rows)
        return True

    def names(self) -> list[str]:
        return [self.item(r).text() for r in range(self.rowCount())]


class HintDelegate(QStyledItemDelegate):
    """Draws the row's name as usual and its hint right of it in a dimmer colour."""

    def paint(self, painter, option: QStyleOptionViewItem, index: QModelIndex | QPersistentModelIndex) -> None:
        super().paint(painter, option, index)
        hint = index.data(HINT_ROLE)
        if not hint:
            return
        painter.save()
        selected = bool(option.state & QStyle.StateFlag.State_Selected)
        color = option.palette.color(QPalette.ColorRole.HighlightedText) if selected else QColor("#7a7a7a")
        painter.setPen(color)
        name_width = option.fontMetrics.horizontalAdvance(str(index.data()))
        rect = option.rect.adjusted(name_width + _HINT_GAP, 0, -6, 0)
        text = option.fontMetrics.elidedText(hint, Qt.TextElideMode.ElideRight, rect.width())
        painter.drawText(rect, int(Qt.AlignmentFlag.AlignVCenter | Qt.AlignmentFlag.AlignRight), text)
        painter.restore()

    def sizeHint(self, option: QStyleOptionViewItem, index: QModelIndex | QPersistentModelIndex) -> QSize:  # noqa: N802
        size = super().sizeHint(option, index)
        hint = index.data(HINT_ROLE)
        if hint:
            size.setWidth(size.width() + _HINT_GAP + option.fontMetrics.horizontalAdvance(hint) + 6)
        return size
