"""What APOSS operators compute (DG 6652-6806). One implementation, used by the compiler's constant
folding and by the controller's VM, so a constant and a run-time value can never disagree.

LONG values are 32-bit two's complement and wrap; DOUBLE values are Python floats (64 bit, DG 6551).
"""

from __future__ import annotations

import math

INT_MIN, INT_MAX = -(1 << 31), (1 << 31) - 1


class OperatorError(ArithmeticError):
    """An operation the controller refuses (division by zero, bad bit number, bad function argument)."""


def wrap(value: int) -> int:
    """Reduce to a signed 32-bit value, as the controller's registers do."""
    value &= 0xFFFFFFFF
    return value - (1 << 32) if value & 0x80000000 else value


def div(a: int, b: int) -> int:
    """``a % b``: DIVISION, truncated toward zero (DG 6677: 19 % 3 = 6)."""
    if b == 0:
        raise OperatorError("division by zero")
    q = abs(a) // abs(b)
    return wrap(q if (a >= 0) == (b >= 0) else -q)


def mod(a: int, b: int) -> int:
    """``a mod b``: remainder with the sign of a (DG 6679: 250 mod 16 = 10)."""
    if b == 0:
        raise OperatorError("division by zero in mod")
    return wrap(a - div(a, b) * b)


def rnd(a: int, b: int) -> int:
    """``a rnd b``: division rounded half away from zero (DG 6680: 250 rnd 16 = 16; DG 6587: -100 rnd 15 = -7)."""
    if b == 0:
        raise OperatorError("division by zero in rnd")
    q, r = divmod(abs(a), abs(b))
    if 2 * r >= abs(b):
        q += 1
    return wrap(q if (a >= 0) == (b >= 0) else -q)


def finite(result: float, a: float, op: str, b: float) -> float:
    """A DOUBLE result beyond the DOUBLE range is error 156, at run time and in a constant (decisions K80): the
    controller has no infinity to go on with, and a saturated LONG made of one would drive the axis to the end."""
    if not math.isfinite(result):
        raise OperatorError(f"{a!r} {op} {b!r} overflows the DOUBLE range")
    return result


def ddiv(a: float, b: float) -> float:
    """``%`` on DOUBLE values (DG 6575: -100.00 % 15.0 = -6.666…)."""
    if b == 0:
        raise OperatorError("division by zero")
    return a / b


def power(a: float, b: float) -> float:
    """``x exp u`` = x to the power u (DG 6569), a DOUBLE."""
    try:
        result = math.pow(a, b)
    except (ValueError, OverflowError):
        raise OperatorError(f"{a} exp {b} has no real result") from None
    return result


def shl(a: int, b: int) -> int:
    return wrap(a << b) if 0 <= b < 64 else 0


def shr(a: int, b: int) -> int:
    """Arithmetic shift right (the sign is kept), as on a signed 32-bit register."""
    return a >> b if 0 <= b < 64 else (-1 if a < 0 else 0)


# Bit selectors (DG 6726-6762): name → (field width in bits, signed, number of fields).
SELECTORS = {"i": (1, False, 32), "b": (8, False, 4), "ub": (8, False, 4), "sb": (8, True, 4),
             "w": (16, False, 2), "uw": (16, False, 2), "sw": (16, True, 2), "l": (32, True, 1)}


def _field(kind: str, n: int) -> tuple[int, int, bool]:
    width, signed, count = SELECTORS[kind]
    if not 1 <= n <= count:
        name = "bit" if kind == "i" else f".{kind}"
        raise OperatorError(f"{name} number {n} is outside 1..{count}")
    return (n - 1) * width, width, signed


def bit_get(value: int, kind: str, n: int) -> int:
    """``value.n`` / ``.b n`` …: the n-th field, 1-based (7.1 = 1, 0x027F.b1 = 127, 0x1FFFE.sb1 = -2)."""
    shift, width, signed = _field(kind, n)
    field = ((value & 0xFFFFFFFF) >> shift) & ((1 << width) - 1)
    if signed and field >> (width - 1):
        field -= 1 << width
    return field


