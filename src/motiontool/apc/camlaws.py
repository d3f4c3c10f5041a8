"""The six CAM interpolation laws of the APC (seed 004 §4.7.3 L1378-1498) — pure integer maths shared by the
kernel's CAM reference and the CAM editor.

The figures with the curves are lost; the position laws are **derived** from the speeds the text states (spec
§2.3, docs/decisions.md A30), with u = x/X the fraction of the segment's master length covered:

    0 Linear  Y·u              1 Cosine  Y·(1−cos πu)/2      2 Square1  Y·u²
    3 Square2 Y·(2u−u²)        4 Cosine1 Y·(u − sin(πu)/π)   5 Cosine2  Y·(u + sin(πu)/π)

Linear: V_s = V_m·Y/X (L1406). Cosine: rest to rest, peak π·Y/(2X) (printed "Y/(2X)", L1422, spec §9.2).
Square1 and Cosine1 end at V_m·2Y/X, Square2 and Cosine2 start there (L1440, L1457, L1474, L1494).
Each value is rounded once from exact integers (or a double for the trigonometric laws), so a segment's end is
exactly Y and a cycle exactly ΣY.
"""

from __future__ import annotations

import math

# 90.49 error codes (Table 4-11, L2316-2324)
ERR_ARRAY_TOO_SMALL, ERR_SEGMENT_OVERRUN, ERR_SIZE_ZERO, ERR_ABS_RESET = 1, 2, 3, 4
LAW_NAMES = ("Linear", "Cosine", "Square1", "Square2", "Cosine1", "Cosine2")


# Inside a segment (0 < x < X) each law is a function of its own, so the kernel's CAM calls a segment's law
# directly. Linear, Square1 and Square2 are exact rationals a/b rounded to the nearest count with halves away
# from zero; the trigonometric laws round a double once.
def linear(x: int, big_x: int, y: int) -> int:
    a = y * x
    if a >= 0:
        return (2 * a + big_x) // (2 * big_x)
    return -((big_x - 2 * a) // (2 * big_x))


def square1(x: int, big_x: int, y: int) -> int:
    a, b = y * x * x, big_x * big_x
    if a >= 0:
        return (2 * a + b) // (2 * b)
    return -((b - 2 * a) // (2 * b))


def square2(x: int, big_x: int, y: int) -> int:
    a, b = y * x * (2 * big_x - x), big_x * big_x
    if a >= 0:
        return (2 * a + b) // (2 * b)
    return -((b - 2 * a) // (2 * b))


def cosine(x: int, big_x: int, y: int) -> int:        # half-cosine from rest to rest
    return round(y * (1.0 - math.cos(math.pi * x / big_x)) / 2.0)


def cosine1(x: int, big_x: int, y: int) -> int:       # sine acceleration from rest to 2Y/X
    u = x / big_x
    return round(y * (u - math.sin(math.pi * u) / math.pi))


def cosine2(x: int, big_x: int, y: int) -> int:       # sine deceleration from 2Y/X to rest
    u = x / big_x
    return round(y * (u + math.sin(math.pi * u) / math.pi))


# law code → its interior function; any other code interpolates linearly (**inferred**)
INTERIOR = (linear, cosine, square1, square2, cosine1, cosine2)


def law_value(code: int, x: int, big_x: int, y: int) -> int:
    """Slave travel after x of a segment's X master counts (0 ≤ x ≤ X), rounded to a count; exact at both ends."""
    if x <= 0:
        return 0
    if x >= big_x:
        return y
    return (INTERIOR[code] if 0 <= code < 6 else linear)(x, big_x, y)
