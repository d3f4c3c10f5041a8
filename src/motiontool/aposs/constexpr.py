"""Constant folding of APOSS expressions with the operators of semantics.py (array sizes, CASE labels,
#if conditions, and the compiler's folding of constant sub-expressions)."""

from __future__ import annotations

from motiontool.aposs import ast, semantics


class NotConstant(Exception):
    pass


def fold(expr: ast.Expr) -> int | float:
    """The value of a constant expression; raises NotConstant, or OperatorError for e.g. 1 % 0."""
    if isinstance(expr, ast.Num):
        return expr.value
    if isinstance(expr, ast.Unary):
        v = fold(expr.operand)
        if expr.op == "-":
            return semantics.wrap(-v) if isinstance(v, int) else -v
        if expr.op == "~":
            return semantics.wrap(~_need_long(v, "~"))
        if expr.op == "NOT":
            return int(v == 0)
        if expr.op == "(long)":
            return semantics.to_long(v) if isinstance(v, float) else v
        return float(v)  # (double)
    if isinstance(expr, ast.Binary):
        a, b = fold(expr.left), fold(expr.right)
        if expr.op == "EXP":
            return semantics.power(float(a), float(b))
        if isinstance(a, int) and isinstance(b, int):
            return semantics.long_binary(expr.op, a, b)
        if expr.op in semantics.LONG_ONLY_OPS:
            raise semantics.OperatorError(f"operator {expr.op.lower()} needs LONG operands")
        return semantics.double_binary(expr.op, float(a), float(b))
    if isinstance(expr, ast.BitSel):
        v, n = fold(expr.base), fold(expr.index)
        return semantics.bit_get(_need_long(v, "a bit selector"), expr.kind, _need_long(n, "a bit number"))
    if isinstance(expr, ast.CmdExpr) and expr.command.kind in ("function", "sysvar"):
        name = expr.command.name
        if name == "PI":
            return 3.141592653589793
        if name in semantics.DOUBLE_FUNCTIONS and len(expr.args) == 1:
            return semantics.DOUBLE_FUNCTIONS[name](float(fold(expr.args[0])))
        if name == "ABS" and len(expr.args) == 1:
            v = fold(expr.args[0])
            return semantics.wrap(abs(v)) if isinstance(v, int) else abs(v)
    raise NotConstant


def _need_long(v: int | float, what: str) -> int:
    if not isinstance(v, int):
        raise semantics.OperatorError(f"{what} needs a LONG value")
    return v


def fold_int(expr: ast.Expr) -> int | None:
    """The integer value of a constant expression, or None if it is not a LONG constant."""
    try:
        v = fold(expr)
    except (NotConstant, semantics.OperatorError):
        return None
    return v if isinstance(v, int) else None
