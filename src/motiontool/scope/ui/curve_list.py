"""The Curve Selection List (DG 4821-5068): curves under grey group rows, with Name (show/hide + colour),
Status, Active, mouse position, Last/Min/Max, cursors A, B and B−A, Units, Controller and Interface."""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QBrush, QColor, QIcon, QPixmap
from PySide6.QtWidgets import QTreeWidget, QTreeWidgetItem

from motiontool.scope.curves import OTHER_CURVES, Curve, Scope
from motiontool.scope.measure import curve_value_at
from motiontool.scope.numbers import grouped, value_text

COLUMNS = ["Name", "Grid", "Status", "Active", "Mouse", "Last", "Minimum", "Maximum", "A", "B", "B−A", "Units",
           "Controller", "Interface"]
NAME, GRID, STATUS, ACTIVE, MOUSE, LAST, MIN, MAX, A, B, BA, UNITS, CONTROLLER, INTERFACE = range(len(COLUMNS))
# DG 4916-4944; the OCR lost the error and lost colours: red and orange (ide-spec 6.14 DECISION)
STATUS_COLOURS = {"running": "#00e000", "connected": "#006400", "unbound": "#ffffff", "error": "#e00000",
                  "lost": "#ff9900"}
GREY = QColor("#d8d8d8")
RED = QColor("#ff9090")


def _patch(colour: str) -> QIcon:
    pm = QPixmap(12, 12)
    pm.fill(QColor(colour))
    return QIcon(pm)


