"""Whole-program checks of a DPL program: tasks, names, arrays, calls, labels. Reports every problem it finds
(GCC style, like the APOSS compiler) and returns the symbols the runtime needs."""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass, field

from motiontool.dpl import ast
from motiontool.dpl.definitions import definitions
from motiontool.dpl.functions import Function, function_table
from motiontool.language.diagnostics import DiagnosticSink, Location

RUN_TASKS = ("Initial", "Background", "Pos0", "Pos1")
POS_TASKS = ("Pos0", "Pos1")
MAX_ARRAY = 65535
# The PLC registers _Pxx% … _Uxx% are the module's menus 70 … 75 (SM-Applications user guide; docs/decisions.md A55).
REGISTER_MENUS = {"P": 70, "Q": 71, "R": 72, "S": 73, "T": 74, "U": 75}
_REGISTER = re.compile(r"_([PQRSTU])(\d\d)%")
_INT32 = (-(1 << 31), (1 << 31) - 1)


@dataclass
class Symbols:
    variables: set[str] = field(default_factory=set)            # scalar integer variables, upper case
    arrays: dict[str, int] = field(default_factory=dict)        # DIM name → size
    consts: dict[str, list[int]] = field(default_factory=dict)  # CONST name → values
    labels: dict[str, dict[str, Location]] = field(default_factory=dict)  # task → label → place


def register_parameter(name: str) -> tuple[int, int] | None:
    """The drive parameter behind a PLC register name (``_P01%`` → (70, 1)); None for other names."""
    m = _REGISTER.fullmatch(name.upper())
    return (REGISTER_MENUS[m.group(1)], int(m.group(2))) if m else None


class ConstantError(ValueError):
    pass


def fold(expr: ast.Expr) -> int:
    """The value of a constant expression (numbers, definitions, + - * / & | and unary minus)."""
    if isinstance(expr, ast.Num):
        return expr.value
    if isinstance(expr, ast.Alias):
        d = definitions().get(expr.name)
        if d is None:
            raise ConstantError(f"unknown name '{expr.text}'")
        return d.value
    if isinstance(expr, ast.Unary) and expr.op == "-":
        return _in_range(-fold(expr.operand))
    if isinstance(expr, ast.Binary) and expr.op in "+-*/&|":
        a, b = fold(expr.left), fold(expr.right)
        if expr.op == "/":
            if b == 0:
                raise ConstantError("division by zero")
            q = abs(a) // abs(b)
            return _in_range(-q if (a < 0) != (b < 0) else q)
        return _in_range({"+": a + b, "-": a - b, "*": a * b, "&": a & b, "|": a | b}[expr.op])
    raise ConstantError("a constant is needed here (numbers, definitions and + - * /)")


def _in_range(value: int) -> int:
    if not _INT32[0] <= value <= _INT32[1]:
        raise ConstantError(f"constant {value} does not fit in 32 bits")
    return value


def check_program(program: ast.Program, sink: DiagnosticSink) -> Symbols:
    return Checker(program, sink).run()


