"""Qt-free curve edits of the CAM editor (cameditor.editing) and the Curve Info/marker helpers (limits)."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from motiontool.camcurve.model import CurveError, FixPoint
from motiontool.cameditor import editing
from motiontool.cameditor.limits import marker_detection, slave_limits
from tests.camcurve.conftest import marker_curve, stamping_curve


def _types(curve):
    return [p.type for p in curve.fix_points]


def test_tangent_pairing_sets_the_preceding_point():
    """DG L1441-1445: "Set the point 2500 to T" — 1500 becomes T as well."""
    plain = editing.replace(stamping_curve(), fix_points=tuple(FixPoint(p.master, p.slave)
                                                               for p in stamping_curve().fix_points))
    assert _types(editing.change_type(plain, 2, "T")) == ["C", "T", "T", "C"]
    assert _types(editing.change_type(plain, 0, "T")) == ["T", "T", "C", "C"]  # the first pairs forwards


def test_releasing_a_tangent_point_releases_its_partner():
    assert _types(editing.change_type(stamping_curve(), 2, "C")) == ["C", "C", "C", "C"]


def test_cz_without_a_following_straight_section_is_refused_with_the_reason():
    """DG L4014-4016: "This curve type can only be used between adjacent tangent segments"."""
    with pytest.raises(CurveError, match="point 4 cannot become Trapezoid"):
        editing.change_type(stamping_curve(), 3, "CZ")


def test_last_point_guards_name_the_blocking_item():
    """DG L3745-3752: not before the previous fix point, a start/stop point, correction start/end or master
    marker position."""
    with pytest.raises(CurveError, match="start/stop pair 2 Stop at 3000"):
        editing.move_point(marker_curve(), 3, 2800, 3600)
    with pytest.raises(CurveError, match="point 3 at 2500"):
        editing.move_point(marker_curve(), 3, 2400, 3600)
    moved = editing.move_point(marker_curve(), 3, 2000, 3600, clamp=True)
    assert moved.master_length == 3000 and moved.intervals == 30  # interval size kept [DG L3978]


def test_moving_the_last_point_right_extends_the_master_length_on_the_grid():
    """DG L3988: "The last Fix point can be moved as far as desired towards the right … always snapped"."""
    moved = editing.move_point(stamping_curve(), 3, 4630, 3600)
    assert moved.master_length == 4600 and moved.intervals == 46


def test_add_points_in_any_order_is_one_edit_and_replaces_equal_masters():
    c = editing.new_curve("x", 4000, 40, True)
    c = editing.add_points(c, [(4000, 3600), (1500, 1200), (0, 0), (2500, 2400)])
    assert [(p.master, p.slave) for p in c.fix_points] == [(0, 0), (1500, 1200), (2500, 2400), (4000, 3600)]


def test_snap_all_puts_points_and_pairs_on_the_grid():
    c = editing.add_points(stamping_curve(), [(1234, 1000)])
    c = editing.add_pairs(editing.replace(c, interpolation=False), [(1010, 1490)])
    snapped = editing.snap_all(c)
    assert all(p.master % 100 == 0 for p in snapped.fix_points)
    assert snapped.start_stop_pairs[-1].start == 1000 and snapped.start_stop_pairs[-1].stop == 1500


@pytest.mark.parametrize(("position", "distance", "expected"),
                         [(1000, 2375, 2625), (1000, 4100, 900), (1000, 3900, 1100), (800, 3900, 900)])
def test_marker_detection_examples(position, distance, expected):
    """DG L1582-1606 (ide-spec 4.45)."""
    assert marker_detection(position, distance, 4000) == expected


@given(st.integers(0, 10_000), st.integers(0, 100_000), st.integers(1, 10_000))
def test_marker_detection_is_in_the_cycle_and_periodic_in_the_distance(position, distance, length):
    at = marker_detection(position, distance, length)
    assert 0 <= at < length
    assert marker_detection(position, distance + length, length) == pytest.approx(at, abs=1e-9) or \
        abs(marker_detection(position, distance + length, length) - at) == pytest.approx(length)


@given(st.floats(1, 600))
def test_limits_shrink_as_cycles_per_minute_rise(cycles):
    """DG L3815: "As Cycle/min Master increases, Slave Velocity Limit will decrease"."""
    params = {"32-01": 500, "32-12": 25, "32-11": 9}
    slow = slave_limits(editing.replace(stamping_curve(), cycles_per_min=cycles), params)
    fast = slave_limits(editing.replace(stamping_curve(), cycles_per_min=cycles * 2), params)
    assert fast.velocity == pytest.approx(slow.velocity / 2)
    assert fast.acceleration == pytest.approx(slow.acceleration / 4)
