"""Integer arithmetic of the SM-Applications module: 32-bit wrap, MULDIV/MULDIVRM, word blocks, ratios.

The APC works in signed 32-bit integers with 64-bit intermediates (seed 004 L455-457); several behaviours
are defined by that arithmetic: indexing past 2^31 wraps seamlessly (L1193-1209), ratio remainders are kept
so a tooth-count ratio never drifts (L1825-1840), MULDIVRM hands the remainder to the program (L6891-6960).
"""

from __future__ import annotations

INT32_MIN = -(1 << 31)
INT32_MAX = (1 << 31) - 1
_MASK32 = 0xFFFFFFFF


def wrap32(value: int) -> int:
    """`value` as the signed 32-bit integer the module would hold (two's complement wrap)."""
    value &= _MASK32
    return value - (1 << 32) if value & 0x80000000 else value


def signed16(value: int) -> int:
    """The lower 16 bits of `value` as a signed 16-bit number."""
    value &= 0xFFFF
    return value - 0x10000 if value & 0x8000 else value


def div_trunc(a: int, b: int) -> tuple[int, int]:
    """Quotient rounded toward zero and the remainder with the sign of the dividend (C / DPL integer
    division). **Inferred**: the manual's MULDIVRM example (L6930-6950) handles negative remainders down to
    -59999, which only a truncating division produces."""
    q = abs(a) // abs(b)
    if (a < 0) != (b < 0):
        q = -q
    return q, a - q * b


def MULDIV(a: int, b: int, c: int) -> int:
    """a·b/c with a 64-bit intermediate, truncated toward zero, wrapped to 32 bits (L702, L4749)."""
    if c == 0:
        raise ZeroDivisionError("MULDIV by zero")
    return wrap32(div_trunc(a * b, c)[0])


def MULDIVRM(a: int, b: int, c: int) -> tuple[int, int]:
    """(quotient, remainder) of a·b/c with a 64-bit intermediate (L6919-6922): the virtual-master example
    accumulates the remainder to keep the speed exact."""
    if c == 0:
        raise ZeroDivisionError("MULDIVRM by zero")
    x = a * b
    if x >= 0 and c > 0:    # div_trunc and wrap32 of this case without their calls (a virtual master per sample)
        q = x // c
        r = x - q * c
        if q <= INT32_MAX and r <= INT32_MAX:
            return q, r
    q, r = div_trunc(x, c)
    return wrap32(q), wrap32(r)


# --- word manipulation function blocks (L4497-4543, L6809-6889) -------------------------------------------------
def UnsignedTopWord(value: int) -> int:
    """Upper 16 bits as an unsigned number: 0x98768765 → 0x9876 (L4502)."""
    return (value >> 16) & 0xFFFF


def SignedTopWord(value: int) -> int:
    """Upper 16 bits sign-extended: 0x98768765 → 0xFFFF9876 (L4508)."""
    return signed16(value >> 16)


def UnsignedBottomWord(value: int) -> int:
    """Lower 16 bits as an unsigned number: 0x98768765 → 0x8765 (L4514)."""
    return value & 0xFFFF


def SignedBottomWord(value: int) -> int:
    """Lower 16 bits sign-extended: 0x98768765 → 0xFFFF8765 (L4520)."""
    return signed16(value)


def PutTopWord(input1: int, input2: int) -> int:
    """Lower 16 bits of input1 into the upper half, lower 16 bits of input2 into the lower half (L4526)."""
    return wrap32(((input1 & 0xFFFF) << 16) | (input2 & 0xFFFF))


def PutBottomWord(input1: int, input2: int) -> int:
    """Lower 16 bits of input1 into the lower half, upper 16 bits of input2 kept (L4532):
    PutBottomWord(0xFFFFFFF7, 0x57043291) = 0x5704FFF7."""
    return wrap32((input2 & 0xFFFF0000) | (input1 & 0xFFFF))


class Ratio:
    """A numerator/denominator applied to increments with the division remainder carried (L1825-1840,
    L1546-1552): over any number of samples the output is exactly floor(N·Σin/D), so 24/10 never drifts.

    The carry uses floor division, so running backwards retraces the same counts (**inferred**: the manual
    only says the remainder is kept)."""

    __slots__ = ("numerator", "denominator", "remainder")

    def __init__(self, numerator: int = 1000, denominator: int = 1000):
        self.numerator = numerator
        self.denominator = denominator
        self.remainder = 0

    def step(self, increment: int) -> int:
        total = increment * self.numerator + self.remainder
        out, self.remainder = divmod(total, self.denominator)
        return out

    def reset(self) -> None:
        self.remainder = 0
