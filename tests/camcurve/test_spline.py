"""Spline properties: interpolation through the fix points, C1 continuity, vectorised = scalar evaluation."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.camcurve import Curve, CurveType, FixPoint, profile, slave, velocity
from motiontool.camcurve.model import LINE
from tests.camcurve.strategies import curves


@settings(max_examples=150, deadline=None)
@given(curves())
def test_curvepos_at_fix_points(curve):
    """CURVEPOS at a fix point's master position equals its slave value (kernel-spec g.2: "slave curve position
    belonging to the current curve-master position")."""
    for p in curve.fix_points:
        assert slave(curve, p.master) == pytest.approx(p.slave, abs=1e-9 * max(1.0, abs(p.slave)))


@settings(max_examples=150, deadline=None)
@given(curves())
def test_slave_and_velocity_continuous_at_fix_points(curve):
    """DG L3990: "The CAM-Editor will always try to make a smooth transition from one segment to the next."""
    prof = profile(curve)
    pieces = prof.ppoly.c.shape[1]
    for i in range(pieces - 1):
        scale = 1.0 + max(abs(p.slave) for p in curve.fix_points)
        for nu in (0, 1):
            left, right = prof.one_sided(i, nu, True), prof.one_sided(i + 1, nu, False)
            assert left == pytest.approx(right, abs=1e-7 * scale), (i, nu)


@settings(max_examples=100, deadline=None)
@given(curves(), st.lists(st.floats(-2.0, 3.0), min_size=1, max_size=20))
def test_vectorised_matches_scalar(curve, fractions):
    prof = profile(curve)
    xs = np.array(fractions) * curve.master_length
    for fn in (prof.slave, prof.velocity, prof.acceleration, prof.jerk):
        vec = fn(xs)
        assert vec.shape == xs.shape
        for x, v in zip(xs, vec, strict=True):
            assert fn(float(x)) == pytest.approx(v, rel=1e-12, abs=1e-9)


@settings(max_examples=100, deadline=None)
@given(curves())
def test_straight_sections_are_straight(curve):
    """DG L4012: "Tangent (T) The following segment is straight. The velocity will be constant and the
    acceleration will be zero." """
    prof = profile(curve)
    for k, kind in enumerate(prof.kinds):
        if kind == LINE:
            a, b = curve.fix_points[k], curve.fix_points[k + 1]
            xs = np.linspace(a.master, b.master, 7)[1:-1]
            np.testing.assert_allclose(prof.velocity(xs), (b.slave - a.slave) / (b.master - a.master), rtol=1e-9,
                                       atol=1e-9)
            np.testing.assert_allclose(prof.acceleration(xs), 0, atol=1e-9)


@settings(max_examples=100, deadline=None)
@given(curves())
def test_curve_type_gradients(curve):
    """DG L3712-3729: the Type of Curve sets the start/end gradients."""
    prof = profile(curve)
    v0, v1 = prof.velocity(0.0), prof.velocity(curve.master_length, periodic=False)
    kinds = prof.kinds
    if kinds[0] == LINE or kinds[-1] == LINE:
        return
    if curve.curve_type == CurveType.ZERO_GRADIENTS:
        assert (v0, v1) == pytest.approx((0, 0), abs=1e-9)
    elif curve.curve_type in (CurveType.SPECIFIED_GRADIENTS, CurveType.SPECIFIED_IMMEDIATE):
        assert (v0, v1) == pytest.approx((curve.start_gradient, curve.end_gradient), abs=1e-7)
    else:
        assert v0 == pytest.approx(v1, abs=1e-7 * (1 + abs(v0)))


def test_single_curve_segment_between_lines_is_quintic():
    """DG L4004: "If it connects adjacent tangent segments, then it will be calculated using a single 5'th order
    curve ... both the velocity and acceleration will match exactly at both ends of the segment."""
    pts = [FixPoint(0, 0, "T"), FixPoint(100, 100, "T"), FixPoint(300, 150, "T"), FixPoint(400, 150, "T")]
    curve = Curve("q", 400, pts, intervals=4)
    prof = profile(curve)
    assert prof.velocity(100.0) == pytest.approx(1.0) and prof.velocity(300.0) == pytest.approx(0.0, abs=1e-12)
    assert prof.one_sided(1, 2, False) == pytest.approx(0, abs=1e-12)
    assert prof.one_sided(1, 2, True) == pytest.approx(0, abs=1e-12)


def test_trapezoid_and_cubic_segments():
    """DG L4014-4020: CZ = two phases of constant acceleration, C3 = one 3rd-order segment."""
    for kind in ("CZ", "C3"):
        pts = [FixPoint(0, 0, "T"), FixPoint(100, 100, kind), FixPoint(300, 200, "T"), FixPoint(400, 200, "T")]
        curve = Curve("z", 400, pts, intervals=4)
        prof = profile(curve)
        assert prof.slave(300.0) == pytest.approx(200)
        assert prof.velocity(100.0) == pytest.approx(1.0) and prof.velocity(300.0) == pytest.approx(0, abs=1e-12)
        if kind == "CZ":
            acc = prof.acceleration(np.array([120.0, 180.0, 220.0, 280.0]))
            assert acc[0] == pytest.approx(acc[1]) and acc[2] == pytest.approx(acc[3])


def test_curvepos_example_passes_fix_points():
    """CR L685-712: fix points (0,0), (500,500), (700,300), (1000,1200) — the curve passes every fix point."""
    pts = [FixPoint(0, 0), FixPoint(500, 500), FixPoint(700, 300), FixPoint(1000, 1200)]
    curve = Curve("ex", 1000, pts, intervals=10)
    assert [slave(curve, p.master) for p in pts] == pytest.approx([0, 500, 300, 1200])
    assert velocity(curve, 0.0) == pytest.approx(velocity(curve, 999.999999), abs=1e-5)


@settings(max_examples=200, deadline=None)
@given(curves(), st.lists(st.floats(0.0, 1.0), max_size=30))
def test_evaluation_on_known_pieces_is_the_ppoly_evaluation(curve, fractions):
    """``at_pieces`` (the CAM diagram's samples of a dragged curve) gives exactly the numbers of the PPoly
    evaluation, for curves with trapezoid and motion-law pieces too."""
    prof = profile(curve)
    xs = np.unique(np.concatenate([prof.x, np.array(fractions) * curve.master_length]))
    below = np.searchsorted(prof.x, xs, side="right") - 1
    pieces = prof.pieces(xs, below)
    for nu in range(4):
        assert np.array_equal(prof.at_pieces(xs, pieces, nu), prof._eval(xs, nu, False))
