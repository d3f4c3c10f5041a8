"""Code generation: checked AST → ProgramImage, resolving names and types on the way.

Scopes: a function's parameters and locals, then globals (declared LONG/DOUBLE scalars and arrays, DIM
arrays, and LONG variables created by their first assignment unless #pragma NOIMPLICIT, DG 6530-6543).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from motiontool.aposs import ast, image, semantics
from motiontool.aposs.ast import DOUBLE, LONG
from motiontool.aposs.codegen_expr import ExpressionCode
from motiontool.aposs.constexpr import fold_int
from motiontool.aposs.image import BINOP_OF, PSEUDO_ARRAYS, SELECTOR_CODES, Op
from motiontool.aposs.verify import MAX_VARIABLE_ELEMENTS
from motiontool.language.diagnostics import Cancelled, CompileError, DiagnosticSink, Location


@dataclass
class Symbol:
    kind: str          # "global" | "local" | "array" (global var array) | "dim" | "larray" (local/param array)
    slot: int
    type: str
    dims: list[int]
    loc: Location | None
    implicit: bool = False  # created by its first use, not declared


class CodeGen(ExpressionCode):
    def __init__(self, program: ast.Program, sink: DiagnosticSink, name: str, debug: bool,
                 files: list[str]):
        self.program = program
        self.sink = sink
        self.img = image.ProgramImage(name=name, debug=debug, files=list(files))
        self.globals: dict[str, Symbol] = {}
        self.locals: dict[str, Symbol] | None = None
        self.current_function: image.Function | None = None
        self.functions: dict[str, int] = {}          # name → index in img.functions
        self.declared_functions: set[str] = set()    # declared so far in source order
        self.func_nodes: dict[str, ast.Function] = {}
        self.subs = {s.name: i for i, s in enumerate(program.subprograms)}
        self.noimplicit = False
        self.assigned = _assigned_names(program)
        self.never_assigned_warned: set[str] = set()
        self.labels: dict[str, int] = {}
        self.label_fixups: list[tuple[int, str]] = []
        self.loop_fixups: list[tuple[int, str]] = []
        self.break_targets: list[list[int]] = []
        self.statement_pc = 0  # pc of the statement being generated (mark_statement)
        self._temps = 0
        self._doubles: dict[float, int] = {}
        self._strings: dict[str, int] = {}

    # --- emission ---------------------------------------------------------------------------------
    def emit(self, op: Op, arg: int = 0) -> int:
        self.img.code += (int(op), int(arg))
        return len(self.img.code) // 2 - 1

    def patch(self, pc: int, target: int) -> None:
        self.img.code[2 * pc + 1] = target

    @property
    def pc(self) -> int:
        return len(self.img.code) // 2

    def const_double(self, value: float) -> int:
        if value not in self._doubles:
            self._doubles[value] = len(self.img.doubles)
            self.img.doubles.append(value)
        return self._doubles[value]

    def const_string(self, value: str) -> int:
        if value not in self._strings:
            self._strings[value] = len(self.img.strings)
            self.img.strings.append(value)
        return self._strings[value]

    def mark_statement(self, stmt: ast.Stmt) -> None:
        loc = stmt.loc
        file = self.img.files.index(loc.file) if loc.file in self.img.files else 0
        self.statement_pc = self.pc  # where the statement begins: before its STMT stop in a debug build
        self.img.lines.append(image.LineEntry(self.pc, file, loc.line, loc.col))
        if self.img.debug:
            self.emit(Op.STMT, len(self.img.lines) - 1)

    # --- program ------------------------------------------------------------------------------------
    def generate(self) -> image.ProgramImage:
        pending: list[tuple[ast.Function, bool, set[str]]] = []
        sub_snapshot: set[str] = set()
        for kind, item in self.program.order:
            if kind == "stmt":
                self.statement(item)
            elif kind == "func":
                self.declare_function(item)
                if item.body is not None:
                    pending.append((item, self.noimplicit, set(self.declared_functions)))
            elif kind == "subarea":
                sub_snapshot = set(self.declared_functions)
        main_declared = self.declared_functions
        self._resolve_labels()
        self.emit(Op.END)
        self.declared_functions = sub_snapshot  # DG 6621: a function is known from its declaration on
        for i, sub in enumerate(self.program.subprograms):
            self.img.subprograms.append(image.Subprogram(sub.text, self.pc))
            self.labels, self.label_fixups, self.loop_fixups = {}, [], []
            self.block(sub.body)
            self._resolve_labels()
            self.mark_statement(ast.Return(sub.end, None))
            self.emit(Op.RETSUB)
            assert len(self.img.subprograms) == i + 1
        for func, noimplicit, declared in pending:
            self.noimplicit = noimplicit
            self.declared_functions = declared
            self.function_body(func)
        self.declared_functions = main_declared
        self._warn_label_clashes()
        return self.img

    def _resolve_labels(self) -> None:
        for pc, name in self.label_fixups:
            self.patch(pc, self.labels.get(name, 0))
        for index, name in self.loop_fixups:
            self.img.loops[index][1] = self.labels.get(name, 0)

    def _warn_label_clashes(self) -> None:
        bodies = [self.program.statements] + [s.body for s in self.program.subprograms] + \
            [f.body for f in self.program.functions if f.body]
        for body in bodies:
            for stmt in ast.walk(body):
                if isinstance(stmt, ast.Label) and stmt.name in self.globals:
                    self.sink.error(f"label '{stmt.text}' has the name of a variable (DG 6425)", stmt.loc)

    # --- names --------------------------------------------------------------------------------------
    def lookup(self, name: str) -> Symbol | None:
        if self.locals is not None and name in self.locals:
            return self.locals[name]
        return self.globals.get(name)

    def new_global(self, name: str, text: str, type_: str, loc: Location | None) -> Symbol:
        sym = Symbol("global", len(self.img.globals), type_, [], loc)
        self.img.globals.append(image.Variable(text, type_))
        self.globals[name] = sym
        return sym

    def temp(self) -> int:
        self._temps += 1
        return self.new_global(f"$T{self._temps}", f"$T{self._temps}", LONG, None).slot

    def scalar(self, name: str, text: str, loc: Location, assigning: bool) -> Symbol:
        sym = self.lookup(name)
        if sym is None:
            if name in self.subs or name in self.functions:
                raise CompileError(f"'{text}' is a {'SUBPROG' if name in self.subs else 'function'}, "
                                   "not a variable", loc)
            if self.noimplicit:
                raise CompileError(f"'{text}' is not declared (#pragma NOIMPLICIT is in force: declare it "
                                   f"with 'long {text}' or 'double {text}')", loc)
            if not assigning and name not in self.assigned and name not in self.never_assigned_warned:
                self.never_assigned_warned.add(name)
                self.sink.warning(f"'{text}' is never assigned; it always reads 0", loc)
            sym = self.new_global(name, text, LONG, loc)
            sym.implicit = True
        if sym.kind in ("array", "dim", "larray"):
            raise CompileError(f"'{text}' is an array; give an element, e.g. {text}[1]", loc)
        return sym

    def array(self, name: str, text: str, loc: Location) -> Symbol:
        sym = self.lookup(name)
        if sym is None:
            raise CompileError(f"array '{text}' is not declared (DIM {text}[n] or long {text}[n])", loc)
        if sym.kind not in ("array", "dim", "larray"):
            raise CompileError(f"'{text}' is not an array", loc)
        return sym

    def push_array(self, sym: Symbol) -> None:
        self.emit({"dim": Op.ARRDIM, "array": Op.ARRG, "larray": Op.ARRL}[sym.kind], sym.slot)

    # --- declarations -------------------------------------------------------------------------------
    def declare(self, decl: ast.Declarator, type_: str, kind: str) -> None:
        scope = self.locals if (self.locals is not None and kind != "dim") else self.globals
        old = scope.get(decl.name)
        if old is not None:
            where = f" at {old.loc}" if old.loc else ""
            if old.implicit:
                raise CompileError(f"'{decl.text}' is used before its declaration (first use{where})", decl.loc)
            raise CompileError(f"'{decl.text}' is already declared{where}", decl.loc)
        if decl.name in self.subs or decl.name in self.functions:
            raise CompileError(f"'{decl.text}' is already the name of a SUBPROG or function", decl.loc)
        if kind == "dim":
            size = decl.dims[0] * (decl.dims[1] if len(decl.dims) > 1 else 1)
            scope[decl.name] = Symbol("dim", len(self.img.dims), LONG, decl.dims, decl.loc)
            self.img.dims.append(image.Variable(decl.text, LONG, list(decl.dims)))
            if size > 1_000_000:
                self.sink.warning(f"array '{decl.text}' has {size} elements; the controller's memory is far "
                                  "smaller", decl.loc)
        elif self.locals is not None:
            func = self.current_function
            assert func is not None  # function_body sets it with self.locals and clears both
            kind_ = "larray" if decl.dims else "local"
            scope[decl.name] = Symbol(kind_, len(func.locals), type_, decl.dims, decl.loc)
            func.locals.append(image.Variable(decl.text, type_, list(decl.dims)))
        elif decl.dims:
            total = sum(math.prod(a.dims) for a in self.img.arrays) + math.prod(decl.dims)
            if total > MAX_VARIABLE_ELEMENTS:  # the controller must be able to hold them (decisions L23)
                raise CompileError(f"array '{decl.text}' makes the variable arrays {total} elements; the controller "
                                   f"holds at most {MAX_VARIABLE_ELEMENTS} (DIM arrays are separate)", decl.loc)
            scope[decl.name] = Symbol("array", len(self.img.arrays), type_, decl.dims, decl.loc)
            self.img.arrays.append(image.Variable(decl.text, type_, list(decl.dims)))
        else:
            sym = self.new_global(decl.name, decl.text, type_, decl.loc)
            sym.loc = decl.loc

    def declare_function(self, func: ast.Function) -> None:
        self.declared_functions.add(func.name)
        if func.name not in self.functions:
            params = [image.Variable(p.text, p.type, [0] if p.is_array else []) for p in func.params]
            self.functions[func.name] = len(self.img.functions)
            self.img.functions.append(image.Function(func.text, func.type, -1, params, list(params)))
        if func.body is not None:
            self.func_nodes[func.name] = func

    def function_body(self, func: ast.Function) -> None:
        entry = self.img.functions[self.functions[func.name]]
        entry.entry = self.pc
        entry.locals = list(entry.params)
        self.current_function = entry
        self.locals = {}
        for i, p in enumerate(func.params):
            if p.name in self.locals:
                self.sink.error(f"parameter '{p.text}' appears twice", p.loc)
            self.locals[p.name] = Symbol("larray" if p.is_array else "local", i, p.type, [0] if p.is_array else [],
                                         p.loc)
        self.labels, self.label_fixups, self.loop_fixups = {}, [], []
        assert func.body is not None  # generate() passes only functions with a body, not prototypes
        self.block(func.body)
        self._resolve_labels()
        self.emit(Op.PUSH, 0)  # falling off the end returns 0 (C:3735-3744 has functions without return)
        if func.type == DOUBLE:
            self.emit(Op.I2D)
        self.emit(Op.RET)
        self.locals = None
        self.current_function = None

    # --- statements ---------------------------------------------------------------------------------
    def block(self, body: list[ast.Stmt]) -> None:
        for stmt in body:
            self.statement(stmt)

    cancelled = None  # a callable: True when the caller no longer wants the result

    def statement(self, stmt: ast.Stmt) -> None:
        if self.cancelled is not None and self.cancelled():
            raise Cancelled
        try:
            if not isinstance(stmt, (ast.Dim, ast.VarDecl, ast.Pragma, ast.Label)):
                self.mark_statement(stmt)
            getattr(self, "s_" + type(stmt).__name__)(stmt)
        except CompileError as exc:
            self.sink.add(exc.diagnostic)
        except semantics.OperatorError as exc:
            self.sink.error(str(exc), stmt.loc)
        except RecursionError:
            self.sink.error("expression nested too deeply", stmt.loc)

    def s_Pragma(self, s: ast.Pragma) -> None:
        self.noimplicit = s.value == "NOIMPLICIT"

    def s_Dim(self, s: ast.Dim) -> None:
        for decl in s.arrays:
            self.declare(decl, LONG, "dim")

    def s_VarDecl(self, s: ast.VarDecl) -> None:
        for decl in s.names:
            self.declare(decl, s.type, "var")

    def s_Label(self, s: ast.Label) -> None:
        self.labels[s.name] = self.pc

    def s_Goto(self, s: ast.Goto) -> None:
        self.label_fixups.append((self.emit(Op.JMP), s.label))

    def s_Loop(self, s: ast.Loop) -> None:
        count = fold_int(s.count)
        if count is not None and count < 0:
            raise CompileError("LOOP needs a count of 0 or more", s.count.loc)
        if s.label not in self.labels and any(isinstance(x, ast.Label) and x.name == s.label
                                              for x in ast.walk(self._unit_body(s))):
            raise CompileError(f"LOOP jumps back: label '{s.text}' must come before the LOOP", s.loc)
        self.to_long(self.expr(s.count))
        index = len(self.img.loops)
        self.img.loops.append([self.temp(), 0])
        self.loop_fixups.append((index, s.label))
        self.emit(Op.LOOP, index)

    def _unit_body(self, stmt: ast.Stmt) -> list[ast.Stmt]:
        bodies = [self.program.statements] + [s.body for s in self.program.subprograms] + \
            [f.body for f in self.program.functions if f.body]
        for body in bodies:
            if any(x is stmt for x in ast.walk(body)):
                return body
        return []

    def s_Gosub(self, s: ast.Gosub) -> None:
        self.emit(Op.GOSUB, self.subs.get(s.name, 0))

    def s_Exit(self, s: ast.Exit) -> None:
        self.emit(Op.END)

    def s_Break(self, s: ast.Break) -> None:
        if self.break_targets:
            self.break_targets[-1].append(self.emit(Op.JMP))

    def s_Return(self, s: ast.Return) -> None:
        func = self.current_function
        assert func is not None  # the parser takes RETURN only inside a function's body (Parser._stmt_return)
        if s.value is None:
            self.emit(Op.PUSH, 0)
            self.convert(LONG, func.type)
        else:
            self.convert(self.expr(s.value), func.type)
        self.emit(Op.RET)

    def s_Assign(self, s: ast.Assign) -> None:
        target = self.stable(s.target) if isinstance(s.target, ast.BitSel) else s.target
        self.store(target, lambda: self.expr(s.value), s.value)

    def s_ArrayCopy(self, s: ast.ArrayCopy) -> None:
        dest = self.array(s.dest, s.dest_text, s.loc)
        src = self.array(s.source, s.source_text, s.loc)
        if dest.type != src.type:
            raise CompileError("an array copy needs two arrays of the same type", s.loc)
        self.push_array(dest)
        self.push_array(src)
        self.emit(Op.COPYA)

    def stable(self, target: ast.Expr) -> ast.Expr:
        """The same place with its indices computed once into temporaries (for read-modify-write)."""
        if isinstance(target, ast.BitSel):
            return ast.BitSel(target.loc, target.kind, self.stable(target.base), target.index)
        if isinstance(target, ast.Index) and any(not isinstance(i, ast.Num) for i in target.indices):
            fixed: list[ast.Expr] = []
            for index in target.indices:
                if isinstance(index, ast.Num):
                    fixed.append(index)
                    continue
                self.to_long(self.expr(index))
                slot = self.temp()
                self.emit(Op.STOREG, slot)
                fixed.append(ast.Name(index.loc, self.img.globals[slot].name.upper(), self.img.globals[slot].name))
            return ast.Index(target.loc, target.name, target.text, fixed)
        if isinstance(target, ast.Pseudo) and not isinstance(target.index, ast.Num):
            self.to_long(self.expr(target.index))
            slot = self.temp()
            self.emit(Op.STOREG, slot)
            name = self.img.globals[slot].name
            return ast.Pseudo(target.loc, target.name, ast.Name(target.loc, name.upper(), name))
        return target

    def s_ExprStmt(self, s: ast.ExprStmt) -> None:
        if isinstance(s.expr, ast.PostIncrement):
            target = self.stable(s.expr.target)
            self.store(target, lambda: self._incremented(target, s.expr.op))
            return
        self.expr(s.expr)
        self.emit(Op.POP)

    def _incremented(self, target: ast.Expr, op: str) -> str:
        t = self.expr(target)
        if t == LONG:
            self.emit(Op.PUSH, 1)
            self.emit(Op.BIN, BINOP_OF["+" if op == "++" else "-"])
        else:
            self.emit(Op.PUSHD, self.const_double(1.0))
            self.emit(Op.BIND, BINOP_OF["+" if op == "++" else "-"])
        return t

    def s_Command(self, s: ast.Command) -> None:
        if self.command(s.call) != "none":
            self.emit(Op.POP)

    def s_PrintStmt(self, s: ast.PrintStmt) -> None:
        if s.device is not None:
            self.to_long(self.expr(s.device))
            self.emit(Op.CMD, self.call_entry("PRINTDEV", 1, False, "none"))
        for item in s.items:
            if isinstance(item, ast.Str):
                self.emit(Op.PRINTS, self.const_string(item.value))
            elif isinstance(item, ast.CmdExpr) and item.command.name == "CHR":
                self.to_long(self.expr(item.args[0]))
                self.emit(Op.PRINTC)
            else:
                self.expr(item)
                self.emit(Op.PRINTV)
        if s.device is None or s.items:  # `PRINTDEV -1` alone only switches the device: no empty line
            self.emit(Op.PRINTNL, int(s.newline))

    def s_If(self, s: ast.If) -> None:
        ends = []
        for cond, body in s.branches:
            self.truth(cond)
            skip = self.emit(Op.JZ)
            self.block(body)
            ends.append(self.emit(Op.JMP))
            self.patch(skip, self.pc)
        if s.orelse is not None:
            self.block(s.orelse)
        for pc in ends:
            self.patch(pc, self.pc)

    def s_While(self, s: ast.While) -> None:
        top = self.statement_pc  # each pass stops at the WHILE line again (single step, a breakpoint there)
        self.truth(s.cond)
        out = self.emit(Op.JZ)
        self.break_targets.append([out])
        self.block(s.body)
        self.emit(Op.JMP, top)
        for pc in self.break_targets.pop():
            self.patch(pc, self.pc)

    def s_Repeat(self, s: ast.Repeat) -> None:
        top = self.pc
        self.break_targets.append([])
        self.block(s.body)
        self.truth(s.cond)
        self.emit(Op.JZ, top)  # C:3613-3633: repeat until the condition becomes true
        for pc in self.break_targets.pop():
            self.patch(pc, self.pc)

    def s_Switch(self, s: ast.Switch) -> None:
        slot = self.temp()
        self.to_long(self.expr(s.value))
        self.emit(Op.STOREG, slot)
        tests: list[tuple[int, int]] = []
        seen: dict[int, Location] = {}
        default_index = None
        for i, (values, _, _) in enumerate(s.cases):
            if not values:
                default_index = i
            for v in values:
                value = fold_int(v)
                if value is None:
                    raise CompileError("CASE needs a constant integer", v.loc)
                if value in seen:
                    raise CompileError(f"CASE {value} appears twice (first at {seen[value]})", v.loc)
                seen[value] = v.loc
                self.emit(Op.LOADG, slot)
                self.emit(Op.PUSH, value)
                self.emit(Op.BIN, image.BinOp.EQ)
                tests.append((self.emit(Op.JNZ), i))
        no_match = self.emit(Op.JMP)
        self.break_targets.append([])
        starts = []
        for _, body, _ in s.cases:  # bodies in order: without BREAK a case falls through, as in C
            starts.append(self.pc)
            self.block(body)
        for pc, i in tests:
            self.patch(pc, starts[i])
        self.patch(no_match, starts[default_index] if default_index is not None else self.pc)
        for pc in self.break_targets.pop():
            self.patch(pc, self.pc)

    def s_OnInterrupt(self, s: ast.OnInterrupt) -> None:
        if s.value is not None and (value := fold_int(s.value)) is not None:
            problem = _interrupt_range(s.kind, value)
            if problem:
                raise CompileError(problem, s.value.loc)
            if s.kind == "PERIOD" and 0 < value < 20:
                self.sink.warning("ON PERIOD is checked every 20 ms; a shorter period cannot be kept (DG 6345)",
                                  s.value.loc)
        for operand in (s.value, s.setout, s.toin):
            if operand is not None:
                self.to_long(self.expr(operand))
        sub = self.subs.get(s.handler, 0) if s.handler else -1
        self.img.interrupts.append(image.Interrupt(s.kind, s.sign, sub, s.value is not None, s.setout is not None,
                                                   s.toin is not None, s.delete))
        self.emit(Op.INTR, len(self.img.interrupts) - 1)

    # --- stores -------------------------------------------------------------------------------------
    def store(self, target: ast.Expr, value, source: ast.Expr | None = None) -> None:
        """Store the value that `value()` pushes into target (converted to the target's type); `source`: the
        expression assigned, if any."""
        if isinstance(target, ast.Name):
            sym = self.scalar(target.name, target.text, target.loc, assigning=True)
            have = value()
            if have == DOUBLE and sym.type == LONG:
                self.sink.warning(f"the DOUBLE value is truncated to store it in LONG '{target.text}'; write "
                                  f"(long) to say so{_bit_hint(source)}", target.loc)
            self.convert(have, sym.type)
            self.emit(Op.STOREL if sym.kind == "local" else Op.STOREG, sym.slot)
        elif isinstance(target, ast.Index):
            sym = self.element_address(target)
            self.convert(value(), sym.type)
            self.emit(Op.STOREE2 if len(target.indices) == 2 else Op.STOREE)
        elif isinstance(target, ast.Pseudo):
            self.to_long(self.expr(target.index))
            self.to_long(value())
            self.emit(Op.STOREP, PSEUDO_ARRAYS.index(target.name))
        elif isinstance(target, ast.BitSel) and isinstance(target.base, (ast.Name, ast.Index, ast.Pseudo)):
            base = target.base

            def updated() -> str:
                if self.expr(base) != LONG:
                    raise CompileError("bit selectors need a LONG variable", target.loc)
                self.to_long(self.expr(target.index))
                self.to_long(value())
                self.emit(Op.BITSET, SELECTOR_CODES.index(target.kind))
                return LONG
            self.store(base, updated)
        else:
            raise CompileError("only a variable, an array element, SYSVAR/PCD/PDO or a bit of those can be "
                               "assigned", target.loc)

    def element_address(self, target: ast.Index) -> Symbol:
        sym = self.array(target.name, target.text, target.loc)
        if len(target.indices) == 2 and len(sym.dims) != 2:
            raise CompileError(f"'{target.text}' has one dimension; use {target.text}[i]", target.loc)
        self.push_array(sym)
        for index in target.indices:
            self.to_long(self.expr(index))
        return sym


def _interrupt_range(kind: str, value: int) -> str | None:
    """Constant operands of ON … outside what the controller accepts (C:2509-3091, D:7157)."""
    if kind == "INT" and value == 0:
        return "ON INT needs an input number other than 0 (negative = falling edge)"
    if kind == "COMBIT" and not (-32 <= value <= 32 and value != 0):
        return "ON COMBIT needs a bit number -32 … 32 other than 0"
    if kind == "STATBIT" and not (1 <= abs(value) <= 32):
        return "ON STATBIT needs a bit number 1 … 32"
    if kind == "CANINPUT" and value != 0:
        return "ON CANINPUT only takes the identifier 0"
    if kind in ("TIME", "PERIOD") and value < 0:
        return f"ON {kind} needs a time ≥ 0 ms"
    return None


def _assigned_names(program: ast.Program) -> set[str]:
    """Names that get a value somewhere (assignment, ++/--, output argument, declaration)."""
    names: set[str] = set()
    bodies = [program.statements] + [s.body for s in program.subprograms] + \
        [f.body for f in program.functions if f.body]
    for body in bodies:
        for stmt in ast.walk(body):
            if isinstance(stmt, ast.Assign):
                target = stmt.target.base if isinstance(stmt.target, ast.BitSel) else stmt.target
                if isinstance(target, ast.Name):
                    names.add(target.name)
            for e in ast.walk_exprs(stmt):
                if isinstance(e, (ast.OutRef, ast.PostIncrement)) and isinstance(e.target, ast.Name):
                    names.add(e.target.name)
    return names


def _bit_hint(source: ast.Expr | None) -> str:
    """DG 6734-6738 prints `7.1 = 1` (bit 1 of 7), written before DOUBLE constants (DG 6565-6577) existed (L2)."""
    if isinstance(source, ast.Num) and isinstance(source.value, float):
        whole, _, bit = repr(source.value).partition(".")
        # only a bit the number has (7.1, 7.3): 2.5 or 0.5 as a bit test would be pointless, so it meant a DOUBLE
        if bit.isdigit() and bit[0] != "0" and whole.isdigit() and 1 <= int(bit) <= int(whole).bit_length():
            return f"; {source.value!r} is a DOUBLE constant: bit {bit} of {whole} is written ({whole}).{bit}"
    return ""
