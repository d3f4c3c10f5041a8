"""Velocity, acceleration and jerk over the curve profile [DG L3811, L3892].

Each quantity has its own view box (so its scale does not squash the others), its own right-hand axis in its
colour and a legend entry with its unit, whether one or all three are shown. The view boxes only draw: they
lie over the profile's view box and hand every mouse event on to it, so dragging a fix point and drag-zoom
work while an overlay is shown (they took the drags before, issue 16)."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt

from motiontool.cameditor.ui.drawing import ScreenCurve

# colours of the manual [DG L3890-3938]
BLUE, DARK_BLUE = (30, 80, 230), (0, 0, 130)
MAGENTA, DARK_MAGENTA = (220, 0, 220), (120, 0, 120)
CYAN = (0, 190, 210)
# name, legend label, unit, colour, limit line colour (None: no limit)
QUANTITIES = (("velocity", "Velocity", "UU/MU", BLUE, DARK_BLUE),
              ("acceleration", "Acceleration", "UU/MU²", MAGENTA, DARK_MAGENTA),
              ("jerk", "Jerk", "UU/MU³", CYAN, None))
FIRST_COLUMN = 3  # PlotItem's layout: left axis 0, view box 1, its own right axis 2


class PassiveViewBox(pg.ViewBox):
    """A view box that draws and never takes the mouse: events go on to the items below it."""

    def __init__(self) -> None:
        super().__init__(enableMenu=False)
        self.setMouseEnabled(False, False)
        self.disableAutoRange()  # x follows the main view, y is SideScales.fit's: no repaint of it all on new data

    def mouseDragEvent(self, ev, axis=None) -> None:  # noqa: N802 - pyqtgraph override
        ev.ignore()

    def mouseClickEvent(self, ev) -> None:  # noqa: N802 - pyqtgraph override
        ev.ignore()

    def wheelEvent(self, ev, axis=None) -> None:  # noqa: N802 - pyqtgraph override
        ev.ignore()

    def hoverEvent(self, ev) -> None:  # noqa: N802 - pyqtgraph override
        pass


class SideScales:
    """The quantities' view boxes, curve items, limit lines, axes and the diagram's legend."""

    def __init__(self, plot: pg.PlotItem, main_box: pg.ViewBox, profile_item) -> None:
        self.plot = plot
        self.main_box = main_box
        self.boxes: dict[str, pg.ViewBox] = {}
        self.items: dict[str, ScreenCurve] = {}
        self.limit_lines: dict[str, list[pg.InfiniteLine]] = {}
        self.axes: dict[str, pg.AxisItem] = {}
        self.labels = {name: f"{title} [{unit}]" for name, title, unit, _c, _l in QUANTITIES}
        plot.hideAxis("right")
        for column, (name, title, unit, colour, limit_colour) in enumerate(QUANTITIES, start=FIRST_COLUMN):
            box = PassiveViewBox()
            box.setXLink(main_box)
            plot.scene().addItem(box)
            box.setZValue(-5)
            self.boxes[name] = box
            self.items[name] = ScreenCurve(pen=pg.mkPen(colour, width=1.5))
            box.addItem(self.items[name])
            if limit_colour is not None:
                self.limit_lines[name] = [pg.InfiniteLine(angle=0, movable=False, pen=pg.mkPen(
                    limit_colour, width=1.5, style=Qt.PenStyle.DashLine)) for _ in range(2)]
                for line in self.limit_lines[name]:
                    box.addItem(line)
            axis = pg.AxisItem("right")
            axis.enableAutoSIPrefix(False)
            axis.setStyle(maxTickLevel=1)
            axis.setPen(pg.mkPen(colour))
            axis.setTextPen(pg.mkPen(colour))
            axis.setLabel(title, units=unit, color=pg.mkColor(colour).name())
            axis.linkToView(box)
            axis.setZValue(1)
            axis.hide()
            axis.setProperty("column", column)
            self.axes[name] = axis
        self.legend = pg.LegendItem(offset=(70, 8), brush=pg.mkBrush(255, 255, 255, 210),
                                    pen=pg.mkPen(170, 170, 170))
        self.legend.setParentItem(main_box)
        self.legend.addItem(profile_item, "Slave position [UU]")
        self._in_legend: list[str] = []
        self.shown: list[str] | None = None
        main_box.sigResized.connect(self.sync)

    def sync(self) -> None:
        for box in self.boxes.values():
            box.setGeometry(self.main_box.sceneBoundingRect())
            box.linkedViewChanged(self.main_box, box.XAxis)

    def show(self, shown: list[str], limits: dict[str, bool]) -> None:
        """Show the quantities `shown` with their axes and legend entries; a limit shown alone (Vel. Limit
        without Velocity) keeps its view box and axis, so its lines have a scale."""
        self.shown = list(shown)
        for name, box in self.boxes.items():
            on = name in shown or limits.get(name, False)
            box.setVisible(on)
            axis = self.axes[name]
            if on and not axis.isVisible():
                self.plot.layout.addItem(axis, 2, axis.property("column"))
                axis.show()
            elif not on and axis.isVisible():
                self.plot.layout.removeItem(axis)
                axis.hide()
        for name in self._in_legend:
            self.legend.removeItem(self.items[name])
        self._in_legend = [name for name, *_ in QUANTITIES if name in shown]
        for name in self._in_legend:
            self.legend.addItem(self.items[name], self.labels[name])
        self.sync()

    def fit(self, layers: dict, limits: dict[str, float | None]) -> None:
        """Scale each quantity's view box to its curve (`layers[item]`) and its limit lines (± limit)."""
        for name, box in self.boxes.items():
            data = layers.get(self.items[name])
            values = list(data[np.isfinite(data)]) if data is not None and len(data) else []
            limit = limits.get(name)
            if limit:
                values += [limit, -limit]
            if values:
                lo, hi = min(values), max(values)
                span = hi - lo or max(abs(hi), 1e-9)
                box.setYRange(lo - 0.08 * span, hi + 0.08 * span, padding=0)

    def visible_axes(self) -> dict[str, pg.AxisItem]:
        return {name: axis for name, axis in self.axes.items() if axis.isVisible()}

    def legend_entries(self) -> list[str]:
        return [label.text for _sample, label in self.legend.items]
