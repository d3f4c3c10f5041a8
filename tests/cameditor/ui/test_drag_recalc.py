"""Issue 6: dragging a fix point of a long curve with Continuous Recalc [DG L3642-3650] is recomputed and redrawn
within a frame (benchmarks/cam_recalc.py).  The shortcuts that make this possible change no result: at the fix points
(and every other sample) the drag's curve is the one a full recompute of the same curve gives, the colouring is
the same, the diagram draws exact samples only, and Curve Info shows the full computation's values."""

from __future__ import annotations

import dataclasses

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from PySide6.QtCore import QEvent, QObject, QRect
from PySide6.QtWidgets import QApplication

from motiontool.camcurve.model import Curve, FixPoint
from motiontool.camcurve.spline import CurveProfile, curve_info
from motiontool.cameditor import editing
from motiontool.cameditor.limits import slave_limits
from motiontool.cameditor.ui.cards import CurveInfoCard
from motiontool.cameditor.ui.diagram import SAMPLES, CurveDiagram, samples
from motiontool.cameditor.ui.edits import FOLLOW_INTERVAL
from motiontool.cameditor.ui.window import Slot

N = 3000  # with the 1600 even samples more than four samples per pixel column: the diagram thins them


def _long_curve() -> Curve:
    rng = np.random.default_rng(3)
    types = ["C"] * N
    for k in range(400, N - 400, 600):  # a few straight sections (green) among the curved ones
        types[k] = types[k + 1] = "T"
    slaves = np.round(np.cumsum(rng.normal(0, 3, N))).astype(int)
    points = tuple(FixPoint(10 * k, int(s) - int(slaves[0]), t) for k, (s, t) in enumerate(zip(slaves, types,
                                                                                               strict=True)))
    return Curve("long", 10 * (N - 1), points, interpolation=False)


def _full(curve: Curve) -> Curve:
    """An equal curve built and validated from scratch (no cache, no shortcut)."""
    return Curve(**{f.name: getattr(curve, f.name) for f in dataclasses.fields(Curve)})


def _open(editor, curve: Curve) -> None:
    editor.slots = [Slot(curve.name, [], curve)]
    editor.current = 0
    editor.refresh(zoom=True)


def _labels(card: CurveInfoCard) -> dict[str, str]:
    return {key: label.text() for key, label in card.labels.items()}


def _check_against_full_recompute(editor, reference: CurveDiagram) -> None:
    d = editor.diagram
    full = _full(editor.curve())
    prof = CurveProfile(full)
    # every sample, the fix points among them, is the full profile's value
    at_points = np.isin(d.samples_x, prof.x)
    assert at_points.sum() == len(full.fix_points)
    assert np.array_equal(d.samples_y, prof.slave(d.samples_x, periodic=False))
    assert np.array_equal(d.samples_y[at_points], prof.slave(prof.x, periodic=False))
    # the same samples and colours as a full redraw of the curve
    reference.show_curve(full, d.overlay)
    assert np.array_equal(reference.samples_x, d.samples_x)
    for item in (d.red, d.green):
        ref_item = reference.red if item is d.red else reference.green
        assert np.array_equal(reference.layers[ref_item], d.layers[item], equal_nan=True)
        # drawn: a thinned subsequence of the exact samples, about two per pixel column
        xs, ys = item.getData()
        if len(xs):
            where = np.searchsorted(d.samples_x, xs)
            assert np.array_equal(d.samples_x[where], xs)
            assert np.array_equal(d.layers[item][where], ys, equal_nan=True)
    assert len(d.red.getData()[0]) < len(d.samples_x) / 2
    # the markers: every fix point where the curve has it; while dragged, one is drawn by the drag marker
    pts = np.column_stack([prof.x, prof.y])
    assert np.array_equal(d.box.points, pts)
    tangent = np.array([q.type == "T" for q in full.fix_points])
    hidden = []
    for item, mask in ((d.points, ~tangent), (d.t_points, tangent)):
        drawn, visible = np.column_stack([item.data["x"], item.data["y"]]), item.data["visible"]
        assert np.array_equal(drawn[visible], pts[mask][visible])
        hidden += [tuple(pts[mask][k]) for k in np.flatnonzero(~visible)]
    if hidden:
        at = d.drag_marker.pos()
        assert hidden == [(at.x(), at.y())] and len(d.drag_marker.data) == 1
    else:
        assert len(d.drag_marker.data) == 0