class CurveList(QTreeWidget):
    visibility_changed = Signal()
    curve_selected = Signal(str)
    axis_clicked = Signal(str)          # a click in the Grid column (DG 4878-4912)

    def __init__(self, scope: Scope, parent=None):
        super().__init__(parent)
        self.scope = scope
        self.setColumnCount(len(COLUMNS))
        self.setHeaderLabels(COLUMNS)
        self.setRootIsDecorated(False)
        self.setIndentation(8)
        self.setUniformRowHeights(True)
        self.controller_state = "unbound"
        self.origin = lambda: 0.0            # the chart's time origin (Shift to 0): times read as on its axis
        self.controller_name = ""
        self.interface = ""
        self._filling = False
        self._items: dict[str, QTreeWidgetItem] = {}
        self.itemChanged.connect(self._item_changed)
        self.currentItemChanged.connect(self._current_changed)
        self.itemClicked.connect(self._clicked)
        self.sides: tuple[str | None, str | None] = (None, None)   # curves owning the left / right axis
        for col, width in ((NAME, 220), (GRID, 40), (STATUS, 50), (ACTIVE, 50), (MOUSE, 80)):
            self.setColumnWidth(col, width)

    def item_for(self, name: str) -> QTreeWidgetItem | None:
        return self._items.get(name)

    def rebuild(self) -> None:
        """Rows for every curve under its group; groups in order, then Other Curves (DG 4821-4848)."""
        self._filling = True
        self.clear()
        self._items = {}
        groups = [g.name for g in self.scope.groups]
        for gname in groups + [OTHER_CURVES]:
            members = [c for c in self.scope.curves
                       if (c.source.group == gname) or (gname == OTHER_CURVES and c.source.group not in groups)]
            if gname == OTHER_CURVES and not members:
                continue
            head = QTreeWidgetItem(self, [gname])
            for col in range(len(COLUMNS)):
                head.setBackground(col, GREY)
            head.setFirstColumnSpanned(True)
            head.setFlags(Qt.ItemIsEnabled)
            for c in members:
                item = QTreeWidgetItem(head, [c.name])
                item.setData(NAME, Qt.UserRole, c.name)
                self._items[c.name] = item
                item.setFlags(Qt.ItemIsEnabled | Qt.ItemIsSelectable | Qt.ItemIsUserCheckable)
                item.setCheckState(NAME, Qt.Checked if c.visible else Qt.Unchecked)
                item.setIcon(NAME, _patch(c.colour))
                if c.first_of_set:
                    item.setBackground(NAME, GREY)
                if c.source.controller is not None and c.source.method not in ("testsetp", "derived", "file"):
                    item.setCheckState(ACTIVE, Qt.Checked if c.active else Qt.Unchecked)
                item.setText(UNITS, c.unit)
            head.setExpanded(True)
        self._filling = False
        self.update_values()

    def update_values(self, *, mouse_t: float | None = None) -> None:
        """Last/Min/Max, mouse and cursor columns; out-of-range values red (DG 5131-5141)."""
        ta, tb = self.scope.cursors
        o = self.origin()
        self.headerItem().setText(A, "A" if ta is None else f"A {grouped(ta - o)}ms")
        self.headerItem().setText(B, "B" if tb is None else f"B {grouped(tb - o)}ms")
        self.headerItem().setText(MOUSE, "Mouse" if mouse_t is None else f"{grouped(mouse_t - o)}ms")
        self._filling = True
        for c in self.scope.curves:
            item = self.item_for(c.name)
            if item is None:
                continue
            st = c.stats()
            for col, value in zip((LAST, MIN, MAX), st or (None, None, None), strict=True):
                self._cell(item, col, c, value)
            va = curve_value_at(c, ta) if ta is not None else None
            vb = curve_value_at(c, tb) if tb is not None else None
            self._cell(item, A, c, va, interpolated=True)
            self._cell(item, B, c, vb, interpolated=True)
            self._cell(item, BA, c, None if va is None or vb is None else vb - va, interpolated=True, check=False)
            self._cell(item, MOUSE, c, curve_value_at(c, mouse_t) if mouse_t is not None else None,
                       interpolated=True)
            bound = c.source.controller is not None and c.source.method not in ("derived", "file")
            if bound:
                item.setBackground(STATUS, QBrush(QColor(STATUS_COLOURS[self.controller_state])))
                item.setText(CONTROLLER, f"{c.source.controller} {self.controller_name}".strip())
                item.setText(INTERFACE, self.interface)
            else:
                item.setBackground(STATUS, QBrush())
                item.setText(CONTROLLER, "")
                item.setText(INTERFACE, "")
            root = self.scope.shared_root(c.name)
            left, right = self.sides
            grid = "L" if c.name == left else "R" if c.name == right else ""
            if not grid and c.axis.share is not None:
                grid = "↑L" if root == left else "↑R" if root == right else "↑"   # sharing (grey arrow)
            item.setText(GRID, grid)
            if "error" in c.source.info:
                item.setToolTip(NAME, c.source.info["error"])
        self._filling = False

    def _cell(self, item, col, curve: Curve, value, *, interpolated=False, check=True) -> None:
        if value is None:
            item.setText(col, "")
            item.setBackground(col, QBrush())
            return
        text = value_text(value) if interpolated and curve.interpolation != "values" else curve.format_value(value)
        item.setText(col, text)
        item.setBackground(col, QBrush(RED) if check and curve.out_of_range(value) else QBrush())

    def _item_changed(self, item: QTreeWidgetItem, col: int) -> None:
        if self._filling:
            return
        name = item.data(NAME, Qt.UserRole)
        if name is None:
            return
        curve = self.scope.curve(name)
        if col == NAME:
            curve.visible = item.checkState(NAME) == Qt.Checked
            self.visibility_changed.emit()
        elif col == ACTIVE:
            curve.active = item.checkState(ACTIVE) == Qt.Checked

    def _clicked(self, item: QTreeWidgetItem, col: int) -> None:
        name = item.data(NAME, Qt.UserRole)
        if name and col == GRID:
            self.axis_clicked.emit(name)

    def _current_changed(self, current, _previous) -> None:
        if current is not None and current.data(NAME, Qt.UserRole):
            self.curve_selected.emit(current.data(NAME, Qt.UserRole))
