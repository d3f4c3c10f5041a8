"""The APOSS virtual machine: executes a ProgramImage instruction by instruction, a slice per control tick.

It knows nothing about motion: commands go to a host (the controller), which returns a value or a Wait
that the program blocks on. Interrupt handlers are entered between two instructions (DG 6287).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Protocol

from motiontool.aposs import semantics
from motiontool.aposs.image import MATH_FUNCTIONS, OPERATOR_OF, SELECTOR_CODES, CommandCall, Op, ProgramImage
from motiontool.kernel.errors import ControllerError

MAX_GOSUB_DEPTH = 10     # DG 11650-11658: error 151
DEFAULT_STACK_SIZE = 200  # Settings → Compiler, stack size (DG 3062); error 193


class ArrayRef:
    """An array: DIM arrays in controller memory, or program arrays. Indexes are 1-based outside."""

    __slots__ = ("name", "data", "dims", "type")

    def __init__(self, name: str, size: int, dims: list[int] | None = None, type_: str = "long"):
        self.name = name
        self.type = type_
        self.dims = dims or [size]
        self.data: list[Any] = [0.0 if type_ == "double" else 0] * size

    def __len__(self) -> int:
        return len(self.data)


class Ref:
    """A reference to a variable or element, handed to a command that writes an output argument."""

    __slots__ = ("container", "index", "type")

    def __init__(self, container: list, index: int, type_: str):
        self.container, self.index, self.type = container, index, type_

    def set(self, value: int | float) -> None:
        self.container[self.index] = float(value) if self.type == "double" else semantics.wrap(int(value))

    def get(self) -> int | float:
        return self.container[self.index]


class Wait:
    """A command the program waits for; the controller checks `done()` once per tick."""

    resumable = True  # after an interrupt handler the wait goes on (False: HOME is abandoned, CR 1498)
    value: int | float | None = None  # pushed when done, for commands that return a value

    def done(self) -> bool:
        raise NotImplementedError

    def resume(self) -> None:
        """Called when an interrupt handler returns to this wait."""

    def abandon(self) -> None:
        """Called when an interrupt abandons a wait that is not resumable (HOME, INDEX: CR 1498-1500)."""


class Host(Protocol):
    def command(self, vm: VM, call: CommandCall, args: list) -> Any: ...
    def dim_array(self, index: int, name: str, dims: list[int]) -> ArrayRef: ...
    def print_text(self, text: str) -> None: ...
    def print_room(self) -> bool: ...
    def define_interrupt(self, vm: VM, index: int, operands: list[int]) -> None: ...
    def read_pseudo(self, which: int, index: int) -> int: ...
    def statement_stop(self, vm: VM, line_index: int) -> bool: ...
    def write_pseudo(self, which: int, index: int, value: int) -> None: ...
    def interrupt_returned(self, vm: VM, kind: str) -> None: ...


class _OutputRoom(Wait):
    """PRINT waits while the controller's output buffer is full (the link has not taken the lines yet)."""

    def __init__(self, host) -> None:
        self.host = host

    def done(self) -> bool:
        return self.host.print_room()


@dataclass
class Frame:
    locals: list
    return_pc: int
    size: int


@dataclass
class SubReturn:
    return_pc: int
    sub: int
    interrupt: str | None = None      # the interrupt kind when this is a handler
    wait: Wait | None = None          # the wait the handler interrupted
    stack_depth: int = 0


