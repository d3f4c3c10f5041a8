"""The chart and navigation panes (DG 4728-4819): pyqtgraph plots fed with min/max-decimated data.

Every curve has its own Y range (Axis tab, DG 5180-5225), so the main view works in normalised units 0..1
and each curve is mapped into them through its (shared) range; the left and right axes show the scales of
the curves that own those sides (Grid column, DG 4878-4912). Only what fits the pixels is handed to Qt:
per pixel column the first minimum and maximum, so peaks survive and 8 × 10 k points draw in a few ms.
"""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QPointF, Qt, Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import QSplitter, QVBoxLayout, QWidget

from motiontool.scope.buffer import MinMaxPyramid, decimate_minmax, visible_slice
from motiontool.scope.curves import Curve, Scope
from motiontool.scope.numbers import decimals_for, grouped, time_ticks, time_unit

PYRAMID_MIN = 200_000   # samples from which a curve's min/max pyramid is cached for browsing
AXIS_WIDTH = 78         # fixed: a new, longer tick label must not make the chart jump (PlotJuggler #1380)
CURSOR_GRAB_PX = 6      # a right-drag this near a cursor moves it


class ScaledAxis(pg.AxisItem):
    """An axis that shows a curve's units for the normalised view: value = low + v · (high − low)."""

    def __init__(self, orientation: str):
        self._norm = (0.0, 1.0)
        self.mapping = (0.0, 1.0)  # set before the base class calls setRange
        self._look = None          # (label, colour, show values) last applied
        super().__init__(orientation)

    def set_mapping(self, low: float, high: float, *, label: str = "", colour: str | None = None,
                    show_values: bool = True) -> None:
        """Called on every live frame: only what changed is applied, since a new label, pen or style makes
        pyqtgraph lay the axis out again (profiled: most of a live frame's axis cost, benchmarks/scope_stream)."""
        look = (label, colour, show_values)
        if look != self._look:
            self._look = look
            self.setLabel(label, color=colour) if label else self.setLabel("")
            if colour:
                self.setTextPen(pg.mkPen(colour))
            self.setStyle(showValues=show_values)
        if (low, high) != self.mapping:
            self.mapping = (low, high)
            self.setRange(*self._norm)

    def setRange(self, mn: float, mx: float):  # noqa: N802 - pyqtgraph override
        self._norm = (mn, mx)
        lo, hi = self.mapping
        super().setRange(lo + mn * (hi - lo), lo + mx * (hi - lo))

    def tickStrings(self, values, scale, spacing):  # noqa: N802 - pyqtgraph override
        # pyqtgraph writes 1.3244e+06 for large values; grouped digits read at a glance (issue 23 item 8)
        places = decimals_for(spacing * scale)
        return [grouped(v * scale, places) for v in values]


class TimeAxis(pg.AxisItem):
    """The time axis: milliseconds in the view, labelled in s from a visible span of 2 s on, else in ms, never
    in scientific notation. `relative` says whether 0 is the recording's start (Shift to 0) or the controller's
    power-up."""

    def __init__(self, *, titled: bool = True) -> None:
        self.titled = titled   # the navigation pane has no room for a title
        self.unit = ""         # set before the base class calls setRange
        self.relative = True
        super().__init__("bottom")
        self.enableAutoSIPrefix(False)
        self.unit = ""
        self._retitle()

    def _retitle(self) -> None:
        span = abs(self.range[1] - self.range[0])
        unit = time_unit(span)
        if unit != self.unit:
            self.unit = unit
            if not self.titled:
                return
            what = "time from the recording's start" if self.relative else "controller time"
            self.setLabel(f"{what} [{unit}]")

    def set_relative(self, relative: bool) -> None:
        self.relative, self.unit = relative, ""
        self._retitle()

    def setRange(self, mn: float, mx: float):  # noqa: N802 - pyqtgraph override
        super().setRange(mn, mx)
        self._retitle()

    def tickStrings(self, values, scale, spacing):  # noqa: N802 - pyqtgraph override
        return time_ticks(list(values), spacing, self.unit)


