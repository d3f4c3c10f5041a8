"""Standard rest-to-rest motion laws (VDI 2143) for CAM segments, Qt-free.

Beyond the manual (issue 6, item 5): besides the editor's spline, a segment between two fix points may follow
one of the normalised laws below.  The law is carried by the segment's **end point**, as a fix point type of
its own (``FixPoint(master, slave, "CYCL")`` makes the segment arriving at that point a cycloid; decision C10);
the segment leaving a law point is shaped as if the point were a C point.

Every law is given normalised on u ∈ [0, 1] (``s(0) = 0``, ``s(1) = 1``, ``s'(0) = s'(1) = 0``) with its
derivatives s', s'', s''' — vectorised over numpy arrays.  A segment from (x0, y0) to (x1, y1), h = x1 − x0,
is y(x) = y0 + (y1 − y0)·s((x − x0)/h); its velocity is (y1 − y0)/h·s', acceleration (y1 − y0)/h²·s'', jerk
(y1 − y0)/h³·s'''.

The profile (camcurve.spline) is one piecewise polynomial of degree 5 that the controller kernel evaluates
directly, so a law segment enters it as quintic Hermite pieces (position, velocity and acceleration of the law
matched at both ends of every piece; ``pieces`` per segment, aligned with the law's own break points): exact for
the 3-4-5 polynomial (one piece); for the other laws (32 pieces) the normalised position is within 1e-8,
velocity within 1e-6, acceleration within 1e-4 and jerk within 0.1 % of its peak (decision C11,
tests/camcurve/test_motionlaws.py).

Peak coefficients Cv = max s', Ca = max |s''| (textbook values, e.g. Norton "Cam Design and Manufacturing
Handbook" table 3-2 / VDI 2143): 3-4-5 1.875 / 5.774, cycloid 2 / 6.283, modified sine 1.760 / 5.528, modified
trapezoid 2 / 4.888, simple harmonic 1.571 / 4.935.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

_PI = math.pi


@dataclass(frozen=True)
class _SinePiece:
    """Acceleration c0 + c1·sin(ω(u − φ)) on [ua, ub] (before normalisation)."""

    ua: float
    ub: float
    c0: float
    c1: float
    omega: float
    phi: float


@dataclass(frozen=True)
class MotionLaw:
    """One normalised rest-to-rest law."""

    code: str  # the fix point type
    name: str  # shown in the editor's popup
    pieces: int  # quintic pieces per segment in the profile
    _sine: tuple[_SinePiece, ...] = ()

    def __call__(self, u, nu: int = 0):
        """d^nu s / du^nu at u (u clipped to [0, 1]); nu in 0..3."""
        u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
        out = _poly345(u, nu) if not self._sine else self._sine_eval(u, nu)
        return float(out) if np.ndim(out) == 0 else out

    def _sine_eval(self, u: np.ndarray, nu: int) -> np.ndarray:
        table = _integrated(self._sine)
        scale = table[-1][2]  # s(1) of the unnormalised law
        out = np.zeros_like(u)
        for (piece, v_a, s_a) in table[:-1]:
            inside = (u >= piece.ua) & (u <= piece.ub)
            t = u[inside] - piece.ua
            out[inside] = _piece_value(piece, t, v_a, s_a, nu)
        return out / scale

    @property
    def cv(self) -> float:
        """Peak velocity coefficient max s' (at u = 1/2 for all the symmetric laws here)."""
        return float(np.max(self(np.linspace(0, 1, 4097), 1)))

    @property
    def ca(self) -> float:
        """Peak acceleration coefficient max |s''|."""
        u = np.union1d(np.linspace(0, 1, 4097), [(3 - math.sqrt(3)) / 6])
        return float(np.max(np.abs(self(u, 2))))


