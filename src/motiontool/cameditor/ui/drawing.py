"""Drawing helpers of the curve diagram that keep a 10 000-point curve as fast on screen as a short one: the
samples a view needs (``thin``), a curve item that draws in pixels and repaints only where its line changed
(``ScreenCurve``) and one-point markers that move instead of taking new data (``show_one``)."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from pyqtgraph import debug
from pyqtgraph.Qt.internals import PrimitiveArray
from PySide6.QtCore import QLineF, QRectF
from PySide6.QtGui import QPainter, QTransform
from PySide6.QtWidgets import QGraphicsItem

DRAW_ALL_UP_TO = 4  # samples per pixel column drawn as they are; more are thinned to each column's extremes
_FAR = 2.0 ** 30  # pixel coordinates are clipped to this (Qt misdraws beyond)


def thin(xs: np.ndarray, ys: np.ndarray, view: tuple[float, float, int] | None) -> tuple[np.ndarray, np.ndarray]:
    """The samples (xs sorted) to draw for ``view`` = (x0, x1, pixel columns), or all of them for None.

    Samples outside the view are left out, except one on each side so the line runs to the edges.  Where more
    than DRAW_ALL_UP_TO samples fall into one pixel column (a long curve seen whole), only the lowest and the
    highest sample of each column are kept, with the first and last sample and the samples on both sides of
    every gap (NaN): the drawn line has the same extent in every column and the same gaps, so it looks the same,
    and every drawn point is an exact sample (about two points per pixel column instead of e.g. 11 600)."""
    if view is None or len(xs) < 3:
        return xs, ys
    x0, x1, columns = view
    lo = max(int(np.searchsorted(xs, x0, side="left")) - 1, 0)
    hi = min(int(np.searchsorted(xs, x1, side="right")) + 1, len(xs))
    xs, ys = xs[lo:hi], ys[lo:hi]
    if len(xs) <= DRAW_ALL_UP_TO * columns or x1 <= x0:
        return xs, ys
    column = np.floor((xs - x0) * (columns / (x1 - x0)))
    starts = np.flatnonzero(np.concatenate([[True], column[1:] != column[:-1]]))
    counts = np.diff(np.append(starts, len(xs)))
    finite = np.isfinite(ys)
    index = np.arange(len(xs))
    keep = [np.array([0, len(xs) - 1])]
    for extreme, fill in ((np.minimum, np.inf), (np.maximum, -np.inf)):
        values = np.where(finite, ys, fill)
        best = np.repeat(extreme.reduceat(values, starts), counts)
        keep.append(np.minimum.reduceat(np.where(values == best, index, len(xs)), starts))
    edge = np.flatnonzero(finite[1:] != finite[:-1])
    keep += [edge, edge + 1]
    kept = np.zeros(len(xs), dtype=bool)  # the kept indices, sorted and once each
    for k in keep:
        kept[k] = True
    return xs[kept], ys[kept]


def changed_span(old_x: np.ndarray, old_y: np.ndarray, x: np.ndarray, y: np.ndarray, tol_x: float = 0.0,
                 tol_y: float = 0.0) -> tuple[float, float] | None:
    """The x range of the segments where polyline (x, y) differs from (old_x, old_y) by more than the tolerances
    (NaN = gap; a gap opening or closing is a change), or None if it does not.  The lines may differ in length:
    what they share at the start and at the end is unchanged, the rest between is the change."""
    m = min(len(old_x), len(x))

    def differs(ax, ay, bx, by):
        return (np.abs(ax - bx) > tol_x) | (np.abs(ay - by) > tol_y) | (np.isnan(ay) != np.isnan(by))

    front = differs(old_x[:m], old_y[:m], x[:m], y[:m])
    if len(old_x) == len(x):
        if not front.any():
            return None
        back = front
    else:
        back = differs(old_x[len(old_x) - m:], old_y[len(old_y) - m:], x[len(x) - m:], y[len(y) - m:])
    first = int(np.argmax(front)) if front.any() else m  # points equal at the start
    last = m - 1 - int(np.flatnonzero(back)[-1]) if back.any() else m  # points equal at the end
    ends = []
    for xs in (old_x, x):  # the changed points and the segments to their neighbours
        n = len(xs)
        lo, hi = max(min(first, n - last) - 1, 0), min(max(first, n - last), n - 1)
        ends += [xs[lo], xs[hi]]
    return min(ends), max(ends)


class ScreenCurve(pg.PlotCurveItem):
    """A PlotCurveItem (solid line, NaN = gap) that maps its points to pixels itself and draws with the identity
    transform: Qt draws thick lines about three times as fast in pixels as through the view's scaling.

    ``set_samples`` (x increasing) repaints only the strip where the line changed: a dragged fix point moves a long
    spline visibly only near the point, so Qt repaints that strip instead of the whole diagram; ``paint`` draws
    only the segments in the part being repainted.  For that the item's geometry is what its view shows, not the
    data's extent (new data never changes it; the view box clips its items to the view anyway)."""

    def __init__(self, pen) -> None:
        super().__init__(pen=pen, connect="finite")
        self._segments = PrimitiveArray(QLineF, 4)
        self._view_rect: QRectF | None = None
        self.setFlag(QGraphicsItem.GraphicsItemFlag.ItemUsesExtendedStyleOption)  # paint() gets the exposed part

    def boundingRect(self) -> QRectF:  # noqa: N802 - Qt override
        if self._view_rect is None:
            view = self.getViewBox()
            rect = None if view is None else self.mapRectFromView(view.viewRect())
            self._view_rect = QRectF() if rect is None else rect.normalized()
        return self._view_rect

    def viewRangeChanged(self) -> None:  # noqa: N802 - pyqtgraph override
        self._view_rect = None
        self.prepareGeometryChange()
        super().viewRangeChanged()

    def viewTransformChanged(self) -> None:  # noqa: N802 - pyqtgraph override, also when the item gets its view
        self._view_rect = None
        super().viewTransformChanged()

    def set_samples(self, x: np.ndarray, y: np.ndarray) -> None:
        """setData for x increasing, repainting only where the drawn line changes (see the class)."""
        old_x, old_y = self.xData, self.yData
        view = self.getViewWidget() if old_x is not None and len(old_x) > 1 and len(x) > 1 else None
        tr = self.deviceTransform(view.viewportTransform()) if view is not None else None
        if tr is None or tr.type().value > QTransform.TransformationType.TxScale.value or tr.m11() == 0 \
                or tr.m22() == 0:
            self.setData(x, y)
            return
        self.xData, self.yData = x, y
        self.invalidateBounds()
        self.informViewBoundsChanged()  # the data's extent, for the view's auto range
        # what PlotCurveItem.updateData resets besides the geometry and the full repaint
        self.path = self.fillPath = self._fillPathList = self._mouseShape = None
        self._lineSegmentsRendered = False
        sx = abs(tr.m11())
        # only points with exactly the same coordinates count as unchanged: Qt then draws exactly the same pixels
        # (a change of a millionth of a pixel can move a pixel edge; far from a dragged fix point the spline's
        # change is below the numbers' resolution, some 30 fix points away)
        span = changed_span(old_x, old_y, x, y)
        if span is not None:
            pad = (self.opts["pen"].widthF() + 2) / sx  # the pen's width and a pixel of rounding either side
            box = self.boundingRect()
            self.update(QRectF(span[0] - pad, box.top(), span[1] - span[0] + 2 * pad, box.height()))
        self.sigPlotChanged.emit(self)

    @debug.warnOnException  # an exception raised in paint() would crash Qt
    def paint(self, p: QPainter, opt, widget) -> None:
        x, y = self.xData, self.yData
        tr = p.transform()
        if (x is None or len(x) < 2 or self.opts["fillLevel"] is not None or self.opts["stepMode"]
                or self.opts["shadowPen"] is not None
                or tr.type().value > QTransform.TransformationType.TxScale.value):
            super().paint(p, opt, widget)
            return
        exposed = opt.exposedRect
        # a line's width reaches beyond its segment's ends: also the segments within that distance of the part
        margin = (self.opts["pen"].widthF() + 2) / abs(tr.m11()) if tr.m11() else 0.0
        left, right = exposed.left() - margin, exposed.right() + margin
        if exposed.width() > 0 and (left > x[0] or right < x[-1]):  # x increasing: a slice
            lo = max(int(np.searchsorted(x, left, side="right")) - 1, 0)
            hi = min(int(np.searchsorted(x, right, side="left")) + 1, len(x))
            x, y = x[lo:hi], y[lo:hi]
            if len(x) < 2:
                return
        px = np.clip(x * tr.m11() + tr.dx(), -_FAR, _FAR)
        py = np.clip(y * tr.m22() + tr.dy(), -_FAR, _FAR)  # NaN stays NaN
        ok = np.isfinite(px) & np.isfinite(py)
        first = np.flatnonzero(ok[:-1] & ok[1:])
        self._segments.resize(len(first))
        lines = self._segments.ndarray()
        lines[:, 0], lines[:, 1], lines[:, 2], lines[:, 3] = px[first], py[first], px[first + 1], py[first + 1]
        p.save()
        p.resetTransform()
        p.setRenderHint(QPainter.RenderHint.Antialiasing, bool(self.opts["antialias"]))
        p.setPen(self.opts["pen"])
        p.drawLines(*self._segments.drawargs())
        p.restore()