def test_a_drag_recomputes_what_a_full_recompute_gives(qtbot, editor):
    curve = _long_curve()
    _open(editor, curve)
    editor.cards.setCurrentWidget(editor.curve_info)  # Curve Info follows the drag while it is shown
    assert editor.options["continuous_recalc"]
    reference = CurveDiagram()
    card = CurveInfoCard()
    index = N // 2
    p = curve.fix_points[index]
    box = editor.diagram.box
    for step, (dm, ds) in enumerate(((2, 15), (4, 40), (-3, -25), (1, 60))):
        box.point_dragged.emit(index, p.master + dm + 0.25, p.slave + ds, False)  # what a mouse move sends
        moved = editor.curve()
        assert moved.fix_points[index] == FixPoint(p.master + dm, p.slave + ds)  # whole units (decision C17)
        assert moved == _full(moved)
        _check_against_full_recompute(editor, reference)
        at = editor.diagram.drag_marker.pos()  # the dragged point's marker sits where the point is
        assert (at.x(), at.y()) == (moved.fix_points[index].master, moved.fix_points[index].slave)
        qtbot.wait(int(FOLLOW_INTERVAL * 1000) + 30)  # Curve Info and the table row catch up
        full = _full(moved)
        assert curve_info(moved) == curve_info(full)
        card.show_info(full, curve_info(full), slave_limits(full, editor.parameters))
        assert _labels(editor.curve_info) == _labels(card), step
        assert editor.fix_table.model.curve.fix_points[index] == moved.fix_points[index]
    box.point_dragged.emit(index, p.master + 1.25, p.slave + 60, True)  # release: one undo step
    final = editing.move_point(curve, index, p.master + 1, p.slave + 60)
    assert editor.curve() == final and editor.slot().history.undo_label() == "Move point"
    _check_against_full_recompute(editor, reference)
    assert len(editor.diagram.drag_marker.data) == 0 and editor.diagram.points.data["visible"].all()
    editor.actions_by_name["undo"].trigger()
    assert editor.curve() == curve
    _check_against_full_recompute(editor, reference)


def test_a_hidden_curve_info_card_catches_up_when_shown(qtbot, editor):
    """Curve Info is computed during a drag only while its card is in front; brought to the front mid-drag it
    shows the dragged curve at once."""
    curve = _long_curve()
    _open(editor, curve)
    assert editor.cards.currentWidget() is not editor.curve_info
    before = _labels(editor.curve_info)
    p = curve.fix_points[100]
    editor.diagram.box.point_dragged.emit(100, p.master, p.slave + 500, False)
    qtbot.wait(int(FOLLOW_INTERVAL * 1000) + 30)
    assert _labels(editor.curve_info) == before  # behind, while hidden
    editor.cards.setCurrentWidget(editor.curve_info)
    full = _full(editor.curve())
    card = CurveInfoCard()
    card.show_info(full, curve_info(full), slave_limits(full, editor.parameters))
    assert _labels(editor.curve_info) == _labels(card) != before
    editor.diagram.box.point_dragged.emit(100, p.master, p.slave + 500, True)
    assert editor.curve() == _full(editor.curve()) and editor.curve().fix_points[100].slave == p.slave + 500


def test_the_slave_marker_follows_a_drag_that_changes_the_slave_length(qtbot, editor):
    """The slave marker is a slave position reduced over the slave length [DG L3762-3765]: dragging the last
    point changes the slave length, so the marker line moves with the drag, not only on release."""
    points = (FixPoint(0, 0), FixPoint(1500, 1200, "T"), FixPoint(2500, 2400, "T"), FixPoint(4000, 3600))
    curve = dataclasses.replace(Curve("marker", 4000, points, intervals=40), slave_marker_pos=3500)
    _open(editor, curve)
    editor.options.boxes["slave_marker"].setChecked(True)
    for slave in (3400, 3000):
        editor.diagram.box.point_dragged.emit(3, 4000, slave, False)
        assert editor.curve().slave_length == slave
        assert editor.diagram.slave_marker_line.value() == editor.overlay().slave_marker_at
    assert editor.diagram.slave_marker_line.value() != 3500  # reduced over the new slave length


@settings(max_examples=300, deadline=None)
@given(st.lists(st.one_of(st.integers(-50, 5050), st.floats(-50, 5050, allow_nan=False)), min_size=2,
                max_size=60, unique=True),
       st.sampled_from([1.0, 999.0, 1000.0, 4000.0, 4001.5]))
