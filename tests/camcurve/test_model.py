"""Curve validation: CurveError names the field."""

from __future__ import annotations

import dataclasses

import pytest

from motiontool.camcurve import Curve, CurveError, FixPoint, StartStopPair, encode, segment_kinds, snap
from tests.camcurve.conftest import STAMPING_POINTS


def make(**changes) -> Curve:
    base = dict(name="stamping", master_length=4000, fix_points=STAMPING_POINTS)
    base.update(changes)
    return Curve(**base)


@pytest.mark.parametrize(("changes", "field"), [
    ({"name": "x" * 17}, "name"),
    ({"master_length": 3000}, "master_length"),
    ({"fix_points": (FixPoint(10, 0), *STAMPING_POINTS[1:])}, "fix_points"),
    ({"fix_points": (STAMPING_POINTS[0], STAMPING_POINTS[2], STAMPING_POINTS[1], STAMPING_POINTS[3])}, "fix_points"),
    ({"fix_points": (FixPoint(0, 0), FixPoint(1500, 1200, "T"), FixPoint(2500, 2400), FixPoint(4000, 3600))},
     "fix_points"),
    ({"fix_points": (FixPoint(0, 0), FixPoint(1500, 1200, "X"), FixPoint(2500, 2400), FixPoint(4000, 3600))},
     "fix_points"),
    ({"start_stop_pairs": (StartStopPair(0, 4100),)}, "start_stop_pairs"),
    ({"start_stop_pairs": (StartStopPair(50, 100),)}, "start_stop_pairs"),  # off the 100 MU grid
    ({"start_stop_pairs": (StartStopPair(0, 0),) * 27}, "start_stop_pairs"),
    ({"correction_start": 5000}, "correction_start"),
    ({"master_marker_pos": -1}, "master_marker_pos"),
    ({"cycles_per_min": 0}, "cycles_per_min"),
    ({"intervals": 0}, "intervals"),
    ({"curve_type": 7}, "curve_type"),
])
def test_invalid_curves_name_the_field(changes, field):
    with pytest.raises(CurveError) as info:
        make(**changes)
    assert info.value.field == field


def test_tangent_rules():
    """DG L3992: "at least one curve segment is required between adjacent tangent segments"; L1445: "two tangent
    points are always required"; L4016/4020: CZ and C3 "can only be used between adjacent tangent segments"."""
    assert segment_kinds("CTTC") == ["spline", "line", "spline"]
    assert segment_kinds("TTTT") == ["line", "spline", "line"]
    assert segment_kinds(["T", "CZ", "T", "T"]) == ["line", "trapezoid", "line"]
    for bad in ("TTT", "CTCC", ["C", "CZ", "T", "T"], ["T", "C3", "C", "C"]):
        with pytest.raises(CurveError):
            segment_kinds(list(bad))


def test_new_curve_with_two_points_is_a_line_but_not_encodable():
    """ide-spec 4.18: a new curve "starts with two fix points forming a straight line"; the array needs >= 4."""
    curve = Curve("new", 1000, (FixPoint(0, 0), FixPoint(1000, 1000)), intervals=10)
    assert curve.slave_length == 1000
    with pytest.raises(CurveError) as info:
        encode(curve)
    assert info.value.field == "fix_points"


def test_non_integral_values_are_not_encodable():
    with pytest.raises(CurveError) as info:
        encode(dataclasses.replace(make(), slave_stop_position=0.5))
    assert info.value.field == "slave_stop_position"


def test_snap_on_grid():
    """DG L3954: "Snap on Grid" snaps a moved point to the nearest grid point."""
    assert snap(1549, 100) == 1500 and snap(1551, 100) == 1600
