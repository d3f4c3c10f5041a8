"""Numbers as the oscilloscope shows them: axis ticks, list values, cursor times (issue 23 item 8). No Qt.

Scientific notation (`1.3244e+06` ms) is never shown: values get thousands grouping with a thin space (the SI
way, read the same in every locale, unlike "," or "."), times are seconds or milliseconds from the recording's
start (decision S32).
"""

from __future__ import annotations

import math

GROUP = "\u2009"            # thin space between groups of three digits
SECONDS_FROM_MS = 2000.0    # a visible span of 2 s or more is labelled in seconds


def decimals_for(step: float) -> int:
    """Digits after the point that tell ticks `step` apart (0 for steps of 1 and more)."""
    if not math.isfinite(step) or step <= 0:
        return 0
    return max(0, min(9, math.ceil(-math.log10(step) - 1e-9)))


def grouped(value: float, decimals: int = 0) -> str:
    """`1324400.5` → "1 324 400.5" (thin spaces); NaN and infinities as Python writes them."""
    if not math.isfinite(value):
        return str(value)
    if round(value, decimals) == 0:
        value = 0.0   # no "-0" tick
    return f"{value:,.{decimals}f}".replace(",", GROUP)


def value_text(value: float) -> str:
    """A value in the curve list: integers whole, else six significant digits, grouped, never scientific."""
    if not math.isfinite(value):
        return str(value)
    if value == int(value) and abs(value) < 1e15:
        return grouped(value)
    digits = max(0, 6 - (math.floor(math.log10(abs(value))) + 1)) if value else 0
    return grouped(value, min(digits, 9)).rstrip("0").rstrip(".") if digits else grouped(value)


def time_unit(span_ms: float) -> str:
    """"s" for a visible span of 2 s or more, else "ms"."""
    return "s" if span_ms >= SECONDS_FROM_MS else "ms"


def time_ticks(values_ms: list[float], spacing_ms: float, unit: str) -> list[str]:
    """Tick labels of the time axis in `unit`, with as many decimals as the tick spacing needs."""
    scale = 1000.0 if unit == "s" else 1.0
    places = decimals_for(spacing_ms / scale)
    return [grouped(v / scale, places) for v in values_ms]


def time_text(ms: float, unit: str | None = None) -> str:
    """A cursor time or difference: "1.250 s" from 2 s on, else "834.0 ms"; `unit` keeps several in one unit."""
    if (unit or time_unit(abs(ms))) == "s":
        return f"{grouped(ms / 1000.0, 3)} s"
    return f"{grouped(ms, 1)} ms"
