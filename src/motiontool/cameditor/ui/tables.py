"""Fix Points and Start-Stop Points tables [DG L3960-4070, ide-spec 4.29-4.33, 4.76].

The tables never change a curve themselves: an edit becomes a request signal, the editor applies it through the
model (cameditor.editing) and shows the result, or the model's error, and the table is refreshed from the curve.
"""

from __future__ import annotations

from PySide6.QtCore import QAbstractTableModel, QEvent, QModelIndex, Qt, Signal
from PySide6.QtGui import QBrush, QColor, QKeySequence
from PySide6.QtWidgets import (
    QAbstractItemView,
    QComboBox,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QPushButton,
    QStyledItemDelegate,
    QTableView,
    QVBoxLayout,
    QWidget,
)

from motiontool.camcurve.model import FIX_POINT_TYPES, LAW_TYPES, Curve
from motiontool.camcurve.motionlaws import LAWS

TANGENT_ROW = QColor(225, 245, 225)
_ROOT = QModelIndex()


def _fmt(value: float) -> str:
    return f"{value:g}" if float(value).is_integer() else f"{value:.6g}"


class FixPointModel(QAbstractTableModel):
    HEADERS = ("Point", "Master", "Slave", "Type")
    edit_requested = Signal(int, str, object)  # row, "master" | "slave" | "type", new value

    def __init__(self) -> None:
        super().__init__()
        self.curve: Curve | None = None

    def set_curve(self, curve: Curve | None) -> None:
        self.beginResetModel()
        self.curve = curve
        self.endResetModel()

    def update_row(self, row: int, curve: Curve) -> None:
        """A drag moved one point: refresh that row only (keeps the selection); not the Point column, which does
        not change."""
        self.curve = curve
        for column in (1, 2, 3):  # cell by cell: a view repaints one changed cell, but all rows for a range
            self.dataChanged.emit(self.index(row, column), self.index(row, column))

    def rowCount(self, parent=_ROOT) -> int:  # noqa: N802 - Qt override
        return 0 if self.curve is None or parent.isValid() else len(self.curve.fix_points)

    def columnCount(self, parent=_ROOT) -> int:  # noqa: N802 - Qt override
        return len(self.HEADERS)

    def headerData(self, section, orientation, role=Qt.ItemDataRole.DisplayRole):  # noqa: N802 - Qt override
        if orientation == Qt.Orientation.Horizontal and role == Qt.ItemDataRole.DisplayRole:
            return self.HEADERS[section]
        return None

    def data(self, index: QModelIndex, role=Qt.ItemDataRole.DisplayRole):
        if self.curve is None or not index.isValid():
            return None
        p = self.curve.fix_points[index.row()]
        col = index.column()
        if role in (Qt.ItemDataRole.DisplayRole, Qt.ItemDataRole.EditRole):
            return (str(index.row() + 1), _fmt(p.master), _fmt(p.slave), p.type)[col]
        if role == Qt.ItemDataRole.TextAlignmentRole:
            return int(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter) if col in (1, 2) else \
                int(Qt.AlignmentFlag.AlignCenter)
        if role == Qt.ItemDataRole.BackgroundRole and p.type == "T":
            return QBrush(TANGENT_ROW)
        if role == Qt.ItemDataRole.ForegroundRole and col == 3:
            return QBrush(QColor(0, 120, 0) if p.type == "T" else QColor(180, 20, 20))
        if role == Qt.ItemDataRole.ToolTipRole and col == 3 and p.type in LAW_TYPES:  # decision C10
            return f"{LAWS[p.type].name} (VDI 2143) from the previous point to this one"
        return None

    def flags(self, index: QModelIndex):
        base = Qt.ItemFlag.ItemIsEnabled | Qt.ItemFlag.ItemIsSelectable
        if index.column() in (1, 2, 3) and not (index.column() == 1 and index.row() == 0):
            base |= Qt.ItemFlag.ItemIsEditable  # the first point stays at master 0
        return base

    def setData(self, index: QModelIndex, value, role=Qt.ItemDataRole.EditRole) -> bool:  # noqa: N802
        if role != Qt.ItemDataRole.EditRole or not index.isValid():
            return False
        self.edit_requested.emit(index.row(), ("", "master", "slave", "type")[index.column()], value)
        return True


class TypeDelegate(QStyledItemDelegate):
    """Double-click on the Type cell: choose C, T, CZ or C3; the choice is applied at once [DG L3986]."""

    def createEditor(self, parent, option, index):  # noqa: N802 - Qt override
        combo = QComboBox(parent)
        combo.addItems(FIX_POINT_TYPES)
        combo.activated.connect(lambda _i, *, c=combo: (self.commitData.emit(c), self.closeEditor.emit(c)))
        return combo

    def setEditorData(self, editor, index) -> None:  # noqa: N802 - Qt override
        editor.setCurrentText(index.data(Qt.ItemDataRole.EditRole))
        editor.showPopup()

    def setModelData(self, editor, model, index) -> None:  # noqa: N802 - Qt override
        if editor.currentText() != index.data(Qt.ItemDataRole.EditRole):
            model.setData(index, editor.currentText())


class _Table(QTableView):
    delete_requested = Signal(int)
    restyled = Signal()  # a new font or style: what was measured must be measured again

    def changeEvent(self, event) -> None:  # noqa: N802 - Qt override
        super().changeEvent(event)
        if event.type() in (QEvent.Type.FontChange, QEvent.Type.StyleChange):
            self.restyled.emit()

    def keyPressEvent(self, event) -> None:  # noqa: N802 - Qt override
        if event.matches(QKeySequence.StandardKey.Delete) or event.key() == Qt.Key.Key_Delete:
            rows = self.selectionModel().selectedRows() if self.selectionModel() else []
            if rows:
                self.delete_requested.emit(rows[0].row())
                return
        super().keyPressEvent(event)


