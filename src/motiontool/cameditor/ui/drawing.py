"""Drawing helpers of the curve diagram that keep a 10 000-point curve as fast on screen as a short one: the
samples a view needs (``thin``), a curve item that draws in pixels (``ScreenCurve``) and one-point markers that
move instead of taking new data (``show_one``)."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from pyqtgraph import debug
from pyqtgraph.Qt.internals import PrimitiveArray
from PySide6.QtCore import QLineF
from PySide6.QtGui import QPainter, QTransform

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
    keep = np.unique(np.concatenate(keep))
    return xs[keep], ys[keep]


class ScreenCurve(pg.PlotCurveItem):
    """A PlotCurveItem (solid line, NaN = gap) that maps its points to pixels itself and draws with the identity
    transform: Qt draws thick lines about three times as fast in pixels as through the view's scaling."""

    def __init__(self, pen) -> None:
        super().__init__(pen=pen, connect="finite")
        self._segments = PrimitiveArray(QLineF, 4)

    @debug.warnOnException  # an exception raised in paint() would crash Qt
    def paint(self, p: QPainter, opt, widget) -> None:
        x, y = self.xData, self.yData
        tr = p.transform()
        if (x is None or len(x) < 2 or self.opts["fillLevel"] is not None or self.opts["stepMode"]
                or self.opts["shadowPen"] is not None
                or tr.type().value > QTransform.TransformationType.TxScale.value):
            super().paint(p, opt, widget)
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
