"""CurveProfile.max_abs (Curve Info maxima, DG L3807-3823) is exact: never below a dense sampling of the
derivative and attained at some point of the cycle."""

import numpy as np
from hypothesis import given, settings

from motiontool.camcurve.spline import profile
from tests.camcurve.strategies import curves


@settings(max_examples=60, deadline=None)
@given(curves())
def test_max_abs_bounds_and_is_attained(curve):
    prof = profile(curve)
    xs = np.linspace(0.0, curve.master_length, 4001)
    breaks = prof.ppoly.x
    for nu in (1, 2, 3):
        exact = prof.max_abs(nu)
        sampled = np.abs(prof._eval(xs, nu, False))
        scale = max(1.0, exact)
        assert exact >= np.max(sampled) - 1e-9 * scale
        # attained: a dense sampling inside each piece comes close (one-sided values at the piece ends included)
        dense = 0.0
        for i in range(len(breaks) - 1):
            t = np.linspace(0.0, breaks[i + 1] - breaks[i], 401)
            poly = np.polyder(np.poly1d(prof.ppoly.c[:, i]), nu)
            dense = max(dense, float(np.max(np.abs(poly(t)))))
        assert exact <= dense * (1 + 1e-4) + 1e-9 * scale
