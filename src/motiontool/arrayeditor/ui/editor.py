"""The Array Editor window (ide-spec 5.5-5.30): toolbar, Array Selection Box and the list.

Expert mode as in the IDE.  Values are edited in the Value column and sent only on Write to controller.
"""

from __future__ import annotations

import time
from pathlib import Path

from PySide6.QtCore import QAbstractTableModel, QModelIndex, Qt
from PySide6.QtGui import QAction, QBrush, QColor, QFont, QKeySequence
from PySide6.QtWidgets import (
    QAbstractItemView,
    QComboBox,
    QLabel,
    QMainWindow,
    QTableView,
    QWidget,
)

from motiontool.arrayeditor.rows import ArrayList, Row, fetch_controller
from motiontool.comms.protocol import LinkError
from motiontool.fileio import reason
from motiontool.formats.zba import ZbaError, read_zba, write_zba
from motiontool.qtjobs.prompts import window_prompts


def shown_date(stamp: str) -> str:
    """The .zba file's "2009:07:27 10:52" (DG 4571) as people write dates: 2009-07-27 10:52."""
    day, _, clock = stamp.partition(" ")
    parts = day.split(":")
    return " ".join(filter(None, ("-".join(parts) if len(parts) == 3 else day, clock)))


COLUMNS = ("Name", "Array", "Index", "R/W", "Value", "Controller", "Default", "Minimum", "Maximum", "Description")
VALUE, CONTROLLER = 4, 5
GREEN, GREY, RED_BG, PENDING_BG = "#d9f2d9", "#8c8c8c", "#f6b3b3", "#fbfbe8"