class Checker:
    def __init__(self, program: ast.Program, sink: DiagnosticSink):
        self.program = program
        self.sink = sink
        self.symbols = Symbols()
        self.functions = function_table()
        self.defs = definitions()
        self.assigned: set[str] = set()
        self.read: dict[str, ast.Var] = {}  # first read of each variable
        self.task = ""

    def run(self) -> Symbols:
        for task in self.program.tasks.values():
            if task.name not in RUN_TASKS and task.name != "Notes":
                self.sink.error(f"the {task.name} task is not run by this simulator (it runs Initial, "
                                "Background, Pos0 and Pos1)", task.loc)
        self._declarations()
        for task in self.program.tasks.values():
            self.task = task.name
            self._collect_labels(task.body, self.symbols.labels.setdefault(task.name, {}))
        for task in self.program.tasks.values():
            self.task = task.name
            self._statements(task.body)
        for name, v in self.read.items():
            if name not in self.assigned and register_parameter(name) is None:
                self.sink.warning(f"'{v.text}' is read but never assigned anywhere (it stays 0)", v.loc)
        if not any(t in self.program.tasks for t in RUN_TASKS):
            self.sink.warning("the program has no Initial, Background, Pos0 or Pos1 task: nothing runs",
                              self.program.loc)
        return self.symbols

    # --- declarations ----------------------------------------------------------------------------------------
    def _declarations(self) -> None:
        dims: list[ast.Dim] = []
        for task in self.program.tasks.values():
            dims += [s for s in _walk(task.body) if isinstance(s, ast.Dim)]
        seen: dict[str, Location] = {}
        for d in dims:
            size = self._constant(d.size, f"the size of {d.text}")
            if d.name in seen:
                self.sink.error(f"{d.text} is DIMensioned twice (first at {seen[d.name]})", d.loc)
                continue
            seen[d.name] = d.loc
            if size is not None and not 1 <= size <= MAX_ARRAY:
                self.sink.error(f"the size of {d.text} must be 1 … {MAX_ARRAY}, not {size}", d.size.loc)
            self.symbols.arrays[d.name] = size if size is not None and 1 <= size <= MAX_ARRAY else 1
        for c in self.program.consts:
            if c.name in seen:
                self.sink.error(f"{c.text} is declared twice (first at {seen[c.name]})", c.loc)
                continue
            seen[c.name] = c.loc
            folded = [self._constant(v, f"a value of {c.text}") for v in c.values]
            values = [v if v is not None else 0 for v in folded]
            size = self._constant(c.size, f"the size of {c.text}") if c.size is not None else len(values)
            if not values:
                self.sink.error(f"CONST {c.text} has no values", c.loc)
            elif size is not None and size != len(values):
                self.sink.error(f"CONST {c.text}[{size}] is given {len(values)} values", c.loc)
            self.symbols.consts[c.name] = values

    def _constant(self, expr: ast.Expr, what: str) -> int | None:
        try:
            return fold(expr)
        except ConstantError as exc:
            self.sink.error(f"{what}: {exc}", expr.loc)
            return None

    def _collect_labels(self, body: list[ast.Stmt], labels: dict[str, Location]) -> None:
        for s in _walk(body):
            if isinstance(s, ast.Label):
                if s.name in labels:
                    self.sink.error(f"label '{s.text}' is defined twice in the {self.task} task (first at "
                                    f"{labels[s.name]})", s.loc)
                else:
                    labels[s.name] = s.loc

    # --- statements ------------------------------------------------------------------------------------------
    def _statements(self, body: list[ast.Stmt]) -> None:
        for s in body:
            if isinstance(s, ast.Assign):
                self._expr(s.value)
                self._target(s.target)
            elif isinstance(s, ast.TupleAssign):
                fn = self._call(s.call)
                for target in s.targets:
                    self._target(target)
                if fn is not None and len(s.targets) != len(fn.returns):
                    self.sink.error(f"{fn.name} gives {len(fn.returns)} result"
                                    f"{'s' if len(fn.returns) > 1 else ''} ({', '.join(fn.returns)}), "
                                    f"not {len(s.targets)}", s.loc)
            elif isinstance(s, ast.CallStmt):
                self._call(s.call)
            elif isinstance(s, ast.If):
                for cond, branch in s.branches:
                    self._expr(cond)
                    self._statements(branch)
                if s.orelse is not None:
                    self._statements(s.orelse)
            elif isinstance(s, ast.Goto):
                self._goto(s)
            elif isinstance(s, ast.Reinit) and self.task != "Initial":
                self.sink.warning("REINIT belongs in the Initial task (after the #81 set-up)", s.loc)

    def _goto(self, s: ast.Goto) -> None:
        if s.name in self.symbols.labels.get(self.task, {}):
            return
        elsewhere = [t for t, labels in self.symbols.labels.items() if s.name in labels]
        where = f"; labels belong to one task and '{s.text}' is in the {elsewhere[0]} task" if elsewhere else ""
        self.sink.error(f"label '{s.text}' is not defined in the {self.task} task{where}", s.loc)

    def _target(self, target: ast.Expr) -> None:
        if isinstance(target, ast.Bit):
            self._target(target.base)
        elif isinstance(target, ast.Var):
            if self._scalar(target):
                self.assigned.add(target.name)
        elif isinstance(target, ast.Elem):
            if target.name in self.symbols.consts:
                self.sink.error(f"{target.text} is a CONST array (in flash): it cannot be written", target.loc)
            self._element(target)
        elif isinstance(target, ast.Param):
            self._param(target)

    # --- expressions -----------------------------------------------------------------------------------------
    def _expr(self, e: ast.Expr) -> None:
        if isinstance(e, ast.Var):
            if self._scalar(e):
                self.read.setdefault(e.name, e)
        elif isinstance(e, ast.Elem):
            self._element(e)
        elif isinstance(e, ast.Param):
            self._param(e)
        elif isinstance(e, ast.Alias):
            self._alias(e)
        elif isinstance(e, ast.Bit):
            self._expr(e.base)
        elif isinstance(e, ast.Call):
            self._call(e)
        elif isinstance(e, ast.Unary):
            self._expr(e.operand)
        elif isinstance(e, ast.Binary):
            self._expr(e.left)
            self._expr(e.right)
            if e.op == "/" and isinstance(e.right, ast.Num) and e.right.value == 0:
                self.sink.error("division by zero", e.right.loc)

    def _scalar(self, v: ast.Var) -> bool:
        if v.name in self.symbols.arrays or v.name in self.symbols.consts:
            self.sink.error(f"{v.text} is an array: give an element, e.g. {v.text}[0]", v.loc)
            return False
        if v.name.startswith("_") and register_parameter(v.name) is None:
            self.sink.error(f"{v.text}: PLC registers are _P00% … _U99% (names starting '_' are reserved)", v.loc)
            return False
        self.symbols.variables.add(v.name)
        return True

    def _element(self, e: ast.Elem) -> None:
        self._expr(e.index)
        size = self.symbols.arrays.get(e.name)
        if size is None and e.name in self.symbols.consts:
            size = len(self.symbols.consts[e.name])
        if size is None:
            self.sink.error(f"{e.text} is not an array: DIM {e.text}[size] first", e.loc)
        elif isinstance(e.index, ast.Num) and not 0 <= e.index.value < size:
            self.sink.error(f"index {e.index.value} is outside {e.text}[0 … {size - 1}]", e.index.loc)

    def _param(self, p: ast.Param) -> None:
        if not (0 <= p.menu <= 99 and 0 <= p.number <= 99):
            self.sink.error(f"drive parameter #{p.menu}.{p.number}: menus and parameters are 0 … 99", p.loc)

    def _alias(self, a: ast.Alias) -> None:
        d = self.defs.get(a.name)
        if d is None:
            hint = _suggest(a.name, list(self.defs))
            self.sink.error(f"unknown name '{a.text}'{hint} (integer variables end with '%')", a.loc)
        elif d.note:
            self.sink.warning(f"{d.name} is {d.value}; the manual prints the name twice ({d.note})", a.loc)

    def _call(self, call: ast.Call) -> Function | None:
        fn = self.functions.get(call.name)
        if fn is None:
            hint = _suggest(call.name, [f.name.upper() for f in self.functions.values()], self.functions)
            self.sink.error(f"unknown function '{call.text}'{hint}", call.loc)
            for arg in call.args:
                self._expr(arg)
            return None
        if len(call.args) != len(fn.args):
            self.sink.error(f"{fn.name} takes {len(fn.args)} argument{'s' if len(fn.args) != 1 else ''} "
                            f"({', '.join(fn.args) or 'none'}), not {len(call.args)}", call.loc)
        for n, arg in enumerate(call.args):
            if n < len(fn.args) and fn.takes_array(n):
                if not (isinstance(arg, ast.Var) and (arg.name in self.symbols.arrays
                                                      or arg.name in self.symbols.consts)):
                    self.sink.error(f"{fn.name}: {fn.args[n]} is the name of a DIM or CONST array", arg.loc)
            else:
                self._expr(arg)
        if not fn.simulated:
            self.sink.warning(f"{fn.name} is not simulated (the SM-Applications manual documents it, not the APC "
                              "manual); the program stops when it gets here", call.loc)
        if fn.tasks == "pos" and self.task not in POS_TASKS:
            self.sink.warning(f"{fn.name} belongs in a POS task (Pos0/Pos1), not {self.task} (seed 004 "
                              f"{fn.src.split(',')[0]})", call.loc)
        return fn


def _suggest(name: str, known: list[str], functions: dict | None = None) -> str:
    close = difflib.get_close_matches(name, known, n=1, cutoff=0.8)
    if not close:
        return ""
    shown = functions[close[0]].name if functions else close[0]
    return f"; did you mean {shown}?"


def _walk(body: list[ast.Stmt]):
    """Every statement, nested ones included, in source order."""
    for s in body:
        yield s
        if isinstance(s, ast.If):
            for _, branch in s.branches:
                yield from _walk(branch)
            if s.orelse is not None:
                yield from _walk(s.orelse)