def bit_set(value: int, kind: str, n: int, new: int) -> int:
    """``value.n = new``: replace the n-th field (Value.3 = 1 → 4, Value.b2 = 128 → 0x8000)."""
    shift, width, _ = _field(kind, n)
    mask = ((1 << width) - 1) << shift
    return wrap((value & ~mask) | ((new << shift) & mask))


def to_long(value: float) -> int:
    """DOUBLE → LONG conversion: truncation toward zero, saturated at the LONG range."""
    if math.isnan(value):
        raise OperatorError("NaN cannot become a LONG")
    if math.isinf(value):
        return INT_MAX if value > 0 else INT_MIN
    return max(INT_MIN, min(INT_MAX, int(value)))


def _checked(name: str, fn, lo: float = -math.inf, hi: float = math.inf):
    def call(x: float) -> float:
        if not lo <= x <= hi:
            raise OperatorError(f"{name}({x}) is not defined (error 156)")
        try:
            result = fn(x)
        except (ValueError, OverflowError):  # e.g. sin(inf)
            raise OperatorError(f"{name}({x}) is not defined (error 156)") from None
        if not math.isfinite(result):  # grad(1e308)
            raise OperatorError(f"{name}({x}) overflows the DOUBLE range (error 156)")
        return result
    return call


def _round(x: float) -> float:
    """round(x): nearest integer value, halves away from zero (DG 6579-6581: round(-6.666) = -7.0)."""
    if not math.isfinite(x):
        raise OperatorError(f"round({x}) is not defined (error 156)")
    return float(math.floor(abs(x) + 0.5) * (1 if x >= 0 else -1))


# DOUBLE functions (DG 6553-6581): illegal arguments raise error 156 on the controller.
DOUBLE_FUNCTIONS = {
    "SQRT": _checked("sqrt", math.sqrt, 0.0), "SIN": _checked("sin", math.sin),
    "COS": _checked("cos", math.cos), "TAN": _checked("tan", math.tan),
    "ACOS": _checked("acos", math.acos, -1.0, 1.0), "ASIN": _checked("asin", math.asin, -1.0, 1.0),
    "ATAN": _checked("atan", math.atan), "GRAD": _checked("grad", math.degrees),
    "RAD": _checked("rad", math.radians), "LN": _checked("ln", math.log, math.ulp(0.0)),
    "FABS": math.fabs, "ROUND": _round,
}


def compare(op: str, a: float, b: float) -> int:
    return int({"==": a == b, "!=": a != b, "<": a < b, "<=": a <= b, ">": a > b, ">=": a >= b}[op])


def long_binary(op: str, a: int, b: int) -> int:
    """Binary operator on two LONG values."""
    if op == "+":
        return wrap(a + b)
    if op == "-":
        return wrap(a - b)
    if op == "*":
        return wrap(a * b)
    if op == "%":
        return div(a, b)
    if op == "MOD":
        return mod(a, b)
    if op == "RND":
        return rnd(a, b)
    if op == "&":
        return wrap(a & b)
    if op == "|":
        return wrap(a | b)
    if op == "^":
        return wrap(a ^ b)
    if op == "<<":
        return shl(a, b)
    if op == ">>":
        return shr(a, b)
    if op == "AND":
        return int(bool(a) and bool(b))
    if op == "OR":
        return int(bool(a) or bool(b))
    return compare(op, a, b)


def double_binary(op: str, a: float, b: float) -> float | int:
    """Binary operator where at least one side is DOUBLE (both already converted)."""
    if op == "+":
        return finite(a + b, a, "+", b)
    if op == "-":
        return finite(a - b, a, "-", b)
    if op == "*":
        return finite(a * b, a, "*", b)
    if op == "%":
        return finite(ddiv(a, b), a, "%", b)
    if op == "EXP":
        return power(a, b)
    if op == "AND":
        return int(bool(a) and bool(b))
    if op == "OR":
        return int(bool(a) or bool(b))
    return compare(op, a, b)


LONG_ONLY_OPS = {"MOD", "RND", "&", "|", "^", "<<", ">>"}
