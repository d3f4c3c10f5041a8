"""camcurve.cubic builds the spline of a run of C points as scipy's CubicSpline does, bit for bit (the curves,
arrays and .zbc files stay exactly what they were), and refuses what CubicSpline refuses."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.interpolate import CubicSpline

from motiontool.camcurve import cubic

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
