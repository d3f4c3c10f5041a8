"""DPL code generation: a checked program → one flat list of operations per task, each a Python closure.

An operation returns None (go on with the next one) or the index to jump to; IF blocks become conditional jumps,
so GOTO can reach any label of its task. Every value is a signed 32-bit integer: results wrap like the module's
registers (docs/decisions.md A51). Calls go to the drive's `call_dpl` (the APC kernel), except the language's
own IWINDOW.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from motiontool.dpl import ast
from motiontool.dpl.check import Symbols, fold, register_parameter
from motiontool.dpl.definitions import definitions
from motiontool.dpl.functions import function_table
from motiontool.language.diagnostics import Location

Op = Callable[[], "int | None"]
_MASK = 0xFFFFFFFF


def wrap32(value: int) -> int:
    value &= _MASK
    return value - 0x100000000 if value & 0x80000000 else value


class DplRuntimeError(Exception):
    """A run-time error of the program (the module would trip): the message and the place."""

    def __init__(self, message: str, loc: Location):
        super().__init__(f"{loc}: error: {message}")
        self.message = message
        self.loc = loc


@dataclass
class TaskCode:
    name: str
    ops: list[Op] = field(default_factory=list)
    locs: list[Location] = field(default_factory=list)   # the statement of each operation
    backward: list[bool] = field(default_factory=list)   # the operation may jump back (a loop's GOTO)


@dataclass
class Memory:
    """The program's variables and arrays (shared by all tasks, as in DPL)."""

    variables: dict[str, int]
    arrays: dict[str, list[int]]


def iwindow(value: int, target: int, below: int, above: int) -> int:
    """1 when target − below ≤ value ≤ target + above, the difference in 32-bit wrap (A58)."""
    difference = wrap32(value - target)
    return 1 if -below <= difference <= above else 0


