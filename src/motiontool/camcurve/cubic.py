"""The cubic spline through one run of curved fix points, clamped (given slope) or natural at each end.

Computed as scipy's ``CubicSpline(xs, ys, bc_type=...)`` computes it: the same tridiagonal system for the
slopes, solved by the same LAPACK routine (gtsv, what ``solve_banded`` calls for one band each side), and the
same Hermite coefficients, so the numbers are bit-identical.  What is left out is what costs time on a
10 000-point curve rebuilt on every mouse move of a drag: scipy's input conversion and checks (our caller
checks ordering and finiteness once), the PPoly object and its copies.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import PPoly
from scipy.linalg import LinAlgError
from scipy.linalg.lapack import dgtsv


def coefficients(xs: np.ndarray, ys: np.ndarray, left: float | None, right: float | None) -> np.ndarray:
    """Piece coefficients (4, len(xs) - 1), descending powers in local x, as ``CubicSpline(...).c``.

    ``left`` / ``right``: None = natural end (second derivative 0), a number = clamped slope.  xs strictly
    increasing, at least two points, everything finite (raises ValueError otherwise, as scipy does)."""
    n = len(xs)
    dx = np.diff(xs)
    if n < 2 or not (dx > 0).all():
        raise ValueError("`x` must be strictly increasing sequence.")
    if not (np.isfinite(xs).all() and np.isfinite(ys).all()):
        raise ValueError("`x` and `y` must contain only finite values.")
    if not all(math.isfinite(end) for end in (left, right) if end is not None):
        raise ValueError("the end slopes must be finite values.")
    slope = np.diff(ys) / dx
    # the system for the slopes s[0..n-1], rows as in scipy's CubicSpline (sub-, main and super-diagonal)
    sub = np.empty(n - 1)
    diag = np.empty(n)
    sup = np.empty(n - 1)
    rhs = np.empty(n)
    diag[1:-1] = 2 * (dx[:-1] + dx[1:])
    sup[1:] = dx[:-1]
    sub[:-1] = dx[1:]
    rhs[1:-1] = 3 * (dx[1:] * slope[:-1] + dx[:-1] * slope[1:])
    if left is None:
        diag[0], sup[0], rhs[0] = 2 * dx[0], dx[0], 3 * (ys[1] - ys[0])  # scipy adds -0.5·0·dx²: exactly 0
    else:
        diag[0], sup[0], rhs[0] = 1.0, 0.0, left
    if right is None:
        diag[-1], sub[-1], rhs[-1] = 2 * dx[-1], dx[-1], 3 * (ys[-1] - ys[-2])
    else:
        diag[-1], sub[-1], rhs[-1] = 1.0, 0.0, right
    *_, s, info = dgtsv(sub, diag, sup, rhs, 1, 1, 1, 1)
    if info > 0:
        raise LinAlgError("singular matrix")
    t = (s[:-1] + s[1:] - 2 * slope) / dx
    return np.stack((t / dx, (slope - s[:-1]) / dx - t, s[:-1], ys[:-1]))


def slope_at(c: np.ndarray, xs: np.ndarray, piece: int, x: float) -> float:
    """The first derivative at x of piece ``piece`` (evaluated as the whole spline's PPoly would)."""
    return float(PPoly(c[:, piece:piece + 1], xs[piece:piece + 2])(x, 1))