def test_diagram_samples_merge_as_sort_and_search_would(points, length):
    """The diagram's samples (even ones plus every fix point) are merged by position; the result is what sorting
    and searching gives: the sorted union without repeats, and the last fix point at or before each sample."""
    xp = np.unique(np.array(points, dtype=float))
    if len(xp) < 2:
        return
    xp = np.concatenate([xp, np.linspace(0.0, length, SAMPLES)[[0, 7, -1]]])  # some on the even grid
    xp = np.unique(xp)
    xs, below = samples(xp, length)
    expected = np.sort(np.concatenate([np.linspace(0.0, length, SAMPLES), xp]))
    expected = expected[np.concatenate([[True], np.diff(expected) > 0])]
    assert np.array_equal(xs, expected)
    assert np.array_equal(below, np.searchsorted(xp, expected, side="right") - 1)


class _PaintSpy(QObject):
    """Records the region of each paint event of one widget."""

    def __init__(self, widget) -> None:
        super().__init__()
        self.regions: list[QRect] = []
        widget.installEventFilter(self)

    def eventFilter(self, obj, event) -> bool:  # noqa: N802 - Qt override
        if event.type() == QEvent.Type.Paint:
            self.regions.append(event.region().boundingRect())
        return False


def _on_screen(editor):
    """What the window shows of the diagram (the backing store, not a fresh rendering)."""
    vp = editor.diagram.viewport()
    top = vp.mapTo(editor, vp.rect().topLeft())
    return editor.screen().grabWindow(editor.winId(), top.x(), top.y(), vp.width(), vp.height()).toImage()


def test_a_drag_repaints_only_the_strip_that_changed_and_the_screen_is_a_full_repaint(qtbot, editor):
    """Each move repaints only where the drawn lines changed: seen whole, a long curve changes in a narrow strip
    around the dragged point, not over the whole diagram.  After the moves the screen shows pixel for pixel what
    a full rendering of the diagram shows, also zoomed in so far that the change spreads over the whole view, and
    with the velocity on the right axis too.  (The comparison renders the diagram once more, which makes Qt
    re-render its cached items: so it comes after the moves, which keeps what they left on screen.)"""
    curve = _long_curve()
    _open(editor, curve)
    editor.options.boxes["velocity"].setChecked(True)
    qtbot.wait(50)
    spy = _PaintSpy(editor.diagram.viewport())
    index = N // 2 + 7
    p = curve.fix_points[index]
    moves = iter(enumerate((12, 30, -45, 80, 81, 20, -60, 5, 100, -100)))
    for zoomed in (False, True):
        if zoomed:  # about 40 fix points in view: the spline's change reaches far beyond the point's marker
            editor.diagram.box.setRange(xRange=(p.master - 200, p.master + 200),
                                        yRange=(p.slave - 150, p.slave + 150), padding=0)
            qtbot.wait(20)
        for _ in range(5):
            step, ds = next(moves)
            spy.regions.clear()
            editor.diagram.box.point_dragged.emit(index, p.master + 0.5 * step, p.slave + ds, False)
            QApplication.processEvents()
            if step and not zoomed:  # (the first move takes the point out of the cached markers: all repainted)
                assert spy.regions and max(r.width() for r in spy.regions) < editor.diagram.viewport().width() / 8
        # the screen after the partial repaints is what a full rendering of the diagram gives
        assert _on_screen(editor) == editor.diagram.viewport().grab().toImage(), zoomed
    editor.diagram.box.point_dragged.emit(index, p.master, p.slave + 81, True)


def test_the_point_column_fits_the_largest_point_number(qtbot, editor):
    """The Fix Points table's Point column is as wide as Qt's own fit to the contents would make it, for a long
    curve (measured on the last row only), a short one (then the header is the widest) and after a new font."""
    table = editor.fix_table.view
    for curve in (_long_curve(), Curve("short", 4000, (FixPoint(0, 0), FixPoint(4000, 3600)))):
        _open(editor, curve)
        qtbot.wait(10)
        assert table.columnWidth(0) == max(table.sizeHintForColumn(0), table.horizontalHeader().sectionSizeHint(0))
    font = table.font()
    font.setPointSizeF(font.pointSizeF() * 1.8)
    table.setFont(font)  # bigger numbers: fitted again
    qtbot.wait(10)
    assert table.columnWidth(0) == max(table.sizeHintForColumn(0), table.horizontalHeader().sectionSizeHint(0))