def _poly345(u: np.ndarray, nu: int) -> np.ndarray:
    """s = 10u³ − 15u⁴ + 6u⁵ and its derivatives."""
    if nu == 0:
        return u ** 3 * (10 - 15 * u + 6 * u ** 2)
    if nu == 1:
        return 30 * u ** 2 * (1 - u) ** 2
    if nu == 2:
        return 60 * u - 180 * u ** 2 + 120 * u ** 3
    if nu == 3:
        return 60 - 360 * u + 360 * u ** 2
    raise ValueError(f"derivative order {nu} (0..3)")


def _piece_value(p: _SinePiece, t, v_a: float, s_a: float, nu: int):
    """Closed-form integrals of the acceleration c0 + c1 sin(ω(u − φ)) from u = ua (t = u − ua)."""
    w, c0, c1 = p.omega, p.c0, p.c1
    th_a = w * (p.ua - p.phi)
    th = th_a + w * t
    if nu == 3:
        return c1 * w * np.cos(th)
    if nu == 2:
        return c0 + c1 * np.sin(th)
    if nu == 1:
        return v_a + c0 * t - c1 / w * (np.cos(th) - math.cos(th_a))
    if nu == 0:
        return (s_a + v_a * t + c0 * t ** 2 / 2
                - c1 / w * ((np.sin(th) - math.sin(th_a)) / w - math.cos(th_a) * t))
    raise ValueError(f"derivative order {nu} (0..3)")


@functools.cache
def _integrated(pieces: tuple[_SinePiece, ...]) -> list:
    """[(piece, v at ua, s at ua), …, (None, v(1), s(1))], integrating piece by piece from rest at u = 0."""
    table: list[tuple[_SinePiece | None, float, float]] = []
    v, s = 0.0, 0.0
    for p in pieces:
        table.append((p, v, s))
        t = p.ub - p.ua
        v, s = float(_piece_value(p, t, v, s, 1)), float(_piece_value(p, t, v, s, 0))
    table.append((None, v, s))
    return table


_E = 1 / 8
# cycloid: s'' = 2π sin 2πu
_CYCLOID = (_SinePiece(0, 1, 0, 1, 2 * _PI, 0),)
# simple harmonic: s = (1 − cos πu)/2, s'' = (π²/2) cos πu = sin(π(u + 1/2)) up to scale
_HARMONIC = (_SinePiece(0, 1, 0, 1, _PI, -0.5),)
# modified sine: quarter sine (period 1/2) up to 1/8, three quarters of a sine of period 3/2 to 7/8, quarter down
_MOD_SINE = (_SinePiece(0, _E, 0, 1, 4 * _PI, 0), _SinePiece(_E, 7 * _E, 0, 1, 4 * _PI / 3, -0.25),
             _SinePiece(7 * _E, 1, 0, 1, 4 * _PI, 0))
# modified trapezoid: sine ramps of 1/8 around constant sections of 1/4 (acceleration +A, then −A)
_MOD_TRAPEZOID = (_SinePiece(0, _E, 0, 1, 4 * _PI, 0), _SinePiece(_E, 3 * _E, 1, 0, 4 * _PI, 0),
                  _SinePiece(3 * _E, 5 * _E, 0, 1, 4 * _PI, 0.25), _SinePiece(5 * _E, 7 * _E, -1, 0, 4 * _PI, 0),
                  _SinePiece(7 * _E, 1, 0, 1, 4 * _PI, 0))

#: The laws by fix point type, in the order the editor offers them.
LAWS: dict[str, MotionLaw] = {
    "P345": MotionLaw("P345", "3-4-5 polynomial", 1),
    "MSIN": MotionLaw("MSIN", "Modified sine", 32, _MOD_SINE),
    "CYCL": MotionLaw("CYCL", "Cycloid", 32, _CYCLOID),
    "MTRAP": MotionLaw("MTRAP", "Modified trapezoid", 32, _MOD_TRAPEZOID),
    "HARM": MotionLaw("HARM", "Simple harmonic", 32, _HARMONIC),
}  # their codes are camcurve.model.LAW_TYPES (a test keeps the two alike)