@dataclass
class VM:
    image: ProgramImage
    host: Host
    stack_size: int = DEFAULT_STACK_SIZE
    pc: int = 0
    stack: list = field(default_factory=list)
    frames: list[Frame] = field(default_factory=list)
    subs: list[SubReturn] = field(default_factory=list)
    wait: Wait | None = None
    ended: bool = False
    nowait: bool = False
    stack_used: int = 0
    print_line: str = ""                                    # text of PRINT …; statements waiting for the line end
    print_items: list[str] = field(default_factory=list)   # the items of the PRINT being executed
    instructions: int = 0
    skip_stop: bool = False

    def __post_init__(self) -> None:
        img = self.image
        self.globals: list = [0.0 if v.type == "double" else 0 for v in img.globals]
        for slot, _ in img.loops:
            self.globals[slot] = -1  # LOOP counters start inactive
        self.arrays = [ArrayRef(v.name, _size(v.dims), v.dims, v.type) for v in img.arrays]
        self.dims = [self.host.dim_array(i, v.name, v.dims) for i, v in enumerate(img.dims)]
        self.code = img.code

    # --- state ----------------------------------------------------------------------------------------
    @property
    def in_interrupt(self) -> bool:
        return any(s.interrupt for s in self.subs)

    @property
    def effective_nowait(self) -> bool:
        """DG 6389: inside interrupt handlers NOWAIT is always ON."""
        return self.nowait or self.in_interrupt

    @property
    def line(self) -> int | None:
        """The source line of the instruction executed last (a running or blocking command's line)."""
        entry = self.image.line_of(max(self.pc - 1, 0))
        return entry.line if entry else None

    def enter_interrupt(self, sub: int, kind: str) -> None:
        """Call subprogram `sub` as an interrupt handler now (between two instructions)."""
        wait = self.wait
        if wait is not None and not wait.resumable and kind != "ERROR":
            wait.abandon()  # an ordinary interrupt ends HOME; ON ERROR does not (CR 2662-2664)
            wait = None
        self.subs.append(SubReturn(self.pc, sub, kind, wait, len(self.stack)))
        self.wait = None
        self.pc = self.image.subprograms[sub].entry

    # --- execution ------------------------------------------------------------------------------------
    def run(self, budget: int) -> None:
        """Execute up to `budget` instructions; stops early at a wait or at the end of the program."""
        if self.ended:
            return
        if self.wait is not None:
            if not self.wait.done():
                return
            finished, self.wait = self.wait, None
            if finished.value is not None:
                self.stack.append(finished.value)
        code, stack, glob = self.code, self.stack, self.globals
        pc = self.pc
        executed = 0
        try:
            while executed < budget:
                op = code[2 * pc]
                arg = code[2 * pc + 1]
                pc += 1
                executed += 1
                if op == Op.PUSH:
                    stack.append(arg)
                elif op == Op.LOADG:
                    stack.append(glob[arg])
                elif op == Op.STOREG:
                    v = stack.pop()
                    glob[arg] = v
                elif op == Op.BIN:
                    b = stack.pop()
                    stack[-1] = semantics.long_binary(_BINOPS[arg], stack[-1], b)
                elif op == Op.JZ:
                    if not stack.pop():
                        pc = arg
                elif op == Op.JMP:
                    pc = arg
                elif op == Op.JNZ:
                    if stack.pop():
                        pc = arg
                elif op == Op.STMT:
                    if self.skip_stop:
                        self.skip_stop = False
                    elif self.host.statement_stop(self, arg):
                        self.pc = pc - 1  # stop before the statement; resuming runs it
                        self.skip_stop = True
                        return
                elif op == Op.CMD:
                    self.pc = pc
                    self._command(arg)
                    if self.wait is not None or self.ended:
                        return
                    pc = self.pc
                else:
                    self.pc = pc
                    self._other(op, arg)
                    if self.wait is not None or self.ended:
                        return
                    pc = self.pc
            self.pc = pc
        except semantics.OperatorError as exc:  # LONG division by zero (decisions L6: error 156)
            self.pc = pc
            raise ControllerError(156, str(exc)) from None
        finally:
            self.instructions += executed

    def _command(self, index: int) -> None:
        call = self.image.calls[index]
        n = call.argc + (1 if call.axis else 0)
        args = self.stack[len(self.stack) - n:] if n else []
        del self.stack[len(self.stack) - n:]
        if call.axis:
            axis = args.pop(0)
            if axis != 1:
                raise ControllerError(103, f"axis {axis}")
        try:
            result = self.host.command(self, call, args)
        except ControllerError:
            if call.returns != "none":  # keep the stack balanced: the program goes on after ON ERROR
                self.stack.append(0)
            raise
        if isinstance(result, Wait):
            self.wait = result
            if result.done():  # finished at once: no need to wait a tick
                self.wait = None
                if call.returns != "none":
                    self.stack.append(result.value if result.value is not None else 0)
        elif call.returns != "none":
            self.stack.append(result if result is not None else 0)

    def _other(self, op: int, arg: int) -> None:  # noqa: C901 - one branch per instruction
        stack = self.stack
        if op == Op.PUSHD:
            stack.append(self.image.doubles[arg])
        elif op == Op.PUSHS:
            stack.append(self.image.strings[arg])
        elif op == Op.LOADL:
            stack.append(self.frames[-1].locals[arg])
        elif op == Op.STOREL:
            v = stack.pop()
            frame = self.frames[-1]
            frame.locals[arg] = v
        elif op == Op.ARRDIM:
            stack.append(self.dims[arg])
        elif op == Op.ARRG:
            stack.append(self.arrays[arg])
        elif op == Op.ARRL:
            stack.append(self.frames[-1].locals[arg])
        elif op == Op.LOADE:
            i = stack.pop()
            array = stack.pop()
            stack.append(0)  # replaced below; stays 0 if the index is refused (stack kept balanced)
            stack[-1] = array.data[_index(array, i)]
        elif op == Op.STOREE:
            v = stack.pop()
            i = stack.pop()
            array = stack.pop()
            array.data[_index(array, i)] = _typed(v, array.type)
        elif op == Op.LOADE2:
            c, r = stack.pop(), stack.pop()
            array = stack.pop()
            stack.append(0)
            stack[-1] = array.data[_index2(array, r, c)]
        elif op == Op.STOREE2:
            v, c, r = stack.pop(), stack.pop(), stack.pop()
            array = stack.pop()
            array.data[_index2(array, r, c)] = _typed(v, array.type)
        elif op == Op.LOADP:
            index = stack.pop()
            stack.append(0)
            stack[-1] = self.host.read_pseudo(arg, index)
        elif op == Op.STOREP:
            v = stack.pop()
            self.host.write_pseudo(arg, stack.pop(), v)
        elif op == Op.REFG:
            stack.append(Ref(self.globals, arg, self.image.globals[arg].type))
        elif op == Op.REFL:
            frame = self.frames[-1]
            stack.append(Ref(frame.locals, arg, "double" if isinstance(frame.locals[arg], float) else "long"))
        elif op == Op.REFE:
            i = stack.pop()
            array = stack.pop()
            stack.append(None)
            stack[-1] = Ref(array.data, _index(array, i), array.type)
        elif op == Op.NEG:
            stack[-1] = semantics.wrap(-stack[-1])
        elif op == Op.NEGD:
            stack[-1] = -stack[-1]
        elif op == Op.BNOT:
            stack[-1] = semantics.wrap(~stack[-1])
        elif op == Op.LNOT:
            stack[-1] = int(stack[-1] == 0)
        elif op == Op.I2D:
            stack[-1] = float(stack[-1])
        elif op == Op.D2I:
            stack[-1] = self._math(semantics.to_long, stack[-1])
        elif op == Op.BIND:
            b = stack.pop()
            a = stack[-1]
            stack[-1] = self._math(semantics.double_binary, _BINOPS[arg], a, b)
        elif op == Op.BITGET:
            n = stack.pop()
            stack[-1] = self._math(semantics.bit_get, stack[-1], SELECTOR_CODES[arg], n)
        elif op == Op.BITSET:
            new, n = stack.pop(), stack.pop()
            stack[-1] = self._math(semantics.bit_set, stack[-1], SELECTOR_CODES[arg], n, new)
        elif op == Op.MATH:
            stack[-1] = self._math(semantics.DOUBLE_FUNCTIONS[MATH_FUNCTIONS[arg]], stack[-1])
        elif op == Op.ABS:
            stack[-1] = semantics.wrap(abs(stack[-1]))
        elif op == Op.FABS:
            stack[-1] = math.fabs(stack[-1])
        elif op == Op.DUP:
            stack.append(stack[-1])
        elif op == Op.POP:
            stack.pop()
        elif op == Op.CALL:
            self._call(arg)
        elif op == Op.RET:
            frame = self.frames.pop()
            self.stack_used -= frame.size
            self.pc = frame.return_pc
        elif op == Op.GOSUB:
            if len(self.subs) >= MAX_GOSUB_DEPTH:
                raise ControllerError(151, "GOSUB nested deeper than 10")
            if any(s.sub == arg for s in self.subs):
                raise ControllerError(151, f"SUBPROG {self.image.subprograms[arg].name} calls itself")
            self.subs.append(SubReturn(self.pc, arg))
            self.pc = self.image.subprograms[arg].entry
        elif op == Op.RETSUB:
            if not self.subs:
                raise ControllerError(152, "RETURN without GOSUB")
            ret = self.subs.pop()
            self.pc = ret.return_pc
            if ret.interrupt:
                del stack[ret.stack_depth:]
                if ret.wait is not None:
                    ret.wait.resume()
                    self.wait = ret.wait
                self.host.interrupt_returned(self, ret.interrupt)
        elif op == Op.PRINTV:
            v = stack.pop()
            self.print_items.append(format_value(v))
        elif op == Op.PRINTS:
            self.print_items.append(self.image.strings[arg])
        elif op == Op.PRINTC:
            self.print_items.append(_Char(chr(stack.pop() & 0xFF)))
        elif op == Op.PRINTNL:
            if arg and not self.host.print_room():  # the output buffer is full: wait, then print (decisions K82)
                self.pc -= 1
                self.wait = _OutputRoom(self.host)
                return
            self.print_line += join_print_items(self.print_items)
            self.print_items.clear()
            if arg:
                self.host.print_text(self.print_line)
                self.print_line = ""
        elif op == Op.INTR:
            info = self.image.interrupts[arg]
            count = int(info.has_value) + int(info.setout) + int(info.toin)
            operands = stack[len(stack) - count:] if count else []
            del stack[len(stack) - count:]
            self.host.define_interrupt(self, arg, operands)
        elif op == Op.LOOP:
            count = stack.pop()
            slot, target = self.image.loops[arg]
            state = self.globals[slot]
            if state < 0:
                state = count
            if state > 0:
                self.globals[slot] = state - 1
                self.pc = target
            else:
                self.globals[slot] = -1
        elif op == Op.COPYA:
            src = stack.pop()
            dest = stack.pop()
            n = min(len(src.data), len(dest.data))
            dest.data[:n] = src.data[:n]  # DG 6461-6486: copies min(size) elements
        elif op == Op.END:
            if self.print_line:
                self.host.print_text(self.print_line)
                self.print_line = ""
            self.ended = True
            self.pc -= 1
        elif op == Op.NOP:
            pass
        else:
            raise ControllerError(110, f"instruction {op} at pc {self.pc - 1}")

    def _call(self, index: int) -> None:
        func = self.image.functions[index]
        n = len(func.params)
        if self.stack_used + len(func.locals) > self.stack_size:  # checked before the arguments are taken
            del self.stack[len(self.stack) - n:]
            self.stack.append(0.0 if func.type == "double" else 0)
            raise ControllerError(193, f"calling {func.name}")
        args = self.stack[len(self.stack) - n:] if n else []
        del self.stack[len(self.stack) - n:]
        size = len(func.locals) + sum(_size(v.dims) for v in func.locals[n:] if v.dims)
        if self.stack_used + size > self.stack_size:  # before anything is allocated: long a[2000000000]
            raise ControllerError(193, f"calling {func.name}")
        local_values = list(args)
        for v in func.locals[n:]:
            if v.dims:
                local_values.append(ArrayRef(v.name, _size(v.dims), v.dims, v.type))
            else:
                local_values.append(0.0 if v.type == "double" else 0)
        self.stack_used += size
        self.frames.append(Frame(local_values, self.pc, size))
        self.pc = func.entry

    @staticmethod
    def _math(fn, *args):
        try:
            return fn(*args)
        except semantics.OperatorError as exc:
            raise ControllerError(156, str(exc)) from None