class Markers(pg.ScatterPlotItem):
    """A ScatterPlotItem that keeps its bounding rect until its points, their sizes or the view change: Qt asks for
    it several times per repaint (each mouse move of a drag), and pyqtgraph works it out from the view's pixel
    size every time."""

    _rect: QRectF | None = None

    def boundingRect(self) -> QRectF:  # noqa: N802 - Qt override
        if self._rect is None:
            self._rect = super().boundingRect()
        return self._rect

    def prepareGeometryChange(self) -> None:  # noqa: N802 - pyqtgraph calls it before any change of the bounds
        # (new points, a new view range or size: ScatterPlotItem.viewTransformChanged calls it too)
        self._rect = None
        super().prepareGeometryChange()

    def updateSpots(self, *args, **kwargs) -> None:  # noqa: N802 - new spot sizes change the padding
        super().updateSpots(*args, **kwargs)
        self._rect = None

    # One point changed in place (a fix point drag): setData or setPointsVisible would re-measure every spot,
    # some 50 ms for 10 000 markers.  What ScatterPlotItem.setData does after new positions, for one record.
    def hide_point(self, k: int) -> None:
        self.data["visible"][k] = False
        self.invalidate()

    def move_point(self, k: int, x: float, y: float) -> None:
        """Point k to (x, y), shown."""
        self.data["x"][k], self.data["y"][k], self.data["visible"][k] = x, y, True
        self.prepareGeometryChange()
        self.informViewBoundsChanged()
        self.bounds = [None, None]
        self.invalidate()


def show_one(item: pg.ScatterPlotItem, at) -> None:
    """A one-point marker at ``at`` (x, y), or none for None.  Its point sits at (0, 0) and the item moves:
    cheaper than new data on every mouse move."""
    if at is None:
        if len(item.data):
            item.setData([], [])
        return
    if len(item.data) != 1:
        item.setData([0.0], [0.0])
    item.setPos(float(at[0]), float(at[1]))
