"""Code generation for expressions, conversions, command calls and their arguments (a mixin of CodeGen).

Split from codegen.py by concept: codegen.py walks statements and owns the symbols; this part turns an
expression into code that pushes its value and returns its type (long/double).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

from motiontool.aposs import ast, image, semantics
from motiontool.aposs.ast import DOUBLE, LONG
from motiontool.aposs.constexpr import NotConstant, fold, fold_int
from motiontool.aposs.image import BINOP_OF, MATH_FUNCTIONS, PSEUDO_ARRAYS, SELECTOR_CODES, Op
from motiontool.aposs.simulated import unserved_note
from motiontool.language.diagnostics import CompileError, DiagnosticSink, Location

if TYPE_CHECKING:
    from motiontool.aposs.codegen import Symbol


class ExpressionCode:
    """Expression code for CodeGen: uses its emit/const/lookup/symbol methods."""

    # What this mixin uses of CodeGen, which sets and defines them (codegen.py)
    program: ast.Program
    sink: DiagnosticSink
    img: image.ProgramImage
    functions: dict[str, int]
    declared_functions: set[str]
    func_nodes: dict[str, ast.Function]
    assigned: set[str]

    if TYPE_CHECKING:
        @property
        def pc(self) -> int: ...
        def emit(self, op: Op, arg: int = 0) -> int: ...
        def const_double(self, value: float) -> int: ...
        def const_string(self, value: str) -> int: ...
        def lookup(self, name: str) -> Symbol | None: ...
        def scalar(self, name: str, text: str, loc: Location, assigning: bool) -> Symbol: ...
        def array(self, name: str, text: str, loc: Location) -> Symbol: ...
        def push_array(self, sym: Symbol) -> None: ...
        def element_address(self, target: ast.Index) -> Symbol: ...
        def stable(self, target: ast.Expr) -> ast.Expr: ...
        def store(self, target: ast.Expr, value: Callable[[], str], source: ast.Expr | None = None) -> None: ...
        def _incremented(self, target: ast.Expr, op: str) -> str: ...

    # --- expressions --------------------------------------------------------------------------------
    def convert(self, have: str, want: str) -> None:
        if have == want:
            return
        if have in ("none", "string"):
            raise CompileError("this has no value", Location("?", 0, 0))
        self.emit(Op.I2D if want == DOUBLE else Op.D2I)

    def to_long(self, have: str) -> None:
        self.convert(have, LONG)

    def truth(self, cond: ast.Expr) -> None:
        """Push 0/1 (or any LONG, non-zero = true) for a condition."""
        if self.expr(cond) == DOUBLE:
            self.emit(Op.PUSHD, self.const_double(0.0))
            self.emit(Op.BIND, image.BinOp.NE)

    def expr(self, e: ast.Expr) -> str:
        """Emit code that pushes the value of e; return its type (long/double)."""
        if not isinstance(e, (ast.Num, ast.Name, ast.Index)):
            try:  # constant sub-expressions are computed once, here, with the controller's own rules
                value = fold(e)
            except NotConstant:
                pass
            except semantics.OperatorError as exc:
                raise CompileError(str(exc), e.loc) from None
            else:
                if isinstance(value, float) and not math.isfinite(value):
                    raise CompileError("this constant expression overflows the DOUBLE range", e.loc)
                e = ast.Num(e.loc, value)
        return getattr(self, "e_" + type(e).__name__)(e)

    def e_Num(self, e: ast.Num) -> str:
        if isinstance(e.value, float):
            self.emit(Op.PUSHD, self.const_double(e.value))
            return DOUBLE
        self.emit(Op.PUSH, e.value)
        return LONG

    def e_Str(self, e: ast.Str) -> str:
        raise CompileError("a text in quotes is only allowed in PRINT and as a command argument", e.loc)

    def e_Name(self, e: ast.Name) -> str:
        sym = self.scalar(e.name, e.text, e.loc, assigning=False)
        self.emit(Op.LOADL if sym.kind == "local" else Op.LOADG, sym.slot)
        return sym.type

    def e_Index(self, e: ast.Index) -> str:
        sym = self.element_address(e)
        self.emit(Op.LOADE2 if len(e.indices) == 2 else Op.LOADE)
        return sym.type

    def e_Pseudo(self, e: ast.Pseudo) -> str:
        self.to_long(self.expr(e.index))
        self.emit(Op.LOADP, PSEUDO_ARRAYS.index(e.name))
        return LONG

    def e_PostIncrement(self, e: ast.PostIncrement) -> str:
        target = self.stable(e.target)
        t = self.expr(target)  # the old value stays on the stack
        self.store(target, lambda: self._incremented(target, e.op))
        return t

    def e_Unary(self, e: ast.Unary) -> str:
        t = self.expr(e.operand)
        if e.op == "-":
            self.emit(Op.NEG if t == LONG else Op.NEGD)
        elif e.op == "~":
            if t != LONG:
                raise CompileError("'~' needs a LONG value", e.loc)
            self.emit(Op.BNOT)
        elif e.op == "NOT":
            if t == DOUBLE:
                self.emit(Op.PUSHD, self.const_double(0.0))
                self.emit(Op.BIND, image.BinOp.NE)
            self.emit(Op.LNOT)
            return LONG
        else:
            want = LONG if e.op == "(long)" else DOUBLE
            self.convert(t, want)
            return want
        return t

    def e_Binary(self, e: ast.Binary) -> str:
        left = self.expr(e.left)
        mark = self.pc
        right = self.expr(e.right)
        op = BINOP_OF[e.op]
        if e.op == "EXP" or (DOUBLE in (left, right)):
            if e.op in semantics.LONG_ONLY_OPS:
                raise CompileError(f"operator '{e.op.lower()}' needs LONG operands, not DOUBLE", e.loc)
            if e.op in ("AND", "OR"):
                self._truth_after(right)
                self._insert_truth(mark, left)
                self.emit(Op.BIN, op)
                return LONG
            if right == LONG:
                self.emit(Op.I2D)
            if left == LONG:
                self._insert(mark, [int(Op.I2D), 0])
            self.emit(Op.BIND, op)
            return LONG if e.op in ("==", "!=", "<", "<=", ">", ">=") else DOUBLE
        self.emit(Op.BIN, op)
        return LONG

    def _truth_after(self, t: str) -> None:
        if t == DOUBLE:
            self.emit(Op.PUSHD, self.const_double(0.0))
            self.emit(Op.BIND, image.BinOp.NE)

    def _insert_truth(self, mark: int, t: str) -> None:
        if t == DOUBLE:
            self._insert(mark, [int(Op.PUSHD), self.const_double(0.0), int(Op.BIND), int(image.BinOp.NE)])

    def _insert(self, pc: int, words: list[int]) -> None:
        # Expressions contain no jumps, so code can be inserted inside one without fixing targets.
        self.img.code[2 * pc:2 * pc] = words

    def e_BitSel(self, e: ast.BitSel) -> str:
        n = fold_int(e.index)
        if n is not None:
            try:
                semantics.bit_get(0, e.kind, n)
            except semantics.OperatorError as exc:
                raise CompileError(str(exc), e.index.loc) from None
        if self.expr(e.base) != LONG:
            raise CompileError("bit selectors need a LONG value", e.loc)
        self.to_long(self.expr(e.index))
        self.emit(Op.BITGET, SELECTOR_CODES.index(e.kind))
        return LONG

    def e_Call(self, e: ast.Call) -> str:
        if e.name not in self.declared_functions:
            if e.name in self.functions or e.name in self.func_nodes or \
                    any(f.name == e.name for f in self.program.functions):
                raise CompileError(f"function '{e.text}' is called before it is declared; put a declaration "
                                   f"'long {e.text}(...);' before this line (DG 6621)", e.loc)
            raise CompileError(f"unknown function '{e.text}'", e.loc)
        index = self.functions[e.name]
        func = self.img.functions[index]
        if len(e.args) != len(func.params):
            raise CompileError(f"function '{e.text}' takes {len(func.params)} argument(s), {len(e.args)} given",
                               e.loc)
        for arg, param in zip(e.args, func.params, strict=True):
            if param.dims:
                if not isinstance(arg, ast.Name):
                    raise CompileError(f"parameter '{param.name}' is an array: pass an array's name", arg.loc)
                sym = self.array(arg.name, arg.text, arg.loc)
                if sym.type != param.type:
                    raise CompileError(f"'{arg.text}' is a {sym.type.upper()} array; parameter '{param.name}' "
                                       f"takes {param.type.upper()}[]", arg.loc)
                self.push_array(sym)
            else:
                self.convert(self.expr(arg), param.type)
        self.emit(Op.CALL, index)
        return func.type

    def e_CmdExpr(self, e: ast.CmdExpr) -> str:
        result = self.command(e)
        if result == "none":
            raise CompileError(f"'{e.command.name}' does not return a value", e.loc)
        return result

    def call_entry(self, name: str, argc: int, axis: bool, returns: str) -> int:
        self.img.calls.append(image.CommandCall(name, argc, axis, returns))
        return len(self.img.calls) - 1

    def command(self, e: ast.CmdExpr) -> str:
        cmd = e.command
        name = cmd.name
        if name == "PI":
            self.emit(Op.PUSHD, self.const_double(3.141592653589793))
            return DOUBLE
        if name in MATH_FUNCTIONS or name in ("FABS", "ABS"):
            t = self.expr(e.args[0])
            if name == "ABS" and t == LONG:
                self.emit(Op.ABS)
                return LONG
            self.convert(t, DOUBLE)
            self.emit(Op.FABS if name in ("FABS", "ABS") else Op.MATH,
                      0 if name in ("FABS", "ABS") else MATH_FUNCTIONS.index(name))
            return DOUBLE
        if name == "CHR":
            raise CompileError("CHR(n) is only allowed as a PRINT item", e.loc)
        if e.axis is not None:
            axis = fold_int(e.axis)
            if axis is not None and axis != 1:
                self.sink.warning(f"the MCO 305 has one axis; axis {axis} raises error 103", e.axis.loc)
            self.to_long(self.expr(e.axis))
        for spec, arg in zip(_expanded_specs(cmd, len(e.args)), e.args, strict=True):
            self.argument(spec, arg)
        if (note := unserved_note(name)) is not None:
            self.sink.warning(note, e.loc)
        self.emit(Op.CMD, self.call_entry(name, len(e.args), e.axis is not None, cmd.returns))
        return cmd.returns

    def argument(self, spec, arg: ast.Expr) -> None:
        if spec.kind == "param" and isinstance(arg, ast.Name) and self.lookup(arg.name) is None \
                and arg.name not in self.assigned:
            raise CompileError(f"'{arg.text}' is not a parameter name (error 112 on the controller); give its "
                               "code name (KPROP) or number (3260)", arg.loc)
        if isinstance(arg, (ast.Word, ast.Str)):
            self.emit(Op.PUSHS, self.const_string(arg.word if isinstance(arg, ast.Word) else arg.value))
        elif isinstance(arg, ast.ArrayArg):
            self.push_array(self.array(arg.name, arg.text, arg.loc))
        elif isinstance(arg, ast.ParamRef):
            self.emit(Op.PUSH, arg.number)
        elif isinstance(arg, ast.OutRef):
            target = arg.target
            if isinstance(target, ast.Name):
                sym = self.scalar(target.name, target.text, target.loc, assigning=True)
                self.emit(Op.REFL if sym.kind == "local" else Op.REFG, sym.slot)
            elif isinstance(target, ast.Index):
                self.element_address(target)
                if len(target.indices) == 2:
                    raise CompileError("an output argument must be a variable or a 1-D array element", arg.loc)
                self.emit(Op.REFE)
            else:
                raise CompileError("an output argument must be a variable or an array element", arg.loc)
        else:
            self.to_long(self.expr(arg))


def _expanded_specs(cmd, count: int) -> list:
    specs = list(cmd.args)
    if specs and specs[-1].repeat:
        specs = specs[:-1] + [specs[-1]] * max(1, count - len(specs) + 1)
    return specs[:count]
