"""What the drive-parameter dialogs share (Parameters ▸ Drive (FC 300), ui/drive_parameters.py; Parameters ▸ APC
(Unidrive SP), ui/apc_parameters.py): menu groups on the left, one table per group, a value column the user types
into. A typed value is checked at once (`parse`) and refused with the reason, never sent; a changed value is
yellow and bold until written, a refused one red; OK writes only the changed values (I22). Reads and writes run on
the dialog's link-jobs thread (ui/link_jobs.py), never on the GUI thread."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from PySide6.QtCore import Qt
from PySide6.QtGui import QBrush, QColor, QFont
from PySide6.QtWidgets import (
    QAbstractItemView,
    QDialog,
    QDialogButtonBox,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QListWidget,
    QPushButton,
    QStackedWidget,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
)

from motiontool.ui.link_jobs import LinkJobs

CHANGED, REFUSED, READ_ONLY = QColor("#fff3b0"), QColor("#ffc8c8"), QColor("#ececec")


@dataclass
class Row:
    p: Any                        # the parameter: has .label, .name, .read_only
    item: QTableWidgetItem        # its value cell
    current: int | None = None    # the drive's value as last read
    pending: int | None = None    # a checked new value, not yet written
    refused: str | None = None


class ParameterPages(QDialog):
    """The groups, tables and feedback; a subclass gives `shown`, `parse` and the reading and writing."""

    VALUE = 2   # the value column

    def __init__(self, parent) -> None:
        super().__init__(parent)
        self.jobs = LinkJobs(self)
        self.rows: dict[Any, Row] = {}
        self._loading = False
        self.groups, self.pages, self.tables = QListWidget(), QStackedWidget(), {}
        self.groups.currentRowChanged.connect(self.pages.setCurrentIndex)
        self.refresh = QPushButton("Refresh")
        self.refresh.clicked.connect(lambda: self.read())
        self.message = QLabel("")
        self.message.setWordWrap(True)
        self.buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        self.buttons.accepted.connect(self.accept)
        self.buttons.rejected.connect(self.reject)
        self.ok = self.buttons.button(QDialogButtonBox.StandardButton.Ok)

    # --- for the subclass --------------------------------------------------------------------------------------
    def shown(self, p, raw: int) -> str:
        raise NotImplementedError

    def parse(self, row: Row) -> int:
        """The raw value of the row's typed text; ValueError with the reason."""
        raise NotImplementedError

    def read(self) -> None:
        """Ask the controller for every value (off the GUI thread: `self.jobs`)."""
        raise NotImplementedError

    def add_group(self, title: str, key, columns, parameters, cells, tooltip) -> QTableWidget:
        """A group page: one row per parameter, `cells(p)` its texts (the value column empty until read)."""
        self.groups.addItem(title)
        table = QTableWidget(len(parameters), len(columns))
        table.setHorizontalHeaderLabels(columns)
        table.verticalHeader().setVisible(False)
        table.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectItems)
        table.setEditTriggers(QAbstractItemView.EditTrigger.DoubleClicked | QAbstractItemView.EditTrigger.EditKeyPressed
                              | QAbstractItemView.EditTrigger.AnyKeyPressed)
        for r, (row_key, p) in enumerate(parameters):
            for c, text in enumerate(cells(p)):
                item = QTableWidgetItem(text)
                if c != self.VALUE or p.read_only:
                    item.setFlags(item.flags() & ~Qt.ItemFlag.ItemIsEditable)
                if p.read_only:
                    item.setBackground(QBrush(READ_ONLY))
                item.setData(Qt.ItemDataRole.UserRole, row_key)
                item.setToolTip(tooltip(p))
                table.setItem(r, c, item)
            self.rows[row_key] = Row(p, table.item(r, self.VALUE))
        header = table.horizontalHeader()   # the columns follow the values read later; the name takes the rest
        for c in range(len(columns)):
            header.setSectionResizeMode(c, QHeaderView.ResizeMode.Stretch if c == 1
                                        else QHeaderView.ResizeMode.ResizeToContents)
        table.verticalHeader().setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        table.itemChanged.connect(self._edited)
        self.tables[key] = table
        self.pages.addWidget(table)
        return table

    def lay_out(self, top: QHBoxLayout, width: int, height: int) -> None:
        """The subclass's top row above the groups and their pages, the feedback and OK/Cancel; then the values
        are read."""
        middle = QHBoxLayout()
        middle.addWidget(self.groups)
        middle.addWidget(self.pages, 1)
        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addLayout(middle, 1)
        layout.addWidget(self.message)
        layout.addWidget(self.buttons)
        self.resize(width, height)
        self.groups.setCurrentRow(0)
        self.read()

    def recheck_others(self, row: Row) -> None:
        """Values whose range depends on `row` (none unless the subclass says)."""

    # --- values ------------------------------------------------------------------------------------------------
    def _loaded(self, cid: int, result) -> None:
        self._busy(None)
        if isinstance(result, Exception):
            self.say(f"Controller {cid}: {result}", error=True)
            return
        self._loading = True
        for key, raw in result.items():
            row = self.rows[key]
            row.current = raw
            if row.pending == raw:
                row.pending = None
            if row.pending is None and row.refused is None:
                row.item.setText(self.shown(row.p, raw))
            self._mark(row)
        self._loading = False
        self._summary()

    def pending(self) -> dict[str, int]:
        return {row.p.label: row.pending for row in self.rows.values() if row.pending is not None}

    def refused(self) -> list[str]:
        return [row.refused for row in self.rows.values() if row.refused]

    def set_pending(self, key, raw: int) -> None:
        """A value from elsewhere (a restored file): shown and marked as if typed."""
        row = self.rows[key]
        self._loading = True
        row.item.setText(self.shown(row.p, raw))
        self._loading = False
        row.refused = None
        row.pending = None if raw == row.current else raw
        self._mark(row)

    # --- editing and feedback ----------------------------------------------------------------------------------
    def _edited(self, item: QTableWidgetItem) -> None:
        if self._loading or item.column() != self.VALUE:
            return
        row = self.rows[item.data(Qt.ItemDataRole.UserRole)]
        self._check(row)
        self.recheck_others(row)
        if row.refused:
            self.say(f"Refused: {row.refused}", error=True)
        else:
            self._summary()

    def _check(self, row: Row) -> None:
        try:
            raw = self.parse(row)
        except ValueError as exc:
            row.pending, row.refused = None, str(exc)
        else:
            row.refused = None
            row.pending = None if raw == row.current else raw
        self._mark(row)

    def _mark(self, row: Row) -> None:
        was, self._loading = self._loading, True   # a style change is an itemChanged too
        if row.refused:
            row.item.setBackground(QBrush(REFUSED))
        elif row.pending is not None:
            row.item.setBackground(QBrush(CHANGED))
        else:
            row.item.setBackground(QBrush(READ_ONLY) if row.p.read_only else QBrush())
        font = QFont(row.item.font())
        font.setBold(row.pending is not None)
        row.item.setFont(font)
        self._loading = was

    def _summary(self) -> None:
        changed = len(self.pending())
        self.say(f"{changed} changed value(s): OK writes them" if changed else "")

    def busy_widgets(self) -> list:
        return [self.ok, self.refresh]

    def _busy(self, text: str | None) -> None:
        for widget in self.busy_widgets():
            widget.setEnabled(text is None)
        if text is not None:
            self.say(text)

    def say(self, text: str, *, error: bool = False) -> None:
        self.message.setText(text)
        self.message.setStyleSheet("color: #a00000;" if error else "")
