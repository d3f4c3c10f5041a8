"""The CAM diagram's drawing helpers (cameditor/ui/drawing.py) give what pyqtgraph's own items give, only
cheaper: the changed part of a polyline, and marker items whose remembered bounding rect is always pyqtgraph's."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg

from motiontool.cameditor.ui.drawing import Markers, changed_span


def test_changed_span_of_two_polylines():
    x = np.arange(10.0)
    y = np.sin(x)
    assert changed_span(x, y, x, y.copy(), 1e-6, 1e-6) is None
    y2 = y.copy()
    y2[4] += 1e-3
    assert changed_span(x, y, x, y2, 1e-6, 1e-6) == (3.0, 5.0)  # the point and the segments to its neighbours
    assert changed_span(x, y, x, y2, 1e-6, 1e-2) is None  # within the tolerance
    gap = y.copy()
    gap[7] = np.nan
    assert changed_span(x, y, x, gap, 1e-6, 1e-6) == (6.0, 8.0)
    # one point more in the middle: what is shared at both ends is unchanged
    x3, y3 = np.insert(x, 5, 4.5), np.insert(y, 5, 0.25)
    assert changed_span(x, y, x3, y3, 1e-6, 1e-6) == (4.0, 5.0)
    assert changed_span(x3, y3, x, y, 1e-6, 1e-6) == (4.0, 5.0)


def test_markers_remember_exactly_pyqtgraphs_bounding_rect(qtbot):
    widget = pg.PlotWidget()
    qtbot.addWidget(widget)
    widget.resize(600, 400)
    widget.show()
    qtbot.waitExposed(widget)
    markers = Markers(size=9, symbol="s")
    widget.addItem(markers)

    def same():
        qtbot.wait(5)
        assert markers.boundingRect() == pg.ScatterPlotItem.boundingRect(markers)

    markers.setData([0.0, 10.0, 20.0], [1.0, 5.0, -3.0])
    same()
    widget.setRange(xRange=(-5, 5), yRange=(0, 2), padding=0)  # zoomed: another pixel size
    same()
    markers.setData([0.0, 100.0], [0.0, 50.0])  # other points
    same()
    markers.setSize(30)  # bigger spots: more padding
    same()
    markers.setPointsVisible(np.array([True, False]))
    same()
    widget.resize(300, 200)  # another view size
    same()
    markers.setData([], [])
    same()
