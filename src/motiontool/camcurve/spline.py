"""Curve maths: the slave position as a piecewise polynomial of the master position.

The CAM editor "calculates the curve from Fix points with the help of a spline interpolation. This is optimized
to a minimum torque. In order to prevent speed leaps in the case of repeated curve cycles, the velocity at the
beginning and the end is equated." [DG L1356-1358].  Segment shapes [DG L3998-4022, ide-spec 4.35-4.37]:

* straight (a T point and the next T/CZ/C3 point): a line, constant velocity, zero acceleration;
* a run of consecutive curved (C) segments: ONE cubic spline through the run's points (camcurve.cubic, the
  numbers of scipy's CubicSpline).
  Where the run borders a straight section its end is clamped to the line's slope, so velocity is continuous
  (C1) into the line; at the profile start/end the Type-of-Curve rule gives the boundary condition
  (``_boundary_gradients``);
* a single curved segment between two straight sections: the 5th-order Hermite polynomial matching position and
  slope at both ends with zero acceleration there ("both the velocity and acceleration will match" [DG L4004]);
* CZ: trapezoidal velocity (two constant-acceleration halves), C3: the cubic Hermite segment;
* a motion-law point (P345, MSIN, CYCL, MTRAP, HARM; beyond the manual): the segment ending there follows the
  VDI 2143 law, as quintic pieces from camcurve.motionlaws; its neighbours are clamped to gradient 0 there.

The whole profile is one scipy PPoly (degree 5, extra breakpoint in the middle of CZ segments), so every
quantity is vectorised over numpy arrays.  Outside 0..master_length the profile repeats cyclically, the slave
advancing by one slave length per cycle (the controller restarts the curve at the end of every cycle).

Velocity is dy/dx in UU/MU, acceleration d²y/dx² in UU/MU², jerk d³y/dx³ in UU/MU³ (ide-spec 4.37).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PPoly

from motiontool.camcurve import cubic, motionlaws
from motiontool.camcurve.model import CUBIC, LAW, LINE, SPLINE, TRAPEZOID, Curve, CurveType, StartStopPair

_DEGREE = 5
_KIND_CODES = {LINE: 0, SPLINE: 1, TRAPEZOID: 2, CUBIC: 3, LAW: 4}


def _column(ascending: list[float]) -> np.ndarray:
    """Local polynomial coefficients (ascending powers) as a PPoly column (descending, padded to degree 5)."""
    col = np.zeros(_DEGREE + 1)
    for power, value in enumerate(ascending):
        col[_DEGREE - power] = value
    return col


def _quintic(h: float, y0: float, v0: float, y1: float, v1: float) -> list[float]:
    """Hermite quintic on [0, h]: position and slope at both ends, zero second derivative at both ends."""
    a = np.array([[h ** 3, h ** 4, h ** 5], [3 * h ** 2, 4 * h ** 3, 5 * h ** 4], [6 * h, 12 * h ** 2, 20 * h ** 3]])
    c3, c4, c5 = np.linalg.solve(a, [y1 - y0 - v0 * h, v1 - v0, 0.0])
    return [y0, v0, 0.0, c3, c4, c5]


def _cubic(h: float, y0: float, v0: float, y1: float, v1: float) -> list[float]:
    """Cubic Hermite on [0, h] (fix point type C3)."""
    m = (y1 - y0) / h
    return [y0, v0, (3 * m - 2 * v0 - v1) / h, (v0 + v1 - 2 * m) / h ** 2]


def _trapezoid(h: float, y0: float, v0: float, y1: float, v1: float) -> tuple[list[float], list[float]]:
    """CZ: velocity linear v0 → vm over the first half and vm → v1 over the second; vm = (4Δy/h − v0 − v1)/2."""
    half = h / 2
    vm = (4 * (y1 - y0) / h - v0 - v1) / 2
    ym = y0 + (v0 + vm) / 2 * half
    return [y0, v0, (vm - v0) / half / 2], [ym, vm, (v1 - vm) / half / 2]


def _spline(xs: np.ndarray, ys: np.ndarray, left: float | None, right: float | None) -> np.ndarray:
    """Cubic spline through a run, as piece coefficients (4, pieces); None = natural end (zero second
    derivative), a number = clamped slope."""
    return cubic.coefficients(xs, ys, None if left is None else float(left), None if right is None else float(right))


def _start_slope(xs: np.ndarray, c: np.ndarray) -> float:
    return cubic.slope_at(c, xs, 0, xs[0])


class CurveProfile:
    """The evaluated profile of one Curve.  Build once (``profile(curve)`` caches), evaluate many times."""

    kind_codes: np.ndarray   # each segment's kind (_KIND_CODES), taken over by a dragged copy

    def __init__(self, curve: Curve, moved_from: tuple[CurveProfile, int] | None = None) -> None:
        """``moved_from`` = (profile, index): the profile of a curve that differs from ``curve`` only in the
        position of fix point ``index`` (a drag); its point types, and so the segment kinds, are taken over."""
        self.curve = curve
        n = len(curve.fix_points)
        if moved_from is None:
            self.kinds = curve.segment_kinds
            self.x = np.array([p.master for p in curve.fix_points], dtype=float)
            self.y = np.array([p.slave for p in curve.fix_points], dtype=float)
            kind_codes = np.fromiter(map(_KIND_CODES.__getitem__, self.kinds), dtype=np.int8, count=n - 1)
        else:
            base, index = moved_from
            self.kinds, kind_codes = base.kinds, base.kind_codes
            self.x, self.y = base.x.copy(), base.y.copy()
            self.x[index], self.y[index] = curve.fix_points[index].master, curve.fix_points[index].slave
        self.kind_codes = kind_codes
        self.line_segments = kind_codes == _KIND_CODES[LINE]  # straight segments (T to T, CZ or C3)
        h = np.diff(self.x)
        self.line_slopes = {int(k): (self.y[k + 1] - self.y[k]) / h[k] for k in np.nonzero(self.line_segments)[0]}
        laws = np.nonzero(kind_codes == _KIND_CODES[LAW])[0]
        self.line_slopes.update(dict.fromkeys(map(int, laws), 0.0))  # a law meets its neighbours at rest
        self.runs = self._spline_runs(kind_codes == _KIND_CODES[SPLINE])
        gs, ge = self._boundary_gradients()
        self.start_gradient_used, self.end_gradient_used = gs, ge
        splines = {run[0]: self._run_spline(run, gs, ge) for run in self.runs}
        quintic_runs = {run[0] for run in self.runs if self._is_quintic(run)}
        # piece p of the PPoly: segment k is piece k + (trapezoids before k); a trapezoid is two pieces
        trapezoid = kind_codes == _KIND_CODES[TRAPEZOID]
        piece = np.arange(n - 1) + np.concatenate([[0], np.cumsum(trapezoid)[:-1]])
        coeffs = np.zeros((_DEGREE + 1, n - 1 + int(trapezoid.sum())))
        breaks = np.empty(coeffs.shape[1] + 1)
        breaks[piece] = self.x[:-1]
        breaks[-1] = self.x[-1]
        contiguous = not trapezoid.any()  # then piece k is segment k: slices instead of gathers
        for first, cs in splines.items():  # whole spline runs at once (a curve may have 10 000 points)
            if first not in quintic_runs:
                cols = slice(first, first + cs.shape[1]) if contiguous else piece[first:first + cs.shape[1]]
                coeffs[_DEGREE - 3:, cols] = cs
        quintic = np.zeros(n - 1, dtype=bool)
        quintic[list(quintic_runs)] = True
        for k in map(int, np.nonzero((kind_codes != _KIND_CODES[SPLINE]) | quintic)[0]):
            kind, p = self.kinds[k], piece[k]
            y0, y1, hk = self.y[k], self.y[k + 1], h[k]
            if kind == LINE:
                coeffs[:, p] = _column([y0, self.line_slopes[k]])
            elif kind == SPLINE:
                coeffs[:, p] = _column(_quintic(hk, y0, self.line_slopes[k - 1], y1, self.line_slopes[k + 1]))
            elif kind == CUBIC:
                coeffs[:, p] = _column(_cubic(hk, y0, self.line_slopes[k - 1], y1, self.line_slopes[k + 1]))
            elif kind == LAW:  # replaced by the law's pieces below
                continue
            else:
                assert kind == TRAPEZOID, kind
                rise, fall = _trapezoid(hk, y0, self.line_slopes[k - 1], y1, self.line_slopes[k + 1])
                coeffs[:, p], coeffs[:, p + 1] = _column(rise), _column(fall)
                breaks[p + 1] = self.x[k] + hk / 2
        if len(laws):  # motion-law segments (camcurve.motionlaws): quintic pieces of the law
            coeffs, breaks = motionlaws.splice(coeffs, breaks, [(int(piece[k]), curve.fix_points[k + 1].type,
                                                                 self.y[k], self.y[k + 1]) for k in laws])
        self.ppoly = PPoly(coeffs, breaks, extrapolate=True)
        self._derivatives: list[PPoly | None] = [self.ppoly, None, None, None]  # made when first asked
        self._ascending: tuple[np.ndarray, np.ndarray] | None = None  # see max_abs

    # -- construction helpers ---------------------------------------------------------------------------------
    @staticmethod
    def _spline_runs(spline: np.ndarray) -> list[range]:
        """Maximal runs of consecutive spline segments (their indices), from the mask of spline segments."""
        edges = np.diff(np.concatenate([[0], spline.astype(np.int8), [0]]))
        return [range(int(a), int(b)) for a, b in zip(np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0],
                                                      strict=True)]

    def _is_quintic(self, run: range) -> bool:
        return len(run) == 1 and run[0] - 1 in self.line_slopes and run[0] + 1 in self.line_slopes

    def _run_bc(self, run: range, gs: float | None, ge: float | None) -> tuple[float | None, float | None]:
        left = self.line_slopes.get(run[0] - 1, gs) if run[0] > 0 else gs
        right = self.line_slopes.get(run[-1] + 1, ge) if run[-1] < len(self.kinds) - 1 else ge
        return left, right

    def _run_points(self, run: range) -> tuple[np.ndarray, np.ndarray]:
        return self.x[run[0]:run[-1] + 2], self.y[run[0]:run[-1] + 2]

    def _run_spline(self, run: range, gs: float | None, ge: float | None) -> np.ndarray:
        return _spline(*self._run_points(run), *self._run_bc(run, gs, ge))

    def _natural_end_slopes(self) -> tuple[float, float]:
        """Slopes at the profile start/end when those ends are left natural (zero curvature)."""
        first, last = self.runs[0], self.runs[-1]
        spline_first = self._run_spline(first, None, None)
        spline_last = spline_first if last is first else self._run_spline(last, None, None)  # one run: one solve
        xs_last = self._run_points(last)[0]
        # evaluated at the profile's ends, also when a run starts later or ends earlier (extrapolated)
        return (cubic.slope_at(spline_first, self._run_points(first)[0], 0, self.x[0]),
                cubic.slope_at(spline_last, xs_last, len(xs_last) - 2, self.x[-1]))

    def _boundary_gradients(self) -> tuple[float | None, float | None]:
        """Gradient imposed on a curved first/last segment by the Type of Curve [DG L3708-3729].

        * AVERAGE_GRADIENTS: both free ends get the mean of their natural-spline slopes; an end that is a
          straight line keeps its slope and the other end takes it (the only way to avoid a velocity leap);
        * END_EQUALS_START: the start is natural (or the line's slope); the end is clamped to that gradient.
          When one spline run spans the whole profile the start slope depends on the end slope linearly, so the
          fixed point g = s0(g) is solved exactly from two evaluations;
        * ZERO_GRADIENTS: both 0;  SPECIFIED_*: the user's start_gradient / end_gradient.
        """
        c = self.curve
        ctype = c.curve_type
        if ctype == CurveType.ZERO_GRADIENTS:
            return 0.0, 0.0
        if ctype in (CurveType.SPECIFIED_GRADIENTS, CurveType.SPECIFIED_IMMEDIATE):
            return float(c.start_gradient), float(c.end_gradient)
        last_k = len(self.kinds) - 1
        start_line = self.line_slopes.get(0)
        end_line = self.line_slopes.get(last_k)
        if start_line is not None and end_line is not None:
            return None, None
        if ctype == CurveType.AVERAGE_GRADIENTS:
            if start_line is not None:
                return None, start_line
            if end_line is not None:
                return end_line, None
            s0, s1 = self._natural_end_slopes()
            g = (s0 + s1) / 2
            return g, g
        # END_EQUALS_START
        if start_line is not None:
            return None, start_line
        first = self.runs[0]
        xs, ys = self._run_points(first)
        if first[-1] == last_k:  # one run from start to end: solve g = s0(g), s0 affine in g
            a = _start_slope(xs, _spline(xs, ys, None, 0.0))
            b = _start_slope(xs, _spline(xs, ys, None, 1.0)) - a
            g = a / (1.0 - b) if abs(1.0 - b) > 1e-12 else a
            return g, g
        g = _start_slope(xs, _spline(xs, ys, None, self._run_bc(first, None, None)[1]))
        return g, g

    # -- evaluation -------------------------------------------------------------------------------------------
    def _eval(self, master, nu: int, periodic: bool):
        x = np.asarray(master, dtype=float)
        length = self.curve.master_length
        if periodic:
            cycles = np.floor(x / length)
            xr = np.clip(x - cycles * length, 0.0, length)
        else:
            cycles, xr = np.zeros_like(x), x
        derivative = self._derivatives[nu]
        if derivative is None:
            derivative = self._derivatives[nu] = self.ppoly.derivative(nu)
        out = derivative(xr)
        if nu == 0:
            out = out + cycles * self.curve.slave_length
        return float(out) if np.ndim(out) == 0 else out

    def pieces(self, xs: np.ndarray, below: np.ndarray) -> np.ndarray:
        """The PPoly piece the evaluation uses for each master position of ``xs`` (sorted, within the cycle),
        given ``below``: the last fix point at or before each position (-1 before the first)."""
        breaks = self.ppoly.x
        if len(breaks) == len(self.x) and np.array_equal(breaks, self.x):  # no extra trapezoid or law pieces
            return np.clip(below, 0, len(breaks) - 2)
        return np.clip(np.searchsorted(breaks, xs, side="right") - 1, 0, len(breaks) - 2)

    def at_pieces(self, xs: np.ndarray, pieces: np.ndarray, nu: int) -> np.ndarray:
        """Derivative nu at the master positions xs of the given pieces (see ``pieces``): the numbers of
        ``_eval(xs, nu, periodic=False)``, summed in the same order as scipy's PPoly evaluation, without its
        search for every position's piece (the diagram evaluates 11 600 samples of a dragged curve twice)."""
        derivative = self._derivatives[nu]
        if derivative is None:
            derivative = self._derivatives[nu] = self.ppoly.derivative(nu)
        c = derivative.c
        s = xs - derivative.x[pieces]
        out, power = np.zeros(len(xs)), np.ones(len(xs))
        for k in range(len(c) - 1, -1, -1):  # ascending powers: out += c_k · s^k
            out = out + c[k][pieces] * power
            if k:
                power = power * s
        return out + np.zeros(len(xs)) * self.curve.slave_length if nu == 0 else out  # as _eval adds 0 cycles

    def slave(self, master, periodic: bool = True):
        """CURVEPOS: slave position [UU] at curve-master position(s) [MU]."""
        return self._eval(master, 0, periodic)

    def velocity(self, master, periodic: bool = True):
        """Slave velocity dy/dx [UU/MU]."""
        return self._eval(master, 1, periodic)

    def acceleration(self, master, periodic: bool = True):
        """Slave acceleration d²y/dx² [UU/MU²]."""
        return self._eval(master, 2, periodic)

    def jerk(self, master, periodic: bool = True):
        """Slave jerk d³y/dx³ [UU/MU³]."""
        return self._eval(master, 3, periodic)

    def one_sided(self, piece: int, nu: int, at_end: bool) -> float:
        """Value of derivative nu of PPoly piece ``piece`` at its start or end (one-sided limit)."""
        col = np.poly1d(self.ppoly.c[:, piece])
        h = self.ppoly.x[piece + 1] - self.ppoly.x[piece]
        return float(np.polyder(col, nu)(h if at_end else 0.0)) if nu else float(col(h if at_end else 0.0))

    def max_abs(self, nu: int) -> float:
        """Exact maximum of |derivative nu| over one cycle: piece ends and interior stationary points.

        Vectorised over all pieces (a 10 000-point curve is recomputed while a point is dragged): the stationary
        points are the real roots of derivative nu+1, found per piece from batched companion matrices grouped by
        the polynomial's actual degree."""
        if self._ascending is None:  # shared by the maxima of all derivatives (Curve Info asks for three)
            asc = self.ppoly.c[::-1]  # ascending powers, shape (degree+1, pieces)
            used = np.flatnonzero(asc.any(axis=1))
            asc = asc[:used[-1] + 1] if len(used) else asc[:1]  # powers no piece uses (a cubic's 4, 5) add 0
            self._ascending = (np.ascontiguousarray(asc), np.diff(self.ppoly.x))
        asc, h = self._ascending
        deriv = _derive(asc, nu)
        slope = _derive(deriv, 1)
        best = float(np.max(np.abs(deriv[0]), initial=0.0))  # at each piece's start: its constant term
        for t in (h, *np.ascontiguousarray(_roots_in(slope, h).T)):  # its end, its stationary points (0: none)
            best = max(best, float(np.max(np.abs(_horner(deriv, t)), initial=0.0)))
        return best


def _derive(asc: np.ndarray, nu: int) -> np.ndarray:
    """Coefficients (ascending, per column) of the nu-th derivative."""
    out = asc
    for _ in range(nu):
        if len(out) <= 1:
            return np.zeros((1, asc.shape[1]))
        out = out[1:] * np.arange(1, len(out))[:, None]
    return out


def _horner(asc: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Evaluate each piece's polynomial (column of asc) at its point t (one per piece)."""
    out = np.zeros_like(t)
    for a in asc[::-1]:
        out = out * t + a
    return out


def _roots_in(asc: np.ndarray, h: np.ndarray) -> np.ndarray:
    """Real roots inside (0, h) of each piece's polynomial, padded with 0 (an end point anyway)."""
    pieces, width = asc.shape[1], max(len(asc) - 1, 1)
    out = np.zeros((pieces, width))
    nonzero = asc != 0
    degree = np.where(nonzero.any(axis=0), len(asc) - 1 - np.argmax(nonzero[::-1], axis=0), 0)
    for g in range(1, len(asc)):
        found = np.nonzero(degree == g)[0]
        if not len(found):
            continue
        # every piece of this degree (a long spline): slices instead of gathers
        idx: slice | np.ndarray = slice(None) if len(found) == pieces else found
        coeffs = asc[:g + 1, idx]
        monic = coeffs[:g] / coeffs[g]
        if g == 1:  # the 1×1 companion matrix [-monic] is its own eigenvalue (LAPACK returns it exactly)
            real = -monic.T
            ok = (real > 0) & (real < h[idx, None])  # real: no imaginary part to test
        else:
            companion = np.zeros((coeffs.shape[1], g, g))
            companion[:, np.arange(1, g), np.arange(g - 1)] = 1.0
            companion[:, :, -1] = -monic.T
            roots = np.linalg.eigvals(companion)
            real = roots.real
            ok = (np.abs(roots.imag) <= 1e-9 * (1.0 + np.abs(real))) & (real > 0) & (real < h[idx, None])
        out[idx, :g] = np.where(ok, real, 0.0)
    return out


@functools.lru_cache(maxsize=128)
def _cached_profile(curve: Curve) -> CurveProfile:
    return CurveProfile(curve)


_last: tuple[Curve | None, CurveProfile | None] = (None, None)


def profile(curve: Curve, cache: bool = True, moved_from: tuple[CurveProfile, int] | None = None) -> CurveProfile:
    """The (cached) evaluated profile of a curve.  The same object asked again skips hashing its fix points
    (the editor asks several times per redraw of a long curve); one tuple swap keeps this thread-safe.

    ``cache=False`` is for a curve that is asked about only while it exists, such as each intermediate curve of
    a fix point drag: it is built without hashing its fix points into the shared cache (a few ms for 10 000
    points), and remembered only as the last curve asked; ``moved_from`` as for CurveProfile."""
    global _last
    last = _last
    if last[0] is curve and last[1] is not None:   # set together: a curve is never without its profile
        return last[1]
    prof = _cached_profile(curve) if cache else CurveProfile(curve, moved_from)
    _last = (curve, prof)
    return prof


def slave(curve: Curve, master):
    return profile(curve).slave(master)


def velocity(curve: Curve, master):
    return profile(curve).velocity(master)


def acceleration(curve: Curve, master):
    return profile(curve).acceleration(master)


def jerk(curve: Curve, master):
    return profile(curve).jerk(master)


def round_half_up(values) -> list[int]:
    """Round to the nearest integer, halves towards +infinity (how we store positions in the array)."""
    return [int(v) for v in np.floor(np.asarray(values, dtype=float) + 0.5)]


def grid_positions(curve: Curve) -> np.ndarray:
    """The N+1 equidistant master positions of the interpolation grid (first and last included)."""
    return np.arange(curve.intervals + 1) * curve.interval_size


def interpolation_points(curve: Curve) -> list[int]:
    """Slave values at the N+1 grid positions, rounded to integers as the controller stores them [DG L1366]."""
    return round_half_up(profile(curve).slave(grid_positions(curve), periodic=False))


# -- curve info --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CurveInfo:
    """Values of the Curve Info card [DG L3799-3839, ide-spec 4.49-4.54]."""

    max_velocity: float  # UU/MU
    max_acceleration: float  # UU/MU²
    max_jerk: float  # UU/MU³
    interval_size: float  # MU
    interval_time_ms: float  # ms
    master_velocity: float  # MU/s at cycles_per_min
    max_velocity_per_s: float  # UU/s
    max_acceleration_per_s2: float  # UU/s²


def curve_info(curve: Curve) -> CurveInfo:
    prof = profile(curve)
    master_velocity = curve.master_length * curve.cycles_per_min / 60.0
    vmax, amax = prof.max_abs(1), prof.max_abs(2)
    return CurveInfo(vmax, amax, prof.max_abs(3), curve.interval_size, curve.interval_time_ms, master_velocity,
                     vmax * master_velocity, amax * master_velocity ** 2)


def slave_velocity_limit(velmax_rpm: float, qc_per_rev: float, qc_per_uu: float, master_length: float,
                         cycles_per_min: float) -> float:
    """Slave velocity limit [UU/MU] (ide-spec 4.51, DERIVED): VELMAX·qc/rev / (qc/UU · L · cycles/min)."""
    return velmax_rpm * qc_per_rev / (qc_per_uu * master_length * cycles_per_min)


def slave_acceleration_limit(velmax_rpm: float, qc_per_rev: float, qc_per_uu: float, rampmin_s: float,
                             master_length: float, cycles_per_min: float) -> float:
    """Slave acceleration limit [UU/MU²] (ide-spec 4.53, DERIVED)."""
    acc_uu_s2 = velmax_rpm / 60.0 * qc_per_rev / qc_per_uu / rampmin_s
    return acc_uu_s2 / (master_length * cycles_per_min / 60.0) ** 2


# -- engage / disengage paths -----------------------------------------------------------------------------------
def blend(u):
    """Quintic smoothstep w(u) = 10u³ − 15u⁴ + 6u⁵: w(0)=0, w(1)=1, w' and w'' zero at both ends."""
    u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
    return u ** 3 * (10 - 15 * u + 6 * u ** 2)


def path_point_count(curve: Curve, span: float) -> int:
    """Points of a path over ``span`` MU: one per grid interval plus one, at least 2 (docs/formats/cam-array.md)."""
    return max(2, int(math.floor(span / curve.interval_size + 1e-9)) + 1)


def _path(curve: Curve, pair: StartStopPair | int, slave_stop: float | None, points: int | None,
          engage: bool) -> tuple[np.ndarray, np.ndarray]:
    if isinstance(pair, int):
        pair = curve.start_stop_pairs[pair]
    stop_pos = curve.slave_stop_position if slave_stop is None else slave_stop
    span = pair.stop - pair.start
    if span < 0:
        span += curve.master_length
    if span == 0:  # Start = Stop: engage at maximum velocity, no path [DG L4050]
        return np.array([float(pair.start)]), np.array([float(stop_pos)])
    n = points or path_point_count(curve, span)
    u = np.linspace(0.0, 1.0, n)
    xs = pair.start + u * span
    on_curve = profile(curve).slave(xs)
    w = blend(u) if engage else 1.0 - blend(u)
    return xs, stop_pos + w * (on_curve - stop_pos)


def engage_path(curve: Curve, pair: StartStopPair | int, slave_stop: float | None = None,
                points: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Engage path (forward): from the slave stop position at rest at Start onto the profile at Stop.

    y(x) = s + w(u)·(f(x) − s), u = (x − Start)/span: y = s and y' = 0 at Start, y = f and y' = f' (and y'' = f'')
    at Stop.  Start > Stop wraps around the cycle (master positions beyond the cycle end are returned).
    """
    return _path(curve, pair, slave_stop, points, engage=True)


def disengage_path(curve: Curve, pair: StartStopPair | int, slave_stop: float | None = None,
                   points: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Disengage path (forward): leaves the profile at Start with its velocity, at rest at the stop position at Stop."""
    return _path(curve, pair, slave_stop, points, engage=False)
