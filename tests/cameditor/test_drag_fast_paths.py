"""The shortcuts a fix point drag takes (issue 6: recompute + redraw of a 10 000-point curve within a frame) give
exactly the results of the full computation: ``editing.move_point`` skips re-validating the unchanged points, and
``CurveProfile(moved_from=...)`` takes the segment kinds over from the curve before the move."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.camcurve.model import Curve, CurveError, CurveType, FixPoint
from motiontool.camcurve.spline import CurveProfile, curve_info
from motiontool.cameditor import editing
from tests.camcurve.strategies import curves


def _validated(curve: Curve) -> Curve:
    """The same field values through Curve's own constructor and validation."""
    return Curve(**{f.name: getattr(curve, f.name) for f in dataclasses.fields(Curve)})


def _same_profile(a: CurveProfile, b: CurveProfile) -> None:
    assert np.array_equal(a.ppoly.c, b.ppoly.c) and np.array_equal(a.ppoly.x, b.ppoly.x)
    assert (a.start_gradient_used, a.end_gradient_used) == (b.start_gradient_used, b.end_gradient_used)
    for nu in range(4):
        assert a.max_abs(nu) == b.max_abs(nu)


@settings(max_examples=150, deadline=None)
@given(curves(integral=True), st.data())
def test_a_moved_point_gives_the_validated_curve_and_the_full_profile(curve, data):
    index = data.draw(st.integers(0, len(curve.fix_points) - 1))
    master = data.draw(st.floats(-100, curve.master_length + 100, allow_nan=False))
    slave = data.draw(st.one_of(st.integers(-6000, 6000), st.floats(-6000, 6000, allow_nan=False)))
    clamp = data.draw(st.booleans())
    try:
        moved = editing.move_point(curve, index, master, slave, clamp=clamp)
    except CurveError:
        return  # refused before any curve is built, as before
    assert moved == _validated(moved)  # what validation would accept, field for field
    try:
        before = CurveProfile(curve)
    except CurveError:
        return
    _same_profile(CurveProfile(moved, moved_from=(before, index)), CurveProfile(_validated(moved)))


def test_a_value_validation_refuses_still_goes_through_validation():
    """Only plain ints and floats take the shortcut; anything else meets Curve.validate as before."""
    curve = Curve("c", 300, (FixPoint(0, 0), FixPoint(100, 50), FixPoint(300, 80)), interpolation=False)
    with pytest.raises(CurveError, match="finite number"):
        editing.move_point(curve, 1, 150, np.float32(12.5))


@pytest.mark.parametrize("curve_type", list(CurveType))
def test_dragging_through_a_long_curve_matches_full_recomputes(curve_type):
    """Drag moves one after another, each profile built from the previous one: the same spline and Curve Info as
    a profile built from scratch."""
    rng = np.random.default_rng(7)
    n = 600
    types = ["C"] * n
    for k in range(40, n - 40, 50):  # straight sections of all closing kinds in between
        types[k], types[k + 1] = "T", "T"
        if k % 100 == 40:
            types[k + 1], types[k + 2], types[k + 3] = "CZ", "T", "T"
    points = tuple(FixPoint(10 * k, int(v), t) for k, (v, t) in
                   enumerate(zip(np.cumsum(rng.normal(0, 4, n)), types, strict=True)))
    curve = Curve("long", 10 * (n - 1), points, interpolation=False, curve_type=curve_type, start_gradient=0.5,
                  end_gradient=-0.25)
    prof = CurveProfile(curve)
    for index, (dm, ds) in ((300, (3, 17)), (300, (-4, -30)), (0, (0, 9)), (41, (2, 5)), (n - 1, (0, -12))):
        p = curve.fix_points[index]
        curve = editing.move_point(curve, index, p.master + dm, p.slave + ds, clamp=True)
        prof = CurveProfile(curve, moved_from=(prof, index))
        fresh = CurveProfile(_validated(curve))
        _same_profile(prof, fresh)
        assert np.array_equal(prof.slave(fresh.x, periodic=False), fresh.slave(fresh.x, periodic=False))
        assert curve_info(curve) == curve_info(_validated(curve))
