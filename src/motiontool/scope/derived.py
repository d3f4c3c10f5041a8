"""Derived curves (DG 5630-5674): computed from other curves, never recorded.

Kinds: derivative (d/dt per second), delta (each point minus the previous), difference (base − second), sum,
product, scaled (factor·y + offset), integral (∫ y dt, seconds), bit mask (with signed/unsigned), and an
expression over named curves. Expressions are parsed into a tree of allowed nodes and evaluated on numpy
arrays; nothing is ever passed to eval.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, field

import numpy as np

from motiontool.scope.curves import Curve, Source

KINDS = ("derivative", "delta", "difference", "sum", "product", "scaled", "integral", "bit_mask", "expression")


class DerivedError(ValueError):
    pass


@dataclass
class DerivedSpec:
    kind: str
    base: str = ""
    second: str = ""
    factor: float = 1.0
    offset: float = 0.0
    mask: int = 0xFFFFFFFF
    signed: bool = False
    expression: str = ""
    variables: dict[str, str] = field(default_factory=dict)   # expression name → curve name

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> DerivedSpec:
        spec = cls(**d)
        if spec.kind not in KINDS:
            raise DerivedError(f"unknown derived curve type '{spec.kind}'")
        return spec

    def inputs(self) -> list[str]:
        if self.kind == "expression":
            return list(self.variables.values())
        if self.kind in ("difference", "sum", "product"):
            return [self.base, self.second]
        return [self.base]


Lookup = Callable[[str], tuple[np.ndarray, np.ndarray]]


def compute(spec: DerivedSpec, lookup: Lookup) -> tuple[np.ndarray, np.ndarray]:
    """Times and values of a derived curve; lookup(name) gives (t, y) of another curve. A second curve is
    sampled at the base curve's times (linear interpolation), so curves of different runs can be compared."""
    if spec.kind == "expression":
        return evaluate_expression(spec.expression, spec.variables, lookup)
    t, y = lookup(spec.base)
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if spec.kind in ("difference", "sum", "product"):
        y2 = resample(lookup(spec.second), t)
        y = {"difference": y - y2, "sum": y + y2, "product": y * y2}[spec.kind]
    elif spec.kind == "derivative":
        y = np.gradient(y, t / 1000.0) if y.size > 1 else np.zeros_like(y)  # per second: t is in ms
    elif spec.kind == "delta":
        y = np.diff(y, prepend=y[:1]) if y.size else y
    elif spec.kind == "integral":
        if y.size:
            dt = np.diff(t) / 1000.0
            y = np.concatenate([[0.0], np.cumsum((y[1:] + y[:-1]) / 2 * dt)])
    elif spec.kind == "scaled":
        y = y * spec.factor + spec.offset
    elif spec.kind == "bit_mask":
        y = bit_mask(y, spec.mask, spec.signed)
    else:
        raise DerivedError(f"unknown derived curve type '{spec.kind}'")
    return t, y


def resample(ty: tuple[np.ndarray, np.ndarray], t: np.ndarray) -> np.ndarray:
    t2, y2 = (np.asarray(a, dtype=float) for a in ty)
    if t2.size == 0:
        return np.full(t.shape, np.nan)
    return np.interp(t, t2, y2, left=np.nan, right=np.nan)


def bit_mask(y: np.ndarray, mask: int, signed: bool) -> np.ndarray:
    """Keep the masked bits and shift them down to bit 0 (the manual's example 12 → 0x78563412 shows the
    selected bytes as one number); signed treats the highest selected bit as the sign."""
    mask &= 0xFFFFFFFF
    if mask == 0:
        return np.zeros_like(y)
    shift = (mask & -mask).bit_length() - 1
    width = mask.bit_length() - shift
    v = (np.asarray(y, dtype=np.float64).astype(np.int64) & mask) >> shift
    if signed:
        v = np.where(v >= (1 << (width - 1)), v - (1 << width), v)
    return v.astype(float)


# --- expressions ---------------------------------------------------------------------------------------------
_FUNCTIONS: dict[str, Callable[..., np.ndarray]] = {
    "abs": np.abs, "sqrt": np.sqrt, "sin": np.sin, "cos": np.cos, "tan": np.tan, "exp": np.exp, "log": np.log,
    "min": np.minimum, "max": np.maximum, "sign": np.sign, "round": np.round}
_CONSTANTS = {"pi": math.pi, "e": math.e}
_BINARY = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply, ast.Div: np.divide,
           ast.Pow: np.power, ast.Mod: np.mod}
_BITS = {ast.BitAnd: np.bitwise_and, ast.BitOr: np.bitwise_or, ast.BitXor: np.bitwise_xor,
         ast.LShift: np.left_shift, ast.RShift: np.right_shift}
MAX_EXPRESSION = 500


