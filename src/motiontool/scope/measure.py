"""Cursor and mouse-position read-outs (DG 4781-4787, 4985-4999, 5030-5038, 5107-5123).

With interpolation "values" (steps) a curve's value at t is the last sample at or before t; with "lines" or
"spline" it is interpolated linearly between the neighbouring samples (the list then shows decimals).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from motiontool.scope.curves import Curve


def value_at(t: np.ndarray, y: np.ndarray, at: float, steps: bool = False) -> float | None:
    """The value at time `at`, or None outside the curve's time range."""
    if t.size == 0 or at < t[0] or at > t[-1]:
        return None
    if steps:
        return float(y[int(np.searchsorted(t, at, side="right")) - 1])
    return float(np.interp(at, t, y))


def curve_value_at(curve: Curve, at: float) -> float | None:
    t, y = curve.raw()
    v = value_at(t, y, at, steps=curve.interpolation == "values")
    return None if v is None else float(curve.scaled(v))


@dataclass
class CursorReadout:
    """Columns A, B and B−A for one curve, and the cursor pair's Δt and 1/Δt."""
    a: float | None
    b: float | None
    dt_ms: float
    d_value: float | None
    frequency_hz: float | None   # 1/Δt

    @classmethod
    def of(cls, curve: Curve, ta: float, tb: float) -> CursorReadout:
        a, b = curve_value_at(curve, ta), curve_value_at(curve, tb)
        dt = tb - ta
        return cls(a, b, dt, None if a is None or b is None else b - a, cursor_frequency(ta, tb))


def cursor_frequency(ta: float, tb: float) -> float | None:
    dt = tb - ta
    return None if dt == 0 else 1000.0 / abs(dt)


def snap_time(curve: Curve, at: float) -> float:
    """The sample time nearest `at` (cursors snap to samples when asked)."""
    t, _ = curve.raw()
    if t.size == 0:
        return at
    i = int(np.clip(np.searchsorted(t, at), 1, t.size - 1)) if t.size > 1 else 0
    if t.size > 1 and abs(t[i - 1] - at) <= abs(t[i] - at):
        i -= 1
    return float(t[i])
