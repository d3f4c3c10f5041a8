"""The Watch pane and the Watch Add dialog (ide-spec 3.12-3.13, DG L2452-2477).

Entries are program variables (the cross-reference of the debug build), array elements (only the first 250
elements of an array can be watched, DG L2467), axis process data and parameters.  The Value cell of a
variable or a parameter can be edited: Enter writes the new value to the controller.  The pane does not talk
to the controller itself: a reader `(kind, key) -> value` and a writer `(kind, key, text) -> error or None`
are set by the debugger; the signal `refused(key, why)` reports a value the writer refused.  Reader and writer
are called on the pane's link-jobs thread (ui/link_jobs.py, issue 27 item 2): each entry is a request, ~60 ms at
9600 baud, and the poll every 250 ms stood the window still while it ran.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QContextMenuEvent, QKeyEvent
from PySide6.QtWidgets import (
    QAbstractItemView,
    QApplication,
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QDockWidget,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QListWidget,
    QMenu,
    QSpinBox,
    QTableWidget,
    QTableWidgetItem,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from motiontool.ui.link_jobs import LinkJobs

MAX_ARRAY_WATCH = 250
HINT_ENTRIES = 12
FORMATS = ("Decimal", "Hexadecimal", "Binary")
AXIS_PROCESS_DATA = ("APOS", "CPOS", "AVEL", "TRACKERR", "AXEND", "STAT", "MAPOS", "MAVEL", "SYNCERR", "IPOS")
PARAMETERS = ("KPROP", "KDER", "KINT", "FFVEL", "VELMAX", "POSERR", "TESTVAL")


def _apc_read_parameters() -> tuple[str, ...]:
    """The APC's read parameters by alias, in number order (the watch of a DPL program on the simulated APC)."""
    from motiontool.dpl.definitions import read_parameter_names

    return tuple(alias for _, alias in sorted(read_parameter_names().items()))


@dataclass
class WatchEntry:
    kind: str       # "variable" | "signal" | "parameter"
    key: str        # name, "name[3]", signal or parameter name
    fmt: str = "Decimal"

    @property
    def label(self) -> str:
        if self.kind == "variable":
            return self.key
        return f"Axis 1: {self.key}" + (" (parameter)" if self.kind == "parameter" else "")


def format_watch(value, fmt: str) -> str:
    if isinstance(value, int) and not isinstance(value, bool):
        if fmt == "Hexadecimal":
            return f"0x{value & 0xFFFFFFFF:08X}"
        if fmt == "Binary":
            return f"{value & 0xFFFFFFFF:032b}"
    if isinstance(value, float):
        text = f"{value:.6f}".rstrip("0")
        return text + "0" if text.endswith(".") else text
    return str(value)


class _Table(QTableWidget):
    def __init__(self, pane: WatchPane) -> None:
        super().__init__(0, 2)
        self.pane = pane
        self.setHorizontalHeaderLabels(["Name", "Value"])
        # names as wide as the longest ("Axis 1: TRACKERR (parameter)" was cut at 100 px), values take the rest
        self.horizontalHeader().setSectionResizeMode(0, QHeaderView.ResizeMode.ResizeToContents)
        self.horizontalHeader().setStretchLastSection(True)
        self.verticalHeader().hide()
        self.verticalHeader().setDefaultSectionSize(self.fontMetrics().height() + 6)
        self.setMinimumSize(320, self.fontMetrics().height() * 7)  # a docked pane keeps room for a few rows
        self.setEditTriggers(QAbstractItemView.EditTrigger.DoubleClicked | QAbstractItemView.EditTrigger.EditKeyPressed
                             | QAbstractItemView.EditTrigger.AnyKeyPressed)
        self.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)

    def contextMenuEvent(self, event: QContextMenuEvent) -> None:  # noqa: N802 (Qt override)
        """Copy value, Remove (the row under the pointer), Clear all, Watch Add (DG L2456 has only Delete)."""
        row = self.rowAt(event.pos().y()) if event.reason() == QContextMenuEvent.Reason.Mouse else self.currentRow()
        if row >= 0:
            self.selectRow(row)
        menu = QMenu(self)
        copy = menu.addAction("Copy value", lambda: QApplication.clipboard().setText(self.item(row, 1).text()))
        remove = menu.addAction("Remove", lambda: self.pane.remove(row))
        copy.setEnabled(row >= 0)
        remove.setEnabled(row >= 0)
        menu.addAction("Clear all", self.pane.clear).setEnabled(bool(self.pane.entries))
        menu.addSeparator()
        menu.addAction("Watch Add...", self.pane.show_add_dialog)
        menu.exec(event.globalPos())

    def keyPressEvent(self, event: QKeyEvent) -> None:  # noqa: N802 (Qt override)
        if event.key() == Qt.Key.Key_Delete and self.currentRow() >= 0:  # DG L2456: Delete removes the entry
            self.pane.remove(self.currentRow())
            return
        super().keyPressEvent(event)