def _fmt(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def parse_value(text: str) -> int | float | None:
    text = text.strip()
    if text == "":
        return None
    try:
        return int(text, 0)
    except ValueError:
        return float(text)  # ValueError for text that is no number


class ArrayTableModel(QAbstractTableModel):
    def __init__(self, data: ArrayList, parent=None) -> None:
        super().__init__(parent)
        self.data_list = data
        self.selection = "All"
        self.shown: list[int] = data.visible()

    def reload(self) -> None:
        self.beginResetModel()
        self.shown = self.data_list.visible(self.selection)
        self.endResetModel()

    def values_changed(self) -> None:
        """Values changed, rows did not: repaint without losing the selection."""
        if self.shown:
            self.dataChanged.emit(self.index(0, 0), self.index(len(self.shown) - 1, len(COLUMNS) - 1))

    def row_at(self, r: int) -> Row:
        return self.data_list.rows[self.shown[r]]

    def rowCount(self, parent: QModelIndex | None = None) -> int:  # noqa: N802 (Qt override)
        return 0 if parent is not None and parent.isValid() else len(self.shown)

    def columnCount(self, parent: QModelIndex | None = None) -> int:  # noqa: N802 (Qt override)
        return 0 if parent is not None and parent.isValid() else len(COLUMNS)

    def headerData(self, section, orientation, role=Qt.ItemDataRole.DisplayRole):  # noqa: N802 (Qt override)
        if orientation == Qt.Orientation.Horizontal and role == Qt.ItemDataRole.DisplayRole:
            return COLUMNS[section]
        return None

    def data(self, index, role=Qt.ItemDataRole.DisplayRole):
        row = self.row_at(index.row())
        r, col = row.record, index.column()
        if role in (Qt.ItemDataRole.DisplayRole, Qt.ItemDataRole.EditRole):
            if row.heading:
                return r.name if col == 0 else ""
            values = (r.name, r.kind if r.array is None else f"{r.kind} {r.array}" if r.kind != "Array"
                      else str(r.array), str(r.index), "✓" if row.writable else "", _fmt(row.pending),
                      _fmt(row.controller), _fmt(r.default), _fmt(r.minimum), _fmt(r.maximum), r.description)
            return values[col]
        if role == Qt.ItemDataRole.BackgroundRole:
            if row.heading:
                return QBrush(QColor(GREY))
            if col == VALUE and row.problem:
                return QBrush(QColor(RED_BG))
            if not row.writable:
                return QBrush(QColor(GREEN))
            if col == VALUE:
                return QBrush(QColor(PENDING_BG))
        if role == Qt.ItemDataRole.ForegroundRole and col == VALUE and row.differs:
            return QBrush(QColor("#c00000"))
        if role == Qt.ItemDataRole.ForegroundRole and row.heading:
            return QBrush(QColor("white"))
        if role == Qt.ItemDataRole.FontRole and (row.heading or (col == VALUE and row.pending is not None)):
            font = QFont()
            font.setBold(True)
            return font
        if role == Qt.ItemDataRole.ToolTipRole and col == VALUE and row.problem:
            return row.problem
        return None

    def flags(self, index):
        row = self.row_at(index.row())
        if row.heading:
            return Qt.ItemFlag.ItemIsEnabled
        flags = Qt.ItemFlag.ItemIsEnabled | Qt.ItemFlag.ItemIsSelectable
        if index.column() == VALUE and row.writable:
            flags |= Qt.ItemFlag.ItemIsEditable
        return flags

    def setData(self, index, value, role=Qt.ItemDataRole.EditRole) -> bool:  # noqa: N802 (Qt override)
        if role != Qt.ItemDataRole.EditRole or index.column() != VALUE:
            return False
        try:
            number = parse_value(str(value))
        except ValueError:
            return False
        self.data_list.set_value(self.shown[index.row()], number)
        self.dataChanged.emit(index, index)
        return True


class ArrayEditor(QMainWindow):
    def __init__(self, bridge=None, controllers=None, parent: QWidget | None = None, *, prompts=None) -> None:
        super().__init__(parent)
        self.bridge = bridge
        self._prompts = prompts   # None: the bridge's (its APOSS window's), else the Qt dialogs (issue 27 item 5)
        self.data_list = ArrayList()
        self.path: Path | None = None
        self.model = ArrayTableModel(self.data_list, self)
        self.table = QTableView()
        self.table.setModel(self.model)
        self.table.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.table.setEditTriggers(QAbstractItemView.EditTrigger.DoubleClicked
                                   | QAbstractItemView.EditTrigger.SelectedClicked
                                   | QAbstractItemView.EditTrigger.AnyKeyPressed)
        self.table.verticalHeader().hide()
        self.table.setWordWrap(False)
        self.table.verticalHeader().setDefaultSectionSize(self.table.fontMetrics().height() + 6)
        self.table.horizontalHeader().setStretchLastSection(True)
        for col, width in enumerate((150, 60, 50, 40, 80, 80, 70, 95, 95)):
            self.table.setColumnWidth(col, width)
        self.setCentralWidget(self.table)
        self.selection_box = QComboBox()
        self.selection_box.setMinimumWidth(110)
        self.selection_box.currentTextChanged.connect(self._select)
        self.actions_by_text: dict[str, QAction] = {}  # not `actions`: that is QWidget.actions()
        bar = self.addToolBar("Array Editor")
        bar.setObjectName("array-editor")
        for text, slot, keys in (("Open...", self.open_file, "Ctrl+O"), ("Save File", self.save, "Ctrl+S"),
                                 ("Save File As...", self.save_as, None), (None, None, None),
                                 ("Read from controller", self.read_controller, "F5"),
                                 ("Write to controller", self.write_controller, None), ("|", None, None),
                                 ("Set to default", self.set_to_default, None),
                                 ("Set all to default", self.set_all_to_default, None),
                                 ("Set to controller", self.set_to_controller, None),
                                 ("Set all to controller", self.set_all_to_controller, None), (None, None, None),
                                 ("Add array...", self.add_array, None), ("Delete array", self.delete_array, "Del")):
            if text is None:
                bar.addSeparator()
                continue
            if text == "|":  # the editing functions on a second row, ending with the selection box
                self.addToolBarBreak()
                bar = self.addToolBar("Array Editor functions")
                bar.setObjectName("array-editor-functions")
                continue
            action = bar.addAction(text)
            action.triggered.connect(lambda *_, s=slot: s())
            if keys:
                action.setShortcut(QKeySequence(keys))
            self.actions_by_text[text] = action
        bar.addSeparator()
        bar.addWidget(QLabel(" Array: "))
        bar.addWidget(self.selection_box)
        self.resize(1000, 600)
        self._title()

    # --- helpers ---------------------------------------------------------------------------------------
    def _title(self) -> None:
        cid = self.bridge.controller_id if self.bridge is not None and self.bridge.link is not None else None
        where = f"Controller {cid}" if cid else "no controller"
        read = f", read {shown_date(self.data_list.read_time)}" if self.data_list.read_time else ""
        name = f" — {self.path.name}" if self.path else ""
        self.setWindowTitle(f"Array Editor (Expert) — {where}{read}{name}")

    def _refresh(self) -> None:
        current = self.selection_box.currentText() or "All"
        self.selection_box.blockSignals(True)
        self.selection_box.clear()
        self.selection_box.addItems(self.data_list.selections())
        index = self.selection_box.findText(current)
        self.selection_box.setCurrentIndex(max(0, index))
        self.selection_box.blockSignals(False)
        self.model.selection = self.selection_box.currentText() or "All"
        self.model.reload()
        self._title()

    def _select(self, text: str) -> None:
        self.model.selection = text or "All"
        self.model.reload()

    def _selected_rows(self) -> list[int]:
        return sorted({self.model.shown[i.row()] for i in self.table.selectionModel().selectedRows()})

    def _link(self):
        return None if self.bridge is None else self.bridge.link

    @property
    def prompts(self):
        return window_prompts(self, self._prompts, self.bridge)

    def _error(self, text: str) -> None:
        self.prompts.warn("Array Editor", text)

    # --- toolbar ---------------------------------------------------------------------------------------
    def read_controller(self) -> bool:
        link = self._link()
        if link is None:
            self._error("No controller is connected: select one in the APOSS window first.")
            return False
        try:
            read = self.bridge.waiting(self, f"Controller {self.bridge.controller_id}: reading arrays and "
                                       "parameters …", lambda: fetch_controller(link))
        except LinkError as exc:
            self._error(f"Read from controller: {exc}")
            return False
        self.data_list.take_controller(read, now=time.strftime("%Y:%m:%d %H:%M"))
        self._refresh()
        return True

    def write_controller(self) -> bool:
        link = self._link()
        if link is None:
            self._error("No controller is connected.")
            return False
        try:   # the rows are only read there; user input waits, so nobody edits them meanwhile
            problems = self.bridge.waiting(self, f"Controller {self.bridge.controller_id}: writing arrays and "
                                           "parameters …", lambda: self.data_list.write_controller(link))
        except LinkError as exc:
            problems = [str(exc)]
        if problems:
            self._error("Not written:\n" + "\n".join(problems[:20]))
            return False
        return self.read_controller()

    def set_to_default(self) -> None:
        self.data_list.set_to_default(self._selected_rows())
        self.model.values_changed()

    def set_all_to_default(self) -> None:
        self.data_list.set_to_default(self.model.shown)
        self.model.values_changed()

    def set_to_controller(self) -> None:
        self.data_list.set_to_controller(self._selected_rows())
        self.model.values_changed()

    def set_all_to_controller(self) -> None:
        self.data_list.set_to_controller(self.model.shown)
        self.model.values_changed()

    def add_array(self, *, size: int | None = None) -> int | None:
        if size is None:
            size = self.prompts.integer("Add array", "Number of elements:", 10, 1, 100000)
            if size is None:
                return None
        k = self.data_list.add_array(size)
        self._refresh()
        return k

    def delete_array(self, *, k: int | None = None) -> bool:
        if k is None:
            rows = [self.data_list.rows[i] for i in self._selected_rows()]
            arrays = {r.record.array for r in rows if r.record.kind == "Array"}
            if len(arrays) != 1:
                self._error("Select elements of exactly one array to delete it.")
                return False
            k = arrays.pop()
        self.data_list.delete_array(k)
        self._refresh()
        return True

    def open_file(self, *, path: Path | None = None) -> bool:
        if path is None:
            path = self.prompts.open_path("Open array definition file", "", "Array definition (*.zba)")
            if path is None:
                return False
        try:
            zba = read_zba(path)
        except (ZbaError, OSError) as exc:
            self._error(f"{path}: {exc}")
            return False
        self.data_list.load_template(zba)
        self.path = path
        self._refresh()   # the table shows the template's rows while the controller's values are read
        if self._link() is not None:
            self.read_controller()
        return True

    def save(self) -> bool:
        return self.save_as(path=self.path) if self.path else self.save_as()

    def save_as(self, *, path: Path | None = None) -> bool:
        if path is None:
            path = self.prompts.save_path("Save array definition file", "arrays.zba", "Array definition (*.zba)")
            if path is None:
                return False
        try:
            zba = self.data_list.to_zba()
            write_zba(path, zba)
        except OSError as exc:  # the editor keeps its values and its file (decisions R7)
            self.prompts.warn("Array Editor", f"Cannot write {path}:\n{reason(exc)}.", critical=True,
                              detail="The values are still in the editor: save them somewhere else.")
            return False
        except ZbaError as exc:
            self._error(f"{path}: {exc}")
            return False
        self.path = path
        self.data_list.template = zba  # Save As switches into "with file" mode (DG L4515-4523)
        self._title()
        return True


def open_array_editor(bridge, *, parent=None) -> ArrayEditor:
    """Tools → Array Editor on an APOSS window's session (`bridge`, ui/bridge.py): opens in Expert mode; the
    controller is read at once (ide-spec 5.5). One per APOSS window is ui/tool_windows.py's rule."""
    editor = ArrayEditor(bridge, parent=parent)
    editor.setWindowFlag(Qt.WindowType.Window, True)
    return editor