def parse_expression(text: str, names: set[str]) -> ast.Expression:
    """Check an expression: numbers, the given names, + - * / ** % & | ^ << >>, unary ±, the functions of
    _FUNCTIONS and pi/e. Anything else is refused with its column."""
    if len(text) > MAX_EXPRESSION:
        raise DerivedError(f"expression longer than {MAX_EXPRESSION} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise DerivedError(f"expression: {exc.msg} at column {exc.offset}") from None
    for node in ast.walk(tree):
        col = getattr(node, "col_offset", 0) + 1
        if isinstance(node, ast.Expression | ast.Load | ast.operator | ast.unaryop):
            if isinstance(node, ast.MatMult):
                raise DerivedError(f"expression: '@' at column {col} is not allowed")
            continue
        if isinstance(node, ast.Constant):
            if not isinstance(node.value, int | float) or isinstance(node.value, bool):
                raise DerivedError(f"expression: only numbers are allowed (column {col})")
        elif isinstance(node, ast.Name):
            if node.id not in names and node.id not in _CONSTANTS and node.id not in _FUNCTIONS:
                raise DerivedError(f"expression: unknown name '{node.id}' at column {col}")
        elif isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in _FUNCTIONS or node.keywords:
                raise DerivedError(f"expression: unknown function at column {col}")
        elif not isinstance(node, ast.BinOp | ast.UnaryOp):
            raise DerivedError(f"expression: '{type(node).__name__}' at column {col} is not allowed")
    return tree


def evaluate_expression(text: str, variables: dict[str, str], lookup: Lookup) -> tuple[np.ndarray, np.ndarray]:
    """Evaluate on the time base of the first variable (others resampled onto it)."""
    tree = parse_expression(text, set(variables))
    if not variables:
        raise DerivedError("expression: name at least one curve")
    first = next(iter(variables.values()))
    t = np.asarray(lookup(first)[0], dtype=float)
    values = {name: resample(lookup(curve), t) for name, curve in variables.items()}
    with np.errstate(all="ignore"):
        y = _eval(tree.body, values, t.shape)
    return t, np.broadcast_to(np.asarray(y, dtype=float), t.shape).copy()


def _eval(node: ast.AST, values: dict[str, np.ndarray], shape):
    if isinstance(node, ast.Constant):
        assert isinstance(node.value, int | float)  # parse_expression lets only numbers through
        return float(node.value)
    if isinstance(node, ast.Name):
        if node.id in values:
            return values[node.id]
        if node.id in _CONSTANTS:
            return _CONSTANTS[node.id]
        raise DerivedError(f"expression: '{node.id}' is a function")
    if isinstance(node, ast.UnaryOp):
        v = _eval(node.operand, values, shape)
        if isinstance(node.op, ast.USub):
            return -v
        if isinstance(node.op, ast.UAdd):
            return v
        if isinstance(node.op, ast.Invert):
            return np.invert(np.asarray(v).astype(np.int64)).astype(float)
        raise DerivedError("expression: 'not' is not allowed")
    if isinstance(node, ast.BinOp):
        a, b = _eval(node.left, values, shape), _eval(node.right, values, shape)
        op = type(node.op)
        if op in _BINARY:
            if op is ast.Pow and np.any(np.abs(b) > 64):
                raise DerivedError("expression: exponent larger than 64")
            return _BINARY[op](a, b)
        if op in _BITS:
            ai = np.asarray(a).astype(np.int64)
            bi = np.asarray(b).astype(np.int64)
            if op in (ast.LShift, ast.RShift):
                bi = np.clip(bi, 0, 63)
            return _BITS[op](ai, bi).astype(float)
        raise DerivedError(f"expression: operator {op.__name__} is not allowed")
    if isinstance(node, ast.Call):
        assert isinstance(node.func, ast.Name)  # parse_expression lets only named functions through
        args = [_eval(a, values, shape) for a in node.args]
        try:
            return _FUNCTIONS[node.func.id](*args)
        except TypeError as exc:
            raise DerivedError(f"expression: {node.func.id}: {exc}") from None
    raise DerivedError(f"expression: '{type(node).__name__}' is not allowed")


def refresh(scope) -> list[str]:
    """Recompute the derived curves of a scope whose inputs changed (in list order, so a derived curve may use
    another one above it). Returns the names of curves that failed, each with its reason kept in
    source.info["error"] (a missing base curve must not stop the others)."""
    failed = []
    for curve in scope.curves:
        if curve.source.method != "derived" or not curve.source.derived:
            continue
        try:
            spec = DerivedSpec.from_dict(curve.source.derived)
            inputs = [scope.curve(name) for name in spec.inputs()]
            key = tuple((c.name, c.buffer.version) for c in inputs) + (repr(curve.source.derived),)
            if getattr(curve, "_derived_key", None) == key:
                continue
            t, y = compute(spec, lambda name: scope.curve(name).raw())
        except (KeyError, DerivedError, TypeError, ValueError) as exc:
            curve.source.info["error"] = str(exc)
            failed.append(curve.name)
            continue
        curve.source.info.pop("error", None)
        curve._derived_key = key  # a cache, not saved with the curve
        if curve.buffer.capacity < max(t.size, 1):
            curve.buffer.set_capacity(t.size)
        curve.buffer.clear()
        ok = np.isfinite(y)
        curve.buffer.extend(t[ok], y[ok])
    return failed


def add_derived(scope, spec: DerivedSpec, name: str, colour: str | None = None):
    """A new derived curve inserted right after its base curve (ide-spec 6.45, DG 5630-5674)."""
    spec = DerivedSpec.from_dict(spec.to_dict())
    for input_name in spec.inputs():
        scope.curve(input_name)  # KeyError names a missing input before anything changes
    if spec.kind == "expression":
        parse_expression(spec.expression, set(spec.variables))
    curve = Curve(name, Source(method="derived", controller=None, derived=spec.to_dict()))
    if colour:
        curve.colour = colour
    after = spec.inputs()[0] if spec.inputs() else None
    scope.add_curve(curve, after=after)
    refresh(scope)
    return curve