class WatchPane(QDockWidget):
    refused = Signal(str, str)    # (key, why): a typed value the controller or the check refused

    def __init__(self, parent=None) -> None:
        super().__init__("Watch", parent)
        self.setObjectName("watch")
        self.entries: list[WatchEntry] = []
        self.variables: list[str] = []
        self.arrays: list[tuple[str, int]] = []
        self.controller_kind = "MCO"   # "APC" when the window runs a DPL program on the simulated APC
        self._reader: Callable[[str, str], object] | None = None
        self._writer: Callable[[str, str, str], str | None] | None = None
        self._filling = False
        self.jobs = LinkJobs(self)
        self._polling = False     # a poll is on the link-jobs thread: the next waits for it (a slow line)
        self._again = False       # asked meanwhile (a value was written): poll once more when it is done
        self._notes: dict[int, str] = {}    # a refused value's reason, by entry, for the next poll's text
        self._tips: dict[int, str] = {}     # a write's answer for the tooltip of a cell being edited meanwhile
        body = QWidget()
        layout = QVBoxLayout(body)
        layout.setContentsMargins(2, 2, 2, 2)
        self.table = _Table(self)
        self.hint = QLabel("Many entries are watched: the Oscilloscope shows them better (Tools → Oscilloscope).")
        self.hint.setWordWrap(True)
        self.hint.hide()
        layout.addWidget(self.table)
        layout.addWidget(self.hint)
        self.setWidget(body)
        self.table.itemChanged.connect(self._value_edited)
        self.hide()

    def set_reader(self, reader: Callable[[str, str], object]) -> None:
        self._reader = reader

    def set_writer(self, writer: Callable[[str, str, str], str | None]) -> None:
        self._writer = writer

    def _value_edited(self, item: QTableWidgetItem) -> None:
        """A value typed into a Value cell goes to the controller; a refusal shows in the cell's tooltip."""
        if self._filling or item.column() != 1 or self._writer is None:
            return
        entry, text, writer = self.entries[item.row()], item.text().strip(), self._writer
        self.jobs.run(lambda: writer(entry.kind, entry.key, text), lambda refused: self._written(entry, refused))

    def _written(self, entry: WatchEntry, refused) -> None:
        refused = str(refused) if isinstance(refused, Exception) else refused
        row = next((r for r, e in enumerate(self.entries) if e is entry), None)
        if row is not None:
            self._tips[id(entry)] = refused or ""
            self._set_tip(row, entry)
            if refused:   # shown beside the controller's value once it has been read again
                self._notes[id(entry)] = refused
        if refused:
            self.refused.emit(entry.key, refused)
        self.refresh()

    def _editing(self, row: int) -> bool:
        return self.table.state() == QAbstractItemView.State.EditingState and self.table.currentRow() == row

    def _set_tip(self, row: int, entry: WatchEntry) -> None:
        """Any change to a cell resets its open editor to the cell's value, and the user's typing was lost:
        a cell being edited gets its tooltip when the editor has closed."""
        if id(entry) in self._tips and not self._editing(row):
            self._filling = True
            self.table.item(row, 1).setToolTip(self._tips.pop(id(entry)))
            self._filling = False

    def set_variables(self, variables: list[str], arrays: list[tuple[str, int]]) -> None:
        self.variables, self.arrays = list(variables), list(arrays)

    def add(self, entry: WatchEntry) -> None:
        if any(e.kind == entry.kind and e.key.upper() == entry.key.upper() for e in self.entries):
            return
        self.entries.append(entry)
        row = self.table.rowCount()
        self._filling = True
        self.table.insertRow(row)
        name = QTableWidgetItem(entry.label)
        name.setFlags(name.flags() & ~Qt.ItemFlag.ItemIsEditable)
        value = QTableWidgetItem("")
        if entry.kind == "signal":  # process data is read by the controller, not set
            value.setFlags(value.flags() & ~Qt.ItemFlag.ItemIsEditable)
        else:
            value.setToolTip("Double-click, type a value, Enter: written to the controller")
        self.table.setItem(row, 0, name)
        self.table.setItem(row, 1, value)
        self._filling = False
        self.hint.setVisible(len(self.entries) > HINT_ENTRIES)
        self.show()

    def remove(self, row: int) -> None:
        self._notes.pop(id(self.entries[row]), None)
        self._tips.pop(id(self.entries[row]), None)
        del self.entries[row]
        self.table.removeRow(row)
        self.hint.setVisible(len(self.entries) > HINT_ENTRIES)

    def clear(self) -> None:
        self._notes.clear()
        self._tips.clear()
        self.entries.clear()
        self.table.setRowCount(0)
        self.hint.hide()

    def values(self) -> list[str]:
        return [self.table.item(r, 1).text() for r in range(self.table.rowCount())]

    def refresh(self) -> None:
        """Read every entry on the link-jobs thread; the values are shown when all have arrived."""
        if self._reader is None or not self.entries:
            return
        if self._polling:
            self._again = True
            return
        self._polling = True
        entries, reader = list(self.entries), self._reader
        self.jobs.run(lambda: [_read(reader, entry) for entry in entries], lambda values: self._show(entries, values))

    def _show(self, entries: list[WatchEntry], values) -> None:
        self._polling = False
        if isinstance(values, Exception):      # the job itself failed: every row says why
            values = [values] * len(entries)
        rows = {id(entry): row for row, entry in enumerate(self.entries)}   # entries removed meanwhile are gone
        self._filling = True
        try:
            for entry, value in zip(entries, values, strict=True):
                row = rows.get(id(entry))
                if row is None:
                    continue
                if self._editing(row):
                    continue  # the user is typing a new value here
                self._set_tip(row, entry)
                text = f"? {value}" if isinstance(value, Exception) else format_watch(value, entry.fmt)
                note = self._notes.pop(id(entry), None)
                self.table.item(row, 1).setText(f"{text}  ({note})" if note else text)
        finally:
            self._filling = False
        if self._again:
            self._again = False
            self.refresh()

    def show_add_dialog(self) -> None:
        WatchAddDialog(self).exec()


