"""Add Curve ▸ Browse…: the signals the connected controller can record (its `list_signals` answer), by group,
filtered as the user types; a double click or OK takes one into Add Curve (issue 23 item 8). The list is asked
for on a thread of its own, so the dialog opens at once and fills in when the answer arrives (a slow line)."""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QLabel,
    QLineEdit,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
)

from motiontool.comms.client import SignalInfo
from motiontool.scope.ui.poll_job import PollJob

Fetch = Callable[[], list[SignalInfo]]


class SignalBrowser(QDialog):
    def __init__(self, fetch: Fetch | None, parent=None):
        super().__init__(parent)
        self.setWindowTitle("Signals of the controller")
        self.filter = QLineEdit()
        self.filter.setPlaceholderText("Filter: part of a name or a description (e.g. pos, 32-6, KPROP)")
        self.filter.setClearButtonEnabled(True)
        self.filter.textChanged.connect(self._apply_filter)
        self.tree = QTreeWidget()
        self.tree.setHeaderLabels(["Signal", "Description"])
        self.tree.setColumnWidth(0, 180)
        self.tree.itemDoubleClicked.connect(lambda item, _col: self._take(item))
        self.tree.currentItemChanged.connect(lambda *_: self._update_ok())
        self.status = QLabel()
        self.buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        self.buttons.accepted.connect(lambda: self._take(self.tree.currentItem()))
        self.buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        for widget in (self.filter, self.tree, self.status, self.buttons):
            layout.addWidget(widget)
        self.resize(560, 480)
        self.choice: str | None = None
        self.total = 0           # signals listed (0 until the answer came)
        self._update_ok()
        if fetch is None:
            self.status.setText("Not connected: connect to a controller to browse the signals it can record.")
        else:
            self.status.setText("Reading the controller's signals …")
            PollJob(self, "signal-list").run(fetch, self._fill)

    def _fill(self, result) -> None:
        if isinstance(result, Exception):
            self.status.setText(f"The controller did not list its signals: {result}")
            return
        groups: dict[str, QTreeWidgetItem] = {}
        for signal in result:
            group = groups.get(signal.group)
            if group is None:
                group = groups[signal.group] = QTreeWidgetItem(self.tree, [signal.group])
                group.setFlags(group.flags() & ~Qt.ItemFlag.ItemIsSelectable)
            item = QTreeWidgetItem(group, [signal.name, signal.text])
            item.setToolTip(1, signal.text)
        if groups:
            next(iter(groups.values())).setExpanded(True)
        self.total = len(result)
        self._apply_filter(self.filter.text())

    def _apply_filter(self, text: str) -> None:
        words = text.lower().split()
        found = 0
        for g in range(self.tree.topLevelItemCount()):
            group = self.tree.topLevelItem(g)
            shown = 0
            for k in range(group.childCount()):
                item = group.child(k)
                hay = f"{item.text(0)} {item.text(1)}".lower()
                hidden = not all(w in hay for w in words)
                item.setHidden(hidden)
                shown += not hidden
            group.setHidden(shown == 0)
            found += shown
            group.setExpanded(bool(words) and shown > 0 or group.isExpanded() and not words)
        if self.total:
            count = f"{found} of {self.total} signals" if words else f"{self.total} signals"
            self.status.setText(f"{count}; type to filter, double-click to take one")
        self._update_ok()

    def _update_ok(self) -> None:
        item = self.tree.currentItem()
        self.buttons.button(QDialogButtonBox.StandardButton.Ok).setEnabled(
            item is not None and item.parent() is not None and not item.isHidden())

    def _take(self, item: QTreeWidgetItem | None) -> None:
        if item is None or item.parent() is None:     # a group: nothing to take
            return
        self.choice = item.text(0)
        self.accept()
