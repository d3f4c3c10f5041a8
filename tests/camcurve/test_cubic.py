"""camcurve.cubic builds the spline of a run of C points as scipy's CubicSpline does, bit for bit (the curves,
arrays and .zbc files stay exactly what they were), and refuses what CubicSpline refuses."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.interpolate import CubicSpline, PPoly

from motiontool.camcurve import cubic
from motiontool.camcurve.spline import CurveProfile
from tests.camcurve.strategies import curves

_ends = st.one_of(st.none(), st.floats(-50, 50, allow_nan=False))


@st.composite
def runs(draw):
    n = draw(st.integers(2, 40))
    steps = draw(st.lists(st.floats(1e-3, 1e4, allow_nan=False), min_size=n - 1, max_size=n - 1))
    xs = np.concatenate([[draw(st.floats(-1e4, 1e4))], np.zeros(n - 1)])
    xs[1:] = xs[0] + np.cumsum(steps)
    ys = np.array(draw(st.lists(st.floats(-1e6, 1e6, allow_nan=False), min_size=n, max_size=n)))
    return xs, ys


@settings(max_examples=300, deadline=None)
@given(runs(), _ends, _ends)
def test_bit_identical_to_scipy(run, left, right):
    xs, ys = run
    if not (np.diff(xs) > 0).all():
        return  # rounding made two steps collapse
    bc = ((2, 0.0) if left is None else (1, left), (2, 0.0) if right is None else (1, right))
    reference = CubicSpline(xs, ys, bc_type=bc)
    c = cubic.coefficients(xs, ys, left, right)
    assert np.array_equal(c, reference.c)
    assert cubic.slope_at(c, xs, 0, xs[0]) == reference(xs[0], 1)
    assert cubic.slope_at(c, xs, len(xs) - 2, xs[-1]) == reference(xs[-1], 1)
    assert cubic.slope_at(c, xs, 0, xs[0] - 7.0) == reference(xs[0] - 7.0, 1)  # extrapolated as the PPoly does


def test_refuses_what_scipy_refuses():
    with pytest.raises(ValueError, match="strictly increasing"):
        cubic.coefficients(np.array([0.0, 1.0, 1.0]), np.array([0.0, 1.0, 2.0]), None, None)
    with pytest.raises(ValueError, match="finite"):
        cubic.coefficients(np.array([0.0, 1.0, 2.0]), np.array([0.0, np.nan, 2.0]), None, 1.0)
    with pytest.raises(ValueError, match="finite"):
        cubic.coefficients(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 2.0]), np.inf, None)


def _scipy_coefficients(xs, ys, left, right):
    bc = ((2, 0.0) if left is None else (1, left), (2, 0.0) if right is None else (1, right))
    return CubicSpline(xs, ys, bc_type=bc).c


def _scipy_slope_at(c, xs, piece, x):
    return float(PPoly(c, xs)(x, 1))  # the whole run's PPoly, as the profile evaluated it with CubicSpline


@settings(max_examples=150, deadline=None)
@given(curves())
def test_whole_profiles_are_what_they_were_with_scipys_cubic_spline(curve):
    """The profile built on camcurve.cubic equals, number for number, the one built on scipy's CubicSpline
    (coefficients, breakpoints, the gradients the curve type chose, and the Curve Info maxima)."""
    ours = CurveProfile(curve)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(cubic, "coefficients", _scipy_coefficients)
        mp.setattr(cubic, "slope_at", _scipy_slope_at)
        reference = CurveProfile(curve)
    assert np.array_equal(ours.ppoly.c, reference.ppoly.c) and np.array_equal(ours.ppoly.x, reference.ppoly.x)
    assert (ours.start_gradient_used, ours.end_gradient_used) == (reference.start_gradient_used,
                                                                  reference.end_gradient_used)
    for nu in range(4):
        assert ours.max_abs(nu) == reference.max_abs(nu)