def segment(law: str, x0: float, x1: float, y0: float, y1: float, master, nu: int = 0):
    """Derivative nu (d/dx, UU/MUⁿ) of the law segment (x0, y0) → (x1, y1) at master position(s)."""
    h = x1 - x0
    value = LAWS[law]((np.asarray(master, dtype=float) - x0) / h, nu) * (y1 - y0) / h ** nu
    return value + y0 if nu == 0 else value


@functools.cache
def _unit_pieces(law: str) -> np.ndarray:
    """The law on [0, 1] (rise 1) as quintic Hermite pieces: coefficients (6, m), PPoly order (descending powers
    of u − break); each piece matches s, s', s'' of the law at both of its ends."""
    m = LAWS[law].pieces
    u = np.linspace(0.0, 1.0, m + 1)
    p, v, a = (LAWS[law](u, nu) for nu in (0, 1, 2))
    w = 1.0 / m
    p0, v0, a0 = p[:-1], v[:-1], a[:-1]
    # quintic Hermite on [0, w]: c3, c4, c5 from the end conditions (closed form)
    dp = p[1:] - p0 - v0 * w - a0 * w ** 2 / 2
    dv = v[1:] - v0 - a0 * w
    da = a[1:] - a0
    c3 = (10 * dp - 4 * dv * w + da * w ** 2 / 2) / w ** 3
    c4 = (-15 * dp + 7 * dv * w - da * w ** 2) / w ** 4
    c5 = (6 * dp - 3 * dv * w + da * w ** 2 / 2) / w ** 5
    out = np.vstack([c5, c4, c3, a0 / 2, v0, p0])
    out.setflags(write=False)
    return out


_POWERS = np.arange(5, -1, -1)  # PPoly rows: descending powers


def pieces(law: str, x0, h, y0, y1) -> tuple[np.ndarray, np.ndarray]:
    """Law segments (x0, y0) → (x0 + h, y1) as quintic pieces, vectorised over segments (arrays of equal length
    or scalars): (coefficients (6, segments, m) in PPoly order, left break points (segments, m)).  Exact scaling
    of the unit pieces: a local power t^k of the unit law becomes (y1 − y0)/h^k · (x − break)^k."""
    x0, h, y0, y1 = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (x0, h, y0, y1))
    unit = _unit_pieces(law)
    m = unit.shape[1]
    scale = (y1 - y0)[None, :] / h[None, :] ** _POWERS[:, None]  # (6, segments)
    coeffs = unit[:, None, :] * scale[:, :, None]
    coeffs[-1] += y0[:, None]
    return coeffs, x0[:, None] + h[:, None] * (np.arange(m) / m)[None, :]


def splice(coeffs: np.ndarray, breaks: np.ndarray, segments: list[tuple[int, str, float, float]]
           ) -> tuple[np.ndarray, np.ndarray]:
    """Replace PPoly piece p by the law's quintic pieces for every (p, law, y0, y1) of ``segments``."""
    count = np.ones(coeffs.shape[1], dtype=np.int64)
    at = np.array([seg[0] for seg in segments], dtype=np.int64)
    codes = [seg[1] for seg in segments]
    count[at] = [LAWS[code].pieces for code in codes]
    first = np.concatenate([[0], np.cumsum(count)[:-1]])
    out_c = np.empty((coeffs.shape[0], int(count.sum())))
    out_b = np.empty(out_c.shape[1] + 1)
    plain = np.ones(coeffs.shape[1], dtype=bool)
    plain[at] = False
    out_c[:, first[plain]] = coeffs[:, plain]
    out_b[first[plain]] = breaks[:-1][plain]
    out_b[-1] = breaks[-1]
    ys = np.array([(seg[2], seg[3]) for seg in segments], dtype=float)
    for code in set(codes):
        sel = np.array([c == code for c in codes])
        p = at[sel]
        c, b = pieces(code, breaks[p], breaks[p + 1] - breaks[p], ys[sel, 0], ys[sel, 1])
        cols = (first[p][:, None] + np.arange(c.shape[2])[None, :]).ravel()
        out_c[:, cols] = c.reshape(c.shape[0], -1)
        out_b[cols] = b.ravel()
    return out_c, out_b
