"""The curve profile diagram [DG L3587-3682, ide-spec 4.20-4.28, 4.58-4.74] with pyqtgraph.

Left axis: slave position (UU); bottom: master (MU); right: one axis for each of velocity, acceleration and jerk
that is shown, in its colour, with a legend (side_scales.py: each has its own view box so their scales do not
squash each other).  Mouse: hover identifies
a fix point (hand cursor), left-drag on a point moves it, left-drag elsewhere zooms to a rectangle (Ctrl keeps
the aspect ratio), right-drag pans, right-click opens the popup, double-click adds a point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QPointF, QRectF, Qt, Signal
from PySide6.QtWidgets import QGraphicsItem

from motiontool.camcurve.model import Curve
from motiontool.camcurve.spline import disengage_path, engage_path, profile
from motiontool.cameditor.ui.drawing import Markers, ScreenCurve, show_one, thin
from motiontool.cameditor.ui.side_scales import DARK_BLUE, SideScales

# colours of the manual [DG L3599-3600, L3890-3938]
RED, GREEN = (210, 30, 30), (0, 150, 0)
GREY, BLUE_GREY = (130, 130, 130), (96, 125, 139)
YELLOW, PALE_GREEN = (230, 190, 0), (170, 230, 170, 110)
SAMPLES = 1600  # diagram resolution over one cycle (plus every fix point)
MARKER_SIZE = 9
PATH_SAMPLES = 120


@dataclass
class Overlay:
    """What the window knows beyond the curve: display options and derived marker positions."""

    velocity: bool = False
    velocity_limit: bool = False
    acceleration: bool = False
    acceleration_limit: bool = False
    jerk: bool = False
    slave_stop: bool = False
    start_stop: bool = False
    engage: bool = False
    disengage: bool = False
    master_marker: bool = False
    slave_marker: bool = False
    correction: bool = False
    selected_pair: int | None = None
    velocity_limit_value: float = 0.0
    acceleration_limit_value: float = 0.0
    master_marker_at: float = 0.0
    master_tolerance: float = 0.0
    slave_marker_at: float = 0.0
    slave_tolerance: float = 0.0


class CurveViewBox(pg.ViewBox):
    """The main view box: hit-tests fix points in pixels and turns mouse gestures into editor signals."""

    point_hovered = Signal(int)  # fix point index, -1 = none
    point_dragged = Signal(int, float, float, bool)  # index, master, slave, finished
    double_clicked = Signal(float, float)
    context_requested = Signal(int, float, float, object)  # point index or -1, master, slave, QPoint (screen)
    user_zoomed = Signal()  # a manual zoom or pan: clears Auto Scale [DG L3614, L3624]

    def __init__(self) -> None:
        super().__init__(enableMenu=False)
        self.points = np.zeros((0, 2))
        self.accuracy = 4
        self.hovered = -1
        self._dragging: int | None = None
        self.setMouseMode(pg.ViewBox.RectMode)

    @property
    def dragged_point(self) -> int | None:
        """The fix point being dragged, if any."""
        return self._dragging

    # -- hit test -------------------------------------------------------------------------------------------------
    def point_at(self, scene_pos: QPointF) -> int:
        """Index of the fix point within Mouse accuracy (pixels beyond the marker's edge) of scene_pos, or -1."""
        if not len(self.points):
            return -1
        tr = self.childGroup.sceneTransform()  # view → scene, applied to all points at once
        px = tr.m11() * self.points[:, 0] + tr.m21() * self.points[:, 1] + tr.dx()
        py = tr.m12() * self.points[:, 0] + tr.m22() * self.points[:, 1] + tr.dy()
        d = np.maximum(np.abs(px - scene_pos.x()), np.abs(py - scene_pos.y()))
        best = int(np.argmin(d))
        return best if d[best] <= MARKER_SIZE / 2 + self.accuracy else -1

    def _set_hovered(self, index: int) -> None:
        if index != self.hovered:
            self.hovered = index
            if index >= 0:
                self.setCursor(Qt.CursorShape.PointingHandCursor)
            else:
                self.unsetCursor()
            self.point_hovered.emit(index)

    # -- events ---------------------------------------------------------------------------------------------------
    def hoverEvent(self, ev) -> None:  # noqa: N802 - pyqtgraph override
        if self._dragging is not None:
            return
        if ev.isExit():
            self._set_hovered(-1)
        else:
            self._set_hovered(self.point_at(ev.scenePos()))

    def mouseDragEvent(self, ev, axis=None) -> None:  # noqa: N802 - pyqtgraph override
        ev.accept()
        view = self.mapSceneToView(ev.scenePos())
        if ev.button() == Qt.MouseButton.LeftButton:
            if ev.isStart():
                hit = self.point_at(ev.buttonDownScenePos(Qt.MouseButton.LeftButton))
                self._dragging = hit if hit >= 0 else None
            if self._dragging is not None:
                index = self._dragging
                if ev.isFinish():
                    self._dragging = None
                self.point_dragged.emit(index, view.x(), view.y(), bool(ev.isFinish()))
                return
            if ev.isFinish():
                self.rbScaleBox.hide()
                rect = QRectF(pg.Point(ev.buttonDownPos(ev.button())), pg.Point(ev.pos())).normalized()
                rect = self.childGroup.mapRectFromParent(rect)
                if ev.modifiers() & Qt.KeyboardModifier.ControlModifier:
                    rect = self._keep_aspect(rect)
                if rect.width() > 0 and rect.height() > 0:
                    self.showAxRect(rect)
                    self.user_zoomed.emit()
            else:
                self.updateScaleBox(ev.buttonDownPos(), ev.pos())
        elif ev.button() == Qt.MouseButton.RightButton:
            last = self.mapSceneToView(ev.lastScenePos())
            self.translateBy(x=last.x() - view.x(), y=last.y() - view.y())
            if ev.isStart():
                self.user_zoomed.emit()

    def _keep_aspect(self, rect: QRectF) -> QRectF:
        """Grow the rectangle so that it keeps the current view's aspect ratio (Ctrl held) [DG L3610]."""
        (x0, x1), (y0, y1) = self.viewRange()
        ratio = (x1 - x0) / (y1 - y0) if y1 != y0 else 1.0
        w, h = rect.width(), rect.height()
        if w / h > ratio:
            h = w / ratio
        else:
            w = h * ratio
        c = rect.center()
        return QRectF(c.x() - w / 2, c.y() - h / 2, w, h)

    def mouseClickEvent(self, ev) -> None:  # noqa: N802 - pyqtgraph override
        view = self.mapSceneToView(ev.scenePos())
        if ev.button() == Qt.MouseButton.RightButton:
            ev.accept()
            self.context_requested.emit(self.point_at(ev.scenePos()), view.x(), view.y(), ev.screenPos().toPoint())
        elif ev.button() == Qt.MouseButton.LeftButton and ev.double():
            ev.accept()
            if self.point_at(ev.scenePos()) < 0:
                self.double_clicked.emit(view.x(), view.y())


class CurveDiagram(pg.PlotWidget):
    """Draws one curve with its overlays; ``show_curve`` redraws everything, ``move_marker`` only the points."""

    def __init__(self, parent=None) -> None:
        self.box = CurveViewBox()
        super().__init__(parent, viewBox=self.box, background="w")
        plot = self.getPlotItem()
        plot.showGrid(x=True, y=True, alpha=0.25)
        plot.setLabel("bottom", "Master", units="MU")
        plot.setLabel("left", "Slave", units="UU")
        plot.hideButtons()
        for name in ("left", "bottom"):
            axis = plot.getAxis(name)
            axis.enableAutoSIPrefix(False)
            axis.setStyle(maxTickLevel=1)  # major and one minor level: a calmer grid, and cheaper to paint
            axis.setPen(pg.mkPen(60, 60, 60))
            axis.setTextPen(pg.mkPen(30, 30, 30))
        self.curve: Curve | None = None
        self.overlay = Overlay()
        self.box.sigResized.connect(lambda *_: self._draw())
        self.box.sigXRangeChanged.connect(lambda *_: self._draw())
        # base items
        self.red = ScreenCurve(pen=pg.mkPen(RED, width=2))
        self.green = ScreenCurve(pen=pg.mkPen(GREEN, width=2.5))
        # tangent points green, all others red [DG L3599]; one brush per item keeps 10 000 points fast
        self.points = Markers(size=MARKER_SIZE, symbol="s", pen=pg.mkPen(20, 20, 20, 200),
                                         brush=pg.mkBrush(RED))
        self.t_points = Markers(size=MARKER_SIZE, symbol="s", pen=pg.mkPen(20, 20, 20, 200),
                                           brush=pg.mkBrush(GREEN))
        self.hover = Markers(size=MARKER_SIZE + 8, symbol="s", pen=pg.mkPen(0, 0, 0, width=2),
                                        brush=None)
        # the point being dragged, drawn on its own while the others stay put (and cached as a picture)
        self.drag_marker = Markers(size=MARKER_SIZE, symbol="s", pen=pg.mkPen(20, 20, 20, 200))
        self._drag_point: int | None = None
        self.slave_stop_line = pg.InfiniteLine(angle=0, movable=False, pen=pg.mkPen(GREY, width=5))
        self.engage_item = pg.PlotDataItem(pen=pg.mkPen(DARK_BLUE, width=2))
        self.disengage_item = pg.PlotDataItem(pen=pg.mkPen(DARK_BLUE, width=2, style=Qt.PenStyle.DashLine))
        self.master_marker_line = pg.InfiniteLine(angle=90, movable=False, pen=pg.mkPen(GREEN, width=2))
        self.master_band = pg.LinearRegionItem(orientation="vertical", brush=pg.mkBrush(PALE_GREEN), movable=False,
                                               pen=pg.mkPen(None))
        self.slave_marker_line = pg.InfiniteLine(angle=0, movable=False, pen=pg.mkPen(GREEN, width=2))
        self.slave_band = pg.LinearRegionItem(orientation="horizontal", brush=pg.mkBrush(PALE_GREEN), movable=False,
                                              pen=pg.mkPen(None))
        self.correction_bars = [pg.LinearRegionItem(orientation="vertical", brush=pg.mkBrush(*BLUE_GREY, 200),
                                                    movable=False, pen=pg.mkPen(None), span=(0.0, 0.025))
                                for _ in range(2)]
        for item in (self.master_band, self.slave_band, *self.correction_bars):
            item.setZValue(-10)
        for item in (self.master_band, self.slave_band, *self.correction_bars, self.slave_stop_line,
                     self.master_marker_line, self.slave_marker_line, self.red, self.green, self.engage_item,
                     self.disengage_item, self.hover, self.points, self.t_points, self.drag_marker):
            plot.addItem(item)
        # axes with their grid, the title and the markers of up to 10 000 fix points change only with the view
        # or the points, the hover and drag markers only move: Qt keeps them as pictures, so a drag repaints
        # just the curves
        for item in (plot.getAxis("left"), plot.getAxis("bottom"), plot.titleLabel.item,
                     self.points, self.t_points, self.hover, self.drag_marker):
            item.setCacheMode(QGraphicsItem.CacheMode.DeviceCoordinateCache)
        # pyqtgraph tells the items under the mouse about every move, also while a fix point is dragged, when no
        # item may take the hover; skip that then (it asks every item for its shape on every move)
        scene, send_hover = self.scene(), self.scene().sendHoverEvents

        def send_hover_unless_dragging(ev, *, exitOnly=False):  # noqa: N803 - pyqtgraph's signature
            if exitOnly or self.box.dragged_point is None:
                send_hover(ev, exitOnly)

        scene.sendHoverEvents = send_hover_unless_dragging
        self.flags: list[pg.GraphicsObject] = []
        # velocity / acceleration / jerk: own view boxes, axes and legend [DG L3811, L3892]
        self.scales = SideScales(plot, self.box, self.red)
        self.side_items, self.limit_lines = self.scales.items, self.scales.limit_lines
        for axis in self.scales.axes.values():
            axis.setCacheMode(QGraphicsItem.CacheMode.DeviceCoordinateCache)
        # the exact samples (tables, limits and Zoom Reset use these); the items draw what the view shows of them
        self.samples_x = np.zeros(0)
        self.tangent = np.zeros(0, dtype=bool)
        self.samples_y = np.zeros(0)
        self.layers: dict[ScreenCurve, np.ndarray] = {}  # item → its y samples over samples_x (NaN: gap)
        self._drawn_for: tuple | None = None
        self._title: str | None = None  # setTitle("") keeps the title row, as for a curve
        self._flag_key: tuple | None = None

    # -- drawing ----------------------------------------------------------------------------------------------------
    def clear_curve(self) -> None:
        self.curve = None
        self.samples_x = self.samples_y = np.zeros(0)
        self.layers = {}
        self._drawn_for = None
        for item in (self.red, self.green, self.points, self.t_points, *self.side_items.values()):
            item.setData([], [])
        show_one(self.hover, None)
        show_one(self.drag_marker, None)
        self._drag_point = None
        self.box.points = np.zeros((0, 2))
        self.tangent = np.zeros(0, dtype=bool)
        self._set_title("")
        for item in (self.engage_item, self.disengage_item):
            item.setData([], [])
        self._show_overlays(None)

    def show_curve(self, curve: Curve, overlay: Overlay, *, dragging: bool = False) -> None:
        """Recompute the samples and redraw everything (the editor's "recalc").

        ``dragging``: one fix point of the shown curve moves (Continuous Recalc).  The samples are the same as
        for a full recalc; the fix point types are unchanged and the right axis keeps its scale until the
        release (no autorange while the mouse moves)."""
        same_frame = (dragging and self.curve is not None and overlay == self.overlay
                      and curve.master_length == self.curve.master_length)
        self.curve, self.overlay = curve, overlay
        prof = profile(curve)
        xs, below = samples(prof.x, curve.master_length)
        pieces = prof.pieces(xs, below)
        ys = prof.at_pieces(xs, pieces, 0)
        self.samples_x, self.samples_y = xs, ys
        green, red = self._straight_masks(prof, xs, below, prof.at_pieces(xs, pieces, 2))
        self.layers = {self.red: np.where(red, ys, np.nan), self.green: np.where(green, ys, np.nan)}
        self._set_title(f"<b>{curve.name}</b>")
        self._set_points(curve, prof, same_types=dragging)
        shown = [n for n in ("velocity", "acceleration", "jerk") if getattr(overlay, n)]
        for nu, name in enumerate(("velocity", "acceleration", "jerk"), start=1):
            if name in shown:
                self.layers[self.side_items[name]] = prof.at_pieces(xs, pieces, nu)
            elif self.side_items[name].xData is not None and len(self.side_items[name].xData):
                self.side_items[name].setData([], [])
        self._drawn_for = None
        self._draw()
        if same_frame:  # markers, limits and bars stay; the start/stop flags and paths follow the curve
            self._show_flags(curve)
            self._show_paths(curve)
        else:
            self._show_overlays(curve)
        self._right_axis(shown, fit=not dragging)

    def _set_title(self, title: str) -> None:
        if title != self._title:  # a new title lays the plot out again
            self._title = title
            self.getPlotItem().setTitle(title, color=(30, 30, 30), size="11pt")

    def _view_columns(self) -> tuple[float, float, int] | None:
        """The master range in view and its width in pixels; None while the view follows the data (auto range)."""
        if not len(self.samples_x) or self.box.autoRangeEnabled()[0]:
            return None
        (x0, x1), _ = self.box.viewRange()
        return float(x0), float(x1), max(1, int(round(self.box.boundingRect().width())))

    def _draw(self) -> None:
        """Hand the samples to the curve items as the view shows them (see ``thin``).  Called after a recalc and
        whenever the master range in view or the diagram's width changes."""
        view = self._view_columns()
        if self._drawn_for == (view, len(self.samples_x)):
            return
        self._drawn_for = (view, len(self.samples_x))
        for item, ys in self.layers.items():
            if not np.isfinite(ys).any():  # e.g. no straight segment: nothing green
                if item.xData is not None and len(item.xData):
                    item.setData([], [])
                continue
            item.set_samples(*thin(self.samples_x, ys, view))

    def _straight_masks(self, prof, xs: np.ndarray, below: np.ndarray,
                        acceleration: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Samples drawn green (straight segments: built as tangent sections, or happening to be straight
        [DG L3600]) and red; a sample on a joint belongs to both neighbours so the colours meet.  ``below``: the
        last fix point at or before each sample (see ``samples``); ``acceleration`` at each sample."""
        xp, yp = prof.x, prof.y
        seg = np.clip(below, 0, len(xp) - 2)
        acc = np.abs(acceleration)
        peak = np.zeros(len(xp) - 1)
        np.maximum.at(peak, seg, acc)
        at_point = xs == xp[below]  # the sample is a fix point (xs starts at xp[0])
        np.maximum.at(peak, np.clip(seg - 1, 0, None)[at_point], acc[at_point])
        flat = peak * np.diff(xp) ** 2 <= 1e-7 * np.maximum(1.0, np.abs(np.diff(yp)))
        straight = flat | prof.line_segments
        joint = at_point & (xs > xp[0]) & (xs < xp[-1])
        before = np.clip(seg - 1, 0, None)
        green = straight[seg] | (joint & straight[before])
        red = ~straight[seg] | (joint & ~straight[before])
        return green, red

    def _set_points(self, curve: Curve, prof, *, same_types: bool = False) -> None:
        pts = np.column_stack([prof.x, prof.y])
        if same_types and len(self.tangent) == len(pts):
            tangent = self.tangent  # a drag moves a point, its type stays
        else:
            tangent = np.array([p.type == "T" for p in curve.fix_points], dtype=bool)
        self._place_points(pts, tangent, dragging=same_types)
        self.set_hover(self.box.hovered)

    def _place_points(self, pts: np.ndarray, tangent: np.ndarray, *, dragging: bool = False) -> None:
        """Draw the fix points.  While a point is dragged (``dragging``: only it moves), the others keep their
        picture and the dragged one is drawn by ``drag_marker``, so 10 000 markers are not redrawn per move; when
        the drag ends (or is undone) with only that point changed, its marker is moved back among the others."""
        old, old_tangent = self.box.points, self.tangent
        self.box.points, self.tangent = pts, tangent
        moved = None
        if old.shape == pts.shape and np.array_equal(old_tangent, tangent):
            moved = np.nonzero((old != pts).any(axis=1))[0]
        if dragging and moved is not None:
            j = int(moved[0]) if len(moved) == 1 else self._drag_point if len(moved) == 0 else None
            if j is not None and self._drag_point in (None, j):
                if self._drag_point is None:
                    self._drag_point = j
                    self._markers_of(j).hide_point(self._marker_index(j))
                    self.drag_marker.setData([0.0], [0.0], brush=pg.mkBrush(GREEN if tangent[j] else RED))
                self.drag_marker.setPos(pts[j, 0], pts[j, 1])
                return
        j, self._drag_point = self._drag_point, None
        show_one(self.drag_marker, None)
        if j is not None and moved is not None and set(moved.tolist()) <= {j}:
            self._markers_of(j).move_point(self._marker_index(j), pts[j, 0], pts[j, 1])
            return
        self.points.setData(pts[~tangent, 0], pts[~tangent, 1])
        self.t_points.setData(pts[tangent, 0], pts[tangent, 1])

    def _markers_of(self, j: int) -> Markers:
        return self.t_points if self.tangent[j] else self.points

    def _marker_index(self, j: int) -> int:
        """Fix point j's index in its marker item (tangent points and the others are two items)."""
        return int(np.count_nonzero(self.tangent[:j] == self.tangent[j]))

    def move_marker(self, index: int, master: float, slave: float) -> None:
        """Only the dragged point moves (Continuous Recalc off)."""
        pts = self.box.points.copy()
        if 0 <= index < len(pts):
            pts[index] = (master, slave)
            self._place_points(pts, self.tangent, dragging=True)
            self.set_hover(index)

    def set_hover(self, index: int) -> None:
        pts = self.box.points
        show_one(self.hover, pts[index] if 0 <= index < len(pts) else None)

    def _right_axis(self, shown: list[str], *, fit: bool = True) -> None:
        """Axes and legend for the quantities shown; ``fit`` scales them to their curves (not while a point is
        dragged: the scales keep still under the mouse)."""
        if not fit and shown == self.scales.shown:
            return
        ov = self.overlay
        self.scales.show(shown, {"velocity": ov.velocity_limit, "acceleration": ov.acceleration_limit})
        self.fit_side()

    def fit_side(self) -> None:
        """Scale each right-axis quantity to its curve and its limit lines."""
        ov = self.overlay
        self.scales.fit(self.layers, {"velocity": ov.velocity_limit_value if ov.velocity_limit else None,
                                      "acceleration": ov.acceleration_limit_value if ov.acceleration_limit else None})

    def side_axes(self) -> dict[str, pg.AxisItem]:
        """The right-hand axes shown, by quantity."""
        return self.scales.visible_axes()

    def legend_entries(self) -> list[str]:
        return self.scales.legend_entries()

    def _show_overlays(self, curve: Curve | None) -> None:
        ov = self.overlay
        on = curve is not None
        self.slave_stop_line.setVisible(on and ov.slave_stop)
        if on:
            self.slave_stop_line.setValue(curve.slave_stop_position)
        for name, limit, value in (("velocity", ov.velocity_limit, ov.velocity_limit_value),
                                   ("acceleration", ov.acceleration_limit, ov.acceleration_limit_value)):
            for sign, line in zip((1, -1), self.limit_lines[name], strict=True):
                line.setVisible(on and limit)
                line.setValue(sign * value)
        self.master_marker_line.setVisible(on and ov.master_marker)
        self.master_band.setVisible(on and ov.master_marker and ov.master_tolerance > 0)
        self.master_marker_line.setValue(ov.master_marker_at)
        m, tol = ov.master_marker_at, ov.master_tolerance
        self.master_band.setRegion((m - tol, m + tol))
        self.slave_marker_line.setVisible(on and ov.slave_marker)
        self.slave_band.setVisible(on and ov.slave_marker and ov.slave_tolerance > 0)
        self.slave_marker_line.setValue(ov.slave_marker_at)
        self.slave_band.setRegion((ov.slave_marker_at - ov.slave_tolerance, ov.slave_marker_at + ov.slave_tolerance))
        for bar in self.correction_bars:
            bar.setVisible(False)
        if on and ov.correction:
            for bar, region in zip(self.correction_bars, correction_regions(curve), strict=False):
                bar.setRegion(region)
                bar.setVisible(True)
        self._show_flags(curve)
        self._show_paths(curve)

    def _show_flags(self, curve: Curve | None) -> None:
        """Start-Stop: "a" with a yellow arrow at Start, "b" with a red arrow at Stop; the selected pair's flags
        are red [DG L4030]."""
        plot = self.getPlotItem()
        key = (curve.start_stop_pairs, self.overlay.selected_pair) if curve is not None and self.overlay.start_stop \
            else None
        if key is not None and key == self._flag_key:  # the same flags: they follow the curve (a drag)
            prof = profile(curve)
            for item in self.flags:
                x = item.pos().x()
                item.setPos(x, float(prof.slave(x, periodic=False)))
            return
        self._flag_key = key
        for item in self.flags:
            plot.removeItem(item)
        self.flags = []
        if key is None:
            return
        prof = profile(curve)
        for k, pair in enumerate(curve.start_stop_pairs):
            if k == 0 and pair.start == pair.stop == 0:
                continue  # the hidden pair 0 has no flags
            selected = k == self.overlay.selected_pair
            flag = pg.mkBrush(RED if selected else YELLOW)
            for label, x, arrow in (("a", pair.start, YELLOW), ("b", pair.stop, RED)):
                y = float(prof.slave(x, periodic=False))
                head = pg.ArrowItem(pos=(x, y), angle=-90, headLen=14, tipAngle=40, brush=pg.mkBrush(arrow),
                                    pen=pg.mkPen(60, 60, 60))
                text = pg.TextItem(f"{label}{k}", color=(0, 0, 0), fill=flag, border=pg.mkPen(80, 80, 80),
                                   anchor=(0.5, 1.9))
                text.setPos(x, y)
                for item in (head, text):
                    plot.addItem(item)
                    self.flags.append(item)

    def _show_paths(self, curve: Curve | None) -> None:
        ov = self.overlay
        k = ov.selected_pair
        usable = curve is not None and k is not None and 0 <= k < len(curve.start_stop_pairs)
        for item, shown, fn in ((self.engage_item, ov.engage, engage_path), (self.disengage_item, ov.disengage,
                                                                               disengage_path)):
            if usable and shown:
                xs, ys = fn(curve, k, points=PATH_SAMPLES)  # smooth on screen; the array keeps its grid
                item.setData(xs, ys)
            elif item.xData is not None and len(item.xData):
                item.setData([], [])

    # -- view ---------------------------------------------------------------------------------------------------
    def zoom_reset(self) -> None:
        """Fit the whole curve (and what is shown with it) [DG L3569]."""
        if self.curve is None:
            return
        ys = list(self.samples_y)
        ov = self.overlay
        if ov.slave_stop:
            ys.append(self.curve.slave_stop_position)
        for shown, xs_ys in ((ov.engage or ov.disengage, (self.engage_item.yData, self.disengage_item.yData)),):
            if shown:
                for data in xs_ys:
                    if data is not None:
                        ys += list(data)
        if ov.slave_marker:
            ys += [ov.slave_marker_at - ov.slave_tolerance, ov.slave_marker_at + ov.slave_tolerance]
        lo, hi = float(np.min(ys)), float(np.max(ys))
        span = hi - lo or 1.0
        self.box.setRange(xRange=(0, self.curve.master_length), yRange=(lo - 0.06 * span, hi + 0.1 * span),
                          padding=0.02)
        self.fit_side()

    def zoom(self, factor: float) -> None:
        """Zoom In (0.5) keeps the central part; Zoom Out (2) [DG L3570-3571]."""
        self.box.scaleBy((factor, factor))


def samples(xp: np.ndarray, master_length: float) -> tuple[np.ndarray, np.ndarray]:
    """The diagram's master positions: SAMPLES evenly over the cycle and every fix point (``xp``, strictly
    increasing), sorted and without repeats; and for each the index of the last fix point at or before it (-1:
    none).  Merged by position rather than sorted and searched: a 10 000-point curve does this on every mouse
    move of a drag."""
    even = np.linspace(0.0, master_length, SAMPLES)
    after = np.searchsorted(xp, even, side="left")  # fix points before each even sample
    repeat = (after < len(xp)) & (xp[np.minimum(after, len(xp) - 1)] == even)  # on a fix point: drawn once
    even, after = even[~repeat], after[~repeat]
    return np.insert(xp, after, even), np.insert(np.arange(len(xp)), after, after - 1)


def correction_regions(curve: Curve) -> list[tuple[float, float]]:
    """The correction bar: Start → End, wrapping round the cycle end when Start > End [DG L1539-1541]."""
    a, b = curve.correction_start, curve.correction_end
    if a == b:
        return []
    if a < b:
        return [(a, b)]
    return [(a, curve.master_length), (0, b)]