_BINOPS = {int(code): name for code, name in OPERATOR_OF.items()}  # BinOp code → operator name of semantics.py


def _size(dims: list[int]) -> int:
    size = 1
    for d in dims:
        size *= max(d, 0)
    return size


def _index(array: ArrayRef, i: int) -> int:
    if not 1 <= i <= len(array.data):
        raise ControllerError(171, f"{array.name}[{i}] outside 1..{len(array.data)}")
    return i - 1


def _index2(array: ArrayRef, r: int, c: int) -> int:
    rows, cols = (array.dims + [1])[:2]
    if not (1 <= r <= rows and 1 <= c <= cols):
        raise ControllerError(171, f"{array.name}[{r}][{c}] outside [1..{rows}][1..{cols}]")
    return (r - 1) * cols + (c - 1)  # row-major (decisions.md)


def _typed(v, type_: str):
    if type_ == "double":
        return float(v)
    return semantics.to_long(v) if isinstance(v, float) else v


_NO_BLANK_AFTER = " \t([{="
_NO_BLANK_BEFORE = " \t,.;:!?)]}="


class _Char(str):
    """The text of a CHR(n) print item: part of the text around it, never separated."""


def join_print_items(items: list[str]) -> str:
    """The items of one PRINT: one blank between two of them, unless there is white space at that junction already
    or the later item begins with a closing punctuation mark, the earlier ends with an opening bracket, either side is
    '=' or an item is a CHR(n) character (decision K48). CR 229-240 prints `PRINT "Actual Position Reached", APOS`
    as "Actual Position Reached 2000", while the manuals' programs write `PRINT "Hello: ",i` expecting one blank.
    PRINTs joined by ';' get nothing between them (CR 3740 prints a string character by character)."""
    text = ""
    glued = True
    for item in items:
        char = isinstance(item, _Char)
        if not (glued or char) and item and text[-1] not in _NO_BLANK_AFTER and item[0] not in _NO_BLANK_BEFORE:
            text += " "
        text += item
        glued = char or not text
    return text


def format_value(v: int | float) -> str:
    """PRINT of a value: LONG as an integer, DOUBLE with up to 6 decimals (decisions.md)."""
    if isinstance(v, float):
        text = f"{v:.6f}".rstrip("0")
        return text + "0" if text.endswith(".") else text
    return str(v)