def _read(reader: Callable[[str, str], object], entry: WatchEntry) -> object:
    try:
        return reader(entry.kind, entry.key)
    except Exception as exc:  # noqa: BLE001 - a failed read shows in its row, the others go on
        return exc


class WatchAddDialog(QDialog):
    """Left: the program's variables and arrays; right: system objects; a display format; Add."""

    def __init__(self, pane: WatchPane) -> None:
        super().__init__(pane.parentWidget())
        self.pane = pane
        self.setWindowTitle("Watch Add")
        self.program = QListWidget()
        self.program.setSelectionMode(QAbstractItemView.SelectionMode.ExtendedSelection)
        for name in pane.variables:
            self.program.addItem(name)
        for name, size in pane.arrays:
            self.program.addItem(f"{name}[{size}]")
        self.system = QTreeWidget()
        self.system.setHeaderHidden(True)
        self.system.setSelectionMode(QAbstractItemView.SelectionMode.ExtendedSelection)
        groups = ((("APC read parameters", _apc_read_parameters(), "signal"),) if pane.controller_kind == "APC"
                  else (("0x2500 Axis 1 Process Data", AXIS_PROCESS_DATA, "signal"),
                        ("Axis 1 Parameters", PARAMETERS, "parameter")))
        for title, names, kind in groups:
            top = QTreeWidgetItem([title])
            for name in names:
                item = QTreeWidgetItem([name])
                item.setData(0, Qt.ItemDataRole.UserRole, kind)
                top.addChild(item)
            self.system.addTopLevelItem(top)
            top.setExpanded(True)
        self.index = QSpinBox()
        self.index.setRange(1, 1)
        self.index.setEnabled(False)
        self.format = QComboBox()
        self.format.addItems(FORMATS)
        lists = QHBoxLayout()
        lists.addWidget(self.program)
        lists.addWidget(self.system)
        options = QHBoxLayout()
        options.addWidget(QLabel("Array index"))
        options.addWidget(self.index)
        options.addWidget(QLabel("Format"))
        options.addWidget(self.format)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Close)
        self.add_button = buttons.addButton("Add", QDialogButtonBox.ButtonRole.ActionRole)
        self.add_button.clicked.connect(self.add_selected)
        buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addLayout(lists)
        layout.addLayout(options)
        layout.addWidget(buttons)
        self.program.currentRowChanged.connect(self._program_row)
        self.program.itemDoubleClicked.connect(lambda item: self._add_program([self.program.row(item)]))
        self.system.itemDoubleClicked.connect(lambda item, _col: self._add_system([item]))

    def _program_row(self, row: int) -> None:
        array = row - len(self.pane.variables)
        is_array = 0 <= array < len(self.pane.arrays)
        self.index.setEnabled(is_array)
        if is_array:  # DG L2467: only the first 250 elements of an array can be watched; DPL counts from 0
            first = 0 if self.pane.controller_kind == "APC" else 1
            self.index.setRange(first, min(self.pane.arrays[array][1], MAX_ARRAY_WATCH) - 1 + first)

    def add_selected(self) -> None:
        """Add: everything selected on both sides, e.g. a variable and a parameter together (DG L2458)."""
        self._add_program(sorted(self.program.row(item) for item in self.program.selectedItems()))
        self._add_system(self.system.selectedItems())

    def _add_system(self, items: list[QTreeWidgetItem]) -> None:
        fmt = self.format.currentText()
        for item in items:
            if item is not None and item.parent() is not None:
                self.pane.add(WatchEntry(item.data(0, Qt.ItemDataRole.UserRole), item.text(0), fmt))

    def _add_program(self, rows: list[int]) -> None:
        fmt = self.format.currentText()
        for row in rows:
            if row < len(self.pane.variables):
                self.pane.add(WatchEntry("variable", self.pane.variables[row], fmt))
            else:
                name = self.pane.arrays[row - len(self.pane.variables)][0]
                self.pane.add(WatchEntry("variable", f"{name}[{self.index.value()}]", fmt))
