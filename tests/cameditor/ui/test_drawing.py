"""The CAM diagram's drawing helpers (cameditor/ui/drawing.py) give what pyqtgraph's own items give, only
cheaper: the changed part of a polyline, and marker items whose remembered bounding rect is always pyqtgraph's."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg

from motiontool.cameditor.ui.drawing import Markers, ScreenCurve, changed_span


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
        """Equal to pyqtgraph's own rect, worked out now and by a fresh item with the same points (no caches)."""
        qtbot.wait(5)
        assert markers.boundingRect() == pg.ScatterPlotItem.boundingRect(markers)
        x, y = markers.getData()
        if not len(x):  # (empty: pyqtgraph keeps the last spots' padding, a fresh item has none)
            return
        fresh = pg.ScatterPlotItem(x=x.copy(), y=y.copy(), size=markers.opts["size"], symbol="s")
        widget.addItem(fresh)
        try:
            assert markers.boundingRect() == fresh.boundingRect()
        finally:
            widget.removeItem(fresh)

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
    markers.hide_point(1)  # a drag starts: the point is drawn apart
    same()
    markers.move_point(1, 250.0, -80.0)  # ... and ends beyond the others: the item grows
    same()
    assert markers.data["visible"].all() and (markers.data["x"][1], markers.data["y"][1]) == (250.0, -80.0)
    markers.setData([], [])
    same()


def test_a_screen_curve_covers_what_its_view_shows(qtbot):
    """A ScreenCurve's geometry is its view, not its data (new data never changes it): it follows zoom, pan and
    resize, also in a second view box linked to the first, as the CAM diagram's right axis has."""
    widget = pg.PlotWidget()
    qtbot.addWidget(widget)
    widget.resize(600, 400)
    widget.show()
    qtbot.waitExposed(widget)
    main = widget.getPlotItem().getViewBox()
    side = pg.ViewBox()
    widget.getPlotItem().scene().addItem(side)
    side.setXLink(main)
    main.setRange(xRange=(0, 10), yRange=(0, 100), padding=0)  # (no auto range: no range change below)
    qtbot.wait(5)
    curves = {main: ScreenCurve(pen=pg.mkPen("r")), side: ScreenCurve(pen=pg.mkPen("b"))}
    assert curves[main].boundingRect().isEmpty()  # no view yet; asked before it gets one
    main.addItem(curves[main])
    assert curves[main].boundingRect() == curves[main].mapRectFromView(main.viewRect()).normalized()
    side.addItem(curves[side])
    for curve in curves.values():
        curve.setData(np.arange(10.0), np.arange(10.0) ** 2)

    def same():
        qtbot.wait(5)
        for box, curve in curves.items():
            assert curve.boundingRect() == curve.mapRectFromView(box.viewRect()).normalized()

    side.setGeometry(main.sceneBoundingRect())
    same()
    main.setRange(xRange=(2, 4), yRange=(0, 1), padding=0)
    same()
    side.setYRange(-5, 5, padding=0)
    same()
    widget.resize(300, 200)
    side.setGeometry(main.sceneBoundingRect())
    same()
    curves[main].set_samples(np.arange(5.0), np.ones(5))  # new data: the same geometry
    same()