class ChartViewBox(pg.ViewBox):
    """Left-drag zooms a rectangle, right-drag pans (DG 4743-4757); a right-drag that starts on cursor A or B
    moves that cursor (DG 4781-4787, ide-spec 6.8: "moved by right-dragging")."""

    def __init__(self) -> None:
        super().__init__()
        self.cursor_lines: list[pg.InfiniteLine] = []   # the chart's cursors A and B
        self.move_cursor = None                           # (cursor index, view x) -> None, set by the chart
        self._moving: int | None = None

    def cursor_at(self, scene_pos) -> int | None:
        """The visible cursor within CURSOR_GRAB_PX of scene_pos, if any (the nearer one)."""
        near = []
        for i, line in enumerate(self.cursor_lines):
            if line.isVisible():
                x = self.mapViewToScene(QPointF(float(line.value()), 0.0)).x()
                near.append((abs(x - scene_pos.x()), i))
        best = min(near, default=None)
        return best[1] if best is not None and best[0] <= CURSOR_GRAB_PX else None

    def mouseDragEvent(self, ev, axis=None):  # noqa: N802 - pyqtgraph override
        if ev.button() != Qt.RightButton:
            super().mouseDragEvent(ev, axis)
            return
        ev.accept()
        if ev.isStart():
            self._moving = self.cursor_at(ev.buttonDownScenePos(Qt.RightButton))
        if self._moving is not None and self.move_cursor is not None:
            self.move_cursor(self._moving, float(self.mapSceneToView(ev.scenePos()).x()))
            if ev.isFinish():
                self._moving = None
            return
        delta = self.mapToView(ev.lastPos()) - self.mapToView(ev.pos())
        self.translateBy(x=delta.x(), y=delta.y())