class CodeGen:
    """Compiles the tasks of one checked program against one drive (an ApcDrive or anything with its
    `call_dpl` and `params`)."""

    def __init__(self, program: ast.Program, symbols: Symbols, drive, memory: Memory):
        self.program, self.symbols, self.drive, self.memory = program, symbols, drive, memory
        self.functions = function_table()
        self.defs = definitions()

    def task(self, name: str) -> TaskCode | None:
        task = self.program.tasks.get(name)
        if task is None:
            return None
        code = TaskCode(name)
        labels: dict[str, int] = {}
        fixups: list[tuple[int, str]] = []
        self._block(task.body, code, labels, fixups)
        for index, label in fixups:  # every GOTO target is known now (checks proved they exist)
            target = labels[label]
            code.ops[index] = (lambda t: lambda: t)(target)
            code.backward[index] = target <= index
        return code

    # --- statements ------------------------------------------------------------------------------------------
    def _emit(self, code: TaskCode, op: Op, loc: Location, backward: bool = False) -> int:
        code.ops.append(op)
        code.locs.append(loc)
        code.backward.append(backward)
        return len(code.ops) - 1

    def _block(self, body: list[ast.Stmt], code: TaskCode, labels: dict[str, int], fixups) -> None:
        for s in body:
            if isinstance(s, ast.Label):
                labels[s.name] = len(code.ops)
            elif isinstance(s, ast.Goto):
                fixups.append((self._emit(code, _nothing, s.loc), s.name))
            elif isinstance(s, ast.If):
                self._if(s, code, labels, fixups)
            elif isinstance(s, ast.Assign):
                self._emit(code, self._assign(s), s.loc)
            elif isinstance(s, ast.TupleAssign):
                self._emit(code, self._tuple(s), s.loc)
            elif isinstance(s, ast.CallStmt):
                call = self._call(s.call, targets=0)
                self._emit(code, _discard(call), s.loc)
            elif isinstance(s, ast.Reinit):
                self._emit(code, lambda: (self.drive.reinit(), None)[1], s.loc)
            elif isinstance(s, ast.Dim):  # executing a DIM clears the array
                self._emit(code, _clear(self.memory.arrays[s.name]), s.loc)
            # ConstArray: a declaration, nothing to execute

    def _if(self, s: ast.If, code: TaskCode, labels, fixups) -> None:
        ends: list[int] = []
        for cond, branch in s.branches:
            test = self._expr(cond)
            at = self._emit(code, _nothing, cond.loc)
            self._block(branch, code, labels, fixups)
            ends.append(self._emit(code, _nothing, cond.loc))
            after = len(code.ops)
            code.ops[at] = (lambda t, a: lambda: None if t() else a)(test, after)
        if s.orelse is not None:
            self._block(s.orelse, code, labels, fixups)
        end = len(code.ops)
        for index in ends:
            code.ops[index] = (lambda e: lambda: e)(end)

    def _assign(self, s: ast.Assign) -> Op:
        store = self._store(s.target)
        value = self._expr(s.value)
        return lambda: store(value())

    def _tuple(self, s: ast.TupleAssign) -> Op:
        stores = [self._store(t) for t in s.targets]
        call = self._call(s.call, targets=len(stores))

        def op():
            for store, value in zip(stores, call(), strict=True):
                store(value)
        return op

    # --- targets ---------------------------------------------------------------------------------------------
    def _store(self, target: ast.Expr) -> Callable[[int], None]:
        if isinstance(target, ast.Bit):
            read, write, bit = self._expr(target.base), self._store(target.base), 1 << target.bit
            return lambda v: write(read() | bit if v else read() & ~bit)
        if isinstance(target, ast.Var):
            register = register_parameter(target.name)
            if register is not None:
                return self._param_store(register)
            variables, name = self.memory.variables, target.name
            return lambda v: variables.__setitem__(name, wrap32(v))
        if isinstance(target, ast.Elem):
            data, index, loc = self.memory.arrays[target.name], self._expr(target.index), target.loc

            def store(v):
                i = index()
                if not 0 <= i < len(data):
                    raise DplRuntimeError(f"index {i} is outside {target.text}[0 … {len(data) - 1}]", loc)
                data[i] = wrap32(v)
            return store
        assert isinstance(target, ast.Param)  # the parser's targets: Bit, Var, Elem, Param
        return self._param_store((target.menu, target.number))

    def _param_store(self, key: tuple[int, int]) -> Callable[[int], None]:
        params = self.drive.params
        return lambda v: params.write(key, wrap32(v))

    # --- expressions -----------------------------------------------------------------------------------------
    def _expr(self, e: ast.Expr) -> Callable[[], int]:
        if isinstance(e, ast.Num | ast.Alias):
            value = fold(e)
            return lambda: value
        if isinstance(e, ast.Var):
            register = register_parameter(e.name)
            if register is not None:
                params = self.drive.params
                return lambda: params.read(register)
            variables, name = self.memory.variables, e.name
            return lambda: variables[name]
        if isinstance(e, ast.Elem):
            data, index, loc = self.memory.arrays[e.name], self._expr(e.index), e.loc

            def element():
                i = index()
                if not 0 <= i < len(data):
                    raise DplRuntimeError(f"index {i} is outside {e.text}[0 … {len(data) - 1}]", loc)
                return data[i]
            return element
        if isinstance(e, ast.Param):
            params, key = self.drive.params, (e.menu, e.number)
            return lambda: params.read(key)
        if isinstance(e, ast.Bit):
            base, bit = self._expr(e.base), e.bit
            return lambda: (base() >> bit) & 1
        if isinstance(e, ast.Call):
            call = self._call(e, targets=1)
            return lambda: call()[0]
        if isinstance(e, ast.Unary):
            x = self._expr(e.operand)
            if e.op == "-":
                return lambda: wrap32(-x())
            return lambda: 0 if x() else 1
        assert isinstance(e, ast.Binary)  # the last kind of ast.Expr
        return self._binary(e)

    def _binary(self, e: ast.Binary) -> Callable[[], int]:
        a, b, op = self._expr(e.left), self._expr(e.right), e.op
        if op == "+":
            return lambda: wrap32(a() + b())
        if op == "-":
            return lambda: wrap32(a() - b())
        if op == "*":
            return lambda: wrap32(a() * b())
        if op == "/":
            loc = e.loc

            def divide():
                x, y = a(), b()
                if y == 0:
                    raise DplRuntimeError("division by zero", loc)
                q = abs(x) // abs(y)
                return wrap32(-q if (x < 0) != (y < 0) else q)
            return divide
        if op == "AND":
            return lambda: 1 if a() and b() else 0
        if op == "OR":
            return lambda: 1 if a() or b() else 0
        return {"&": lambda: a() & b(), "|": lambda: a() | b(),
                "=": lambda: int(a() == b()), "<>": lambda: int(a() != b()), "<": lambda: int(a() < b()),
                ">": lambda: int(a() > b()), "<=": lambda: int(a() <= b()), ">=": lambda: int(a() >= b())}[op]

    def _call(self, call: ast.Call, targets: int) -> Callable[[], tuple]:
        fn = self.functions[call.name]
        loc = call.loc
        if fn.key == "IWINDOW":  # four integer expressions, no array
            values = [self._expr(a) for a in call.args]
            return lambda: (iwindow(*(v() for v in values)),)[:max(targets, 1)]
        args = [self._argument(fn, n, a) for n, a in enumerate(call.args)]
        if not fn.simulated:
            def refuse():
                raise DplRuntimeError(f"{fn.name} is not simulated (an SM-Applications call the APC manual does "
                                      "not document)", loc)
            return refuse
        drive, name = self.drive, fn.name
        method = getattr(drive, name, None)
        if callable(method):  # an APC call is the drive's own method (docs/apc.md): no name lookup per call
            def call_method():
                try:
                    result = method(*[a() for a in args])
                except (TypeError, ValueError, KeyError, ZeroDivisionError) as exc:
                    raise DplRuntimeError(f"{name}: {exc}", loc) from None
                values = result if isinstance(result, tuple) else (result,)
                if targets == len(values) + 1:  # the quick reference's extra Status% (APCGetOutputSpeed …): ok
                    return (*values, 1)
                return values[:targets]
            return call_method

        def invoke():  # the language's built-ins the kernel provides (MULDIV, the word blocks)
            try:
                return drive.call_dpl(name, tuple(a() for a in args), targets)
            except (TypeError, ValueError, KeyError, ZeroDivisionError) as exc:
                raise DplRuntimeError(f"{name}: {exc}", loc) from None
        return invoke

    def _argument(self, fn, position: int, arg: ast.Expr) -> Callable[[], object]:
        if fn.takes_array(position):  # the array itself: the kernel reads it live (L1528-1531)
            assert isinstance(arg, ast.Var)  # the checks refused anything but an array's name here
            data = self.memory.arrays[arg.name]
            return lambda: data
        return self._expr(arg)


def _nothing() -> None:
    return None


def _discard(call: Callable[[], object]) -> Op:
    """A call as a statement: its results are dropped, execution goes on with the next operation."""
    return lambda: (call(), None)[1]


def _clear(data: list[int]) -> Op:
    """Executing a DIM: every element of the array becomes 0."""
    return lambda: (data.__setitem__(slice(None), [0] * len(data)), None)[1]