def _table_box(title: str, table: QTableView, add: QPushButton) -> QWidget:
    box = QWidget()
    layout = QVBoxLayout(box)
    layout.setContentsMargins(0, 0, 0, 0)
    layout.setSpacing(2)
    head = QHBoxLayout()
    label = QLabel(f"<b>{title}</b>")
    head.addWidget(label)
    head.addStretch(1)
    head.addWidget(add)
    layout.addLayout(head)
    layout.addWidget(table)
    return box


class FixPointTable(QWidget):
    add_clicked = Signal()

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.model = FixPointModel()
        self.view = _Table()
        self.view.setModel(self.model)
        self.view.setItemDelegateForColumn(3, TypeDelegate(self.view))
        self.view.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.view.setSelectionMode(QAbstractItemView.SelectionMode.SingleSelection)
        self.view.setEditTriggers(QAbstractItemView.EditTrigger.DoubleClicked)
        self.view.verticalHeader().hide()
        self.view.verticalHeader().setDefaultSectionSize(20)
        self.view.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
        # the Point column fits its largest number, measured on the last row: Qt's ResizeToContents asks a
        # thousand rows for their text after every reset (~80 ms for a 10 000-point curve)
        self.view.horizontalHeader().setSectionResizeMode(0, QHeaderView.ResizeMode.Fixed)
        self.model.modelReset.connect(self._fit_point_column)
        self.view.restyled.connect(self._fit_point_column)
        self.view.setAlternatingRowColors(False)
        self.add_button = QPushButton("Add...")
        self.add_button.clicked.connect(self.add_clicked)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(_table_box("Fix Points", self.view, self.add_button))

    def _fit_point_column(self) -> None:
        rows = self.model.rowCount()
        number = self.view.sizeHintForIndex(self.model.index(rows - 1, 0)).width() + self.view.showGrid() if rows \
            else 0  # (the grid line as QTableView.sizeHintForColumn counts it)
        self.view.setColumnWidth(0, max(number, self.view.horizontalHeader().sectionSizeHint(0)))

    def highlight(self, row: int) -> None:
        """Hover in the diagram highlights the point's row [DG L3640]."""
        if row >= 0:
            self.view.selectRow(row)
            self.view.scrollTo(self.model.index(row, 0))

    def selected_row(self) -> int:
        rows = self.view.selectionModel().selectedRows()
        return rows[0].row() if rows else -1


class PairModel(QAbstractTableModel):
    """Start/stop pairs 1.. (pair 0, the hidden Start = Stop pair, is not listed) [DG L1508-1511]."""

    HEADERS = ("Point", "Start", "Stop")

    def __init__(self) -> None:
        super().__init__()
        self.curve: Curve | None = None

    def set_curve(self, curve: Curve | None) -> None:
        self.beginResetModel()
        self.curve = curve
        self.endResetModel()

    def rowCount(self, parent=_ROOT) -> int:  # noqa: N802 - Qt override
        return 0 if self.curve is None or parent.isValid() else max(0, len(self.curve.start_stop_pairs) - 1)

    def columnCount(self, parent=_ROOT) -> int:  # noqa: N802 - Qt override
        return 3

    def headerData(self, section, orientation, role=Qt.ItemDataRole.DisplayRole):  # noqa: N802 - Qt override
        if orientation == Qt.Orientation.Horizontal and role == Qt.ItemDataRole.DisplayRole:
            return self.HEADERS[section]
        return None

    def data(self, index: QModelIndex, role=Qt.ItemDataRole.DisplayRole):
        if self.curve is None or not index.isValid():
            return None
        pair = self.curve.start_stop_pairs[index.row() + 1]
        if role == Qt.ItemDataRole.DisplayRole:
            return (str(index.row() + 1), _fmt(pair.start), _fmt(pair.stop))[index.column()]
        if role == Qt.ItemDataRole.TextAlignmentRole:
            return int(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter) if index.column() else \
                int(Qt.AlignmentFlag.AlignCenter)
        return None


class StartStopTable(QWidget):
    add_clicked = Signal()
    edit_requested = Signal(int)  # pair number
    pair_selected = Signal(object)  # pair number or None

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.model = PairModel()
        self.view = _Table()
        self.view.setModel(self.model)
        self.view.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.view.setSelectionMode(QAbstractItemView.SelectionMode.SingleSelection)
        self.view.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        self.view.verticalHeader().hide()
        self.view.verticalHeader().setDefaultSectionSize(20)
        self.view.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
        self.view.horizontalHeader().setSectionResizeMode(0, QHeaderView.ResizeMode.ResizeToContents)
        self.view.doubleClicked.connect(lambda index: self.edit_requested.emit(index.row() + 1))
        self.add_button = QPushButton("Add...")
        self.add_button.clicked.connect(self.add_clicked)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(_table_box("Start Stop Points", self.view, self.add_button))
        self._connect_selection()

    def _connect_selection(self) -> None:
        self.view.selectionModel().selectionChanged.connect(lambda *_: self.pair_selected.emit(self.selected_pair()))

    def set_curve(self, curve: Curve | None) -> None:
        keep = self.selected_pair()
        self.model.set_curve(curve)
        if keep is not None and curve is not None and keep < len(curve.start_stop_pairs):
            self.select_pair(keep)

    def selected_pair(self) -> int | None:
        rows = self.view.selectionModel().selectedRows()
        return rows[0].row() + 1 if rows else None

    def select_pair(self, k: int) -> None:
        self.view.selectRow(k - 1)