class Chart(QWidget):
    """Main chart above the navigation pane; `refresh()` redraws from the model."""

    x_range_changed = Signal(float, float)
    cursor_moved = Signal(int, float)           # cursor 0 = A, 1 = B; time ms
    mouse_time = Signal(float)

    def __init__(self, scope: Scope, parent=None):
        super().__init__(parent)
        self.scope = scope
        self.left_curve: str | None = None
        self.right_curve: str | None = None
        self.shift_to_zero = scope.settings.relative_origin
        self.live = False
        self.ranges: dict[str, tuple[float, float]] = {}
        self.left_axis, self.right_axis = ScaledAxis("left"), ScaledAxis("right")
        bottom = self.time_axis = TimeAxis()
        bottom.set_relative(self.shift_to_zero)
        self.plot = pg.PlotWidget(viewBox=ChartViewBox(),
                                  axisItems={"left": self.left_axis, "right": self.right_axis, "bottom": bottom})
        self.plot.setBackground("w")
        self.plot.showAxis("right")
        self.left_axis.setWidth(AXIS_WIDTH)
        self.right_axis.setWidth(AXIS_WIDTH)
        self.plot.showGrid(x=True, y=True, alpha=0.25)
        # horizontal grid lines follow the left axis only: the right axis has other ticks (another curve's
        # scale), and its second set of lines cost ~1/6 of a live frame (benchmarks/scope_stream.py)
        self.right_axis.setGrid(False)
        # grid lines at major ticks only: the minor grid costs more than all curves together (benchmark)
        for axis in (self.left_axis, self.right_axis, bottom):
            axis.setStyle(maxTickLevel=0)
        self.plot.setMenuEnabled(False)
        self.plot.hideButtons()
        self.view = self.plot.getPlotItem().getViewBox()
        self.view.setMouseMode(pg.ViewBox.RectMode)   # left-drag zooms a rectangle (DG 4743-4757)
        self.view.setYRange(0, 1, padding=0.02)
        self.view.sigXRangeChanged.connect(self._x_changed)
        self.plot.scene().sigMouseMoved.connect(self._mouse_moved)
        self.items: dict[str, pg.PlotCurveItem] = {}
        self.cursors = []
        for name, colour in (("A", "#0050d0"), ("B", "#d07000")):
            line = pg.InfiniteLine(angle=90, movable=False, pen=pg.mkPen(colour, width=1.5),
                                   label=name, labelOpts={"position": 0.97, "color": colour, "fill": "#ffffffc0"})
            line.setVisible(False)
            self.plot.addItem(line, ignoreBounds=True)
            self.cursors.append(line)
        self.view.cursor_lines = self.cursors
        self.view.move_cursor = lambda i, x: self.set_cursor(i, x + self.origin())
        self.pause_lines: list[pg.InfiniteLine] = []
        self.zero_marks = pg.ScatterPlotItem(symbol="t2", size=12, pen=None)  # Axis → Display zero mark
        self.plot.addItem(self.zero_marks, ignoreBounds=True)
        # navigation: the whole recording with the visible region (DG 4789-4819)
        self.nav_time_axis = TimeAxis(titled=False)
        self.nav_time_axis.set_relative(self.shift_to_zero)
        self.nav = pg.PlotWidget(axisItems={"bottom": self.nav_time_axis})
        self.nav.setBackground("w")
        self.nav.setMenuEnabled(False)
        self.nav.hideButtons()
        self.nav.getPlotItem().hideAxis("left")
        self.nav.setMouseEnabled(x=False, y=False)
        self.nav_items: dict[str, pg.PlotCurveItem] = {}
        self.region = pg.LinearRegionItem(brush=QColor(0, 0, 0, 25), pen=pg.mkPen("k", width=1.5))
        self.region.setZValue(10)
        self.region.sigRegionChanged.connect(self._region_changed)
        self.nav.addItem(self.region, ignoreBounds=True)
        self.nav_cursors = [pg.InfiniteLine(angle=90, pen=pg.mkPen(c)) for c in ("#0050d0", "#d07000")]
        for line in self.nav_cursors:
            line.setVisible(False)
            self.nav.addItem(line, ignoreBounds=True)
        split = QSplitter(Qt.Vertical)
        split.addWidget(self.plot)
        split.addWidget(self.nav)
        split.setSizes([400, 90])
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(split)
        self._updating = False
        self._cache: dict[str, tuple] = {}
        self._nav_drawn = True

    def _display_data(self, curve: Curve):
        """(t, y, pyramid or None) as displayed, cached until the data or the display settings change."""
        key = (curve.buffer.version, id(curve.buffer), repr(curve.scaling), curve.smoothing)
        hit = self._cache.get(curve.name)
        if hit is not None and hit[0] == key:
            return hit[1]
        t, y = curve.display()
        pyramid = MinMaxPyramid(t, y) if t.size >= PYRAMID_MIN and not self.live else None
        self._cache[curve.name] = (key, (t, y, pyramid))
        return t, y, pyramid

    # --- time origin -----------------------------------------------------------------------------------------
    def set_shift(self, on: bool) -> None:
        """Shift to 0 on or off: the origin and the time axes' titles."""
        self.shift_to_zero = on
        self.time_axis.set_relative(on)
        self.nav_time_axis.set_relative(on)

    def origin(self) -> float:
        """Shift to 0 (DG 4728-4739): the first sample becomes time 0."""
        if not self.shift_to_zero:
            return 0.0
        span = self.scope.time_span()
        return span[0] if span else 0.0

    # --- ranges --------------------------------------------------------------------------------------------
    def reset_ranges(self) -> None:
        """Zoom Reset: new Y ranges from the Axis settings, whole time range."""
        self.ranges = {c.name: c.y_range() for c in self.scope.curves}
        self.view.setYRange(0, 1, padding=0.02)
        span = self.scope.time_span()
        if span:
            o = self.origin()
            lo, hi = span[0] - o, span[1] - o
            if hi - lo < 1:
                hi = lo + max(1.0, self.scope.settings.min_length_ms)
            self.view.setXRange(lo, hi, padding=0.01)

    def range_of(self, curve: Curve) -> tuple[float, float]:
        root = self.scope.shared_root(curve.name)
        if root not in self.ranges or self.live:
            self.ranges[root] = self.scope.curve(root).y_range()
        return self.ranges[root]

    # --- drawing -----------------------------------------------------------------------------------------------
    def refresh(self, *, navigation: bool = True) -> None:
        names = {c.name for c in self.scope.curves}
        for name in [n for n in self.items if n not in names]:
            self._cache.pop(name, None)
            self.plot.removeItem(self.items.pop(name))
            self.nav.removeItem(self.nav_items.pop(name))
        x0, x1 = self.view.viewRange()[0]
        width = max(int(self.view.width()), 100)
        o = self.origin()
        for curve in self.scope.curves:
            item = self.items.get(curve.name)
            if item is None:
                # PlotCurveItem, not PlotDataItem: the data is decimated here, its extra pass costs time
                item = self.items[curve.name] = pg.PlotCurveItem(skipFiniteCheck=True, antialias=False)
                self.plot.addItem(item)
                self.nav_items[curve.name] = pg.PlotCurveItem(skipFiniteCheck=True)
                self.nav.addItem(self.nav_items[curve.name])
            item.setVisible(curve.visible)
            self.nav_items[curve.name].setVisible(curve.visible and navigation)
            if not curve.visible:
                continue
            if item.opts.get("_colour") != curve.colour:
                item.setPen(pg.mkPen(curve.colour, width=1))  # 1-px lines: wider ones draw far slower
                item.opts["_colour"] = curve.colour
            t, y, pyramid = self._display_data(curve)
            lo, hi = self.range_of(curve)
            span = (hi - lo) or 1.0
            if pyramid is not None:
                tt, yy = pyramid.window(x0 + o, x1 + o, width)
            else:
                s = visible_slice(t, x0 + o, x1 + o)
                tt, yy = decimate_minmax(t[s], y[s], width)
            if curve.interpolation == "values" and tt.size > 1:
                tt, yy = np.repeat(tt, 2)[1:], np.repeat(yy, 2)[:-1]   # steps: hold until the next sample
            item.setData(tt - o, (yy - lo) / span)
            if navigation:
                nt, ny = pyramid.window(t[0], t[-1], 400) if pyramid is not None else decimate_minmax(t, y, 400)
                self.nav_items[curve.name].setData(nt - o, (ny - lo) / span, pen=pg.mkPen(curve.colour))
        marks = [c for c in self.scope.curves if c.visible and c.axis.zero_mark]
        self.zero_marks.setData([{"pos": (x0, -self.range_of(c)[0] / ((self.range_of(c)[1] - self.range_of(c)[0])
                                                                     or 1.0)),
                                  "brush": pg.mkBrush(c.colour)} for c in marks])
        if not navigation and self._nav_drawn:
            for it in self.nav_items.values():
                it.setData([], [])
        self._nav_drawn = navigation
        self.region.setVisible(navigation)
        self._update_axes()
        self._sync_region()

    def _default_sides(self) -> None:
        """Until the user picks (Grid column / selection), the first visible curve owns the left axis and the
        first one with another scale the right axis; a curve with data goes before an empty one, whose 0..1 scale
        is not what the drawn curves are read against (a TESTSETP set was, issue 23 item 8)."""
        shown = [c for c in self.scope.curves if c.visible]
        filled = [c.name for c in shown if len(c.buffer)]
        visible = filled + [c.name for c in shown if not len(c.buffer)]
        if self.left_curve not in visible or (filled and self.left_curve not in filled):
            self.left_curve = visible[0] if visible else None
        left_root = self.scope.shared_root(self.left_curve) if self.left_curve else None
        if self.right_curve not in visible or (filled and self.right_curve not in filled) or \
                self.scope.shared_root(self.right_curve) == left_root:
            self.right_curve = next((n for n in visible if self.scope.shared_root(n) != left_root), None)

    def _update_axes(self) -> None:
        self._default_sides()
        for axis, name in ((self.left_axis, self.left_curve), (self.right_axis, self.right_curve)):
            try:
                curve = self.scope.curve(name) if name else None
            except KeyError:
                curve = None
            if curve is None:  # no owner: no numbers that mean nothing
                axis.set_mapping(0.0, 1.0, show_values=False)
            else:
                lo, hi = self.range_of(curve)
                axis.set_mapping(lo, hi, label=f"{curve.name} [{curve.unit}]" if curve.unit else curve.name,
                                 colour=curve.colour)

    def set_pauses(self, times: list[float]) -> None:
        """A red vertical bar where a paused recording resumed (DG 5943)."""
        for line in self.pause_lines:
            self.plot.removeItem(line)
        o = self.origin()
        self.pause_lines = [pg.InfiniteLine(t - o, angle=90, pen=pg.mkPen("r", width=2)) for t in times]
        for line in self.pause_lines:
            self.plot.addItem(line, ignoreBounds=True)

    # --- cursors ---------------------------------------------------------------------------------------------
    def show_cursor(self, i: int, on: bool) -> None:
        line = self.cursors[i]
        if on and self.scope.cursors[i] is None:
            x0, x1 = self.view.viewRange()[0]
            self.scope.cursors[i] = x0 + (x1 - x0) * (0.33 if i == 0 else 0.66) + self.origin()
        if not on:
            self.scope.cursors[i] = None
        line.setVisible(on)
        self.nav_cursors[i].setVisible(on)
        if on:
            self.set_cursor(i, self.scope.cursors[i])

    def set_cursor(self, i: int, t: float) -> None:
        """Place cursor i at controller time t (ms)."""
        self.scope.cursors[i] = t
        self._updating = True
        self.cursors[i].setValue(t - self.origin())
        self.nav_cursors[i].setValue(t - self.origin())
        self._updating = False
        self.cursor_moved.emit(i, t)

    # --- navigation ----------------------------------------------------------------------------------------
    def _x_changed(self, *_):
        x0, x1 = self.view.viewRange()[0]
        self._sync_region()
        self.x_range_changed.emit(x0, x1)

    def _sync_region(self) -> None:
        if self._updating:
            return
        self._updating = True
        self.region.setRegion(self.view.viewRange()[0])
        self._updating = False

    def _region_changed(self) -> None:
        if self._updating:
            return
        self._updating = True
        self.view.setXRange(*self.region.getRegion(), padding=0)
        self._updating = False

    def _mouse_moved(self, pos) -> None:
        if self.plot.sceneBoundingRect().contains(pos):
            self.mouse_time.emit(float(self.view.mapSceneToView(pos).x()) + self.origin())
