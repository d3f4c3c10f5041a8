"""Complete validation of a program image before a controller may load it (decisions K81).

A downloaded image may come from anywhere (a file, a link, a fuzzer), so a controller must never meet an instruction
it cannot execute: every field has its type and range, and the code is followed from every entry (main program,
subprograms, functions) with the operand stack's depth and types (LONG, DOUBLE, text, array, reference) known at
each instruction. Refused: an operand of the wrong type, a stack that underflows or differs where two paths meet,
a jump outside the code or into another program part, code that runs past the end, a RETURN where there is nothing
to return from, a command called with arguments its table entry does not take. ``verify`` raises ImageError naming
the instruction (pc, op) or field; ProgramImage.from_bytes adds the byte offset.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from motiontool.aposs.commands import command_table
from motiontool.aposs.opcodes import MATH_FUNCTIONS, OPERATOR_OF, PSEUDO_ARRAYS, SELECTOR_CODES, BinOp, ImageError, Op

if TYPE_CHECKING:
    from motiontool.aposs.image import ProgramImage

L, D, S = "LONG", "DOUBLE", "text"
MAX_VARIABLE_ELEMENTS = 1_000_000     # all variable arrays of a program together (decisions L23)
MAX_CODE = 4_000_000                  # instructions; a 10 000-line program has some 60 000
INT32 = (-(1 << 31), (1 << 31) - 1)
INTERRUPT_KINDS = {"APOS", "IPOS", "MAPOS", "MCPOS", "MIPOS", "POSITION", "INT", "PERIOD", "TIME", "COMBIT",
                   "STATBIT", "PARAM", "CANINPUT", "ERROR", "KEYPRESSED", "CANMSG"}
LONG_ONLY = {"MOD", "RND", "&", "|", "^", "<<", ">>"}
COMPARISONS = {"==", "!=", "<", "<=", ">", ">="}
_OPS = {int(op) for op in Op}
_VARIABLE_OPS = (Op.LOADG, Op.STOREG, Op.REFG, Op.LOADL, Op.STOREL, Op.REFL)
_ARG_TYPES = {"expr": {L}, "param": {L}, "word": {S}, "string": {S}, "array": {"array"}, "var": {"ref"}}


def array(type_: str) -> str:
    return f"{type_} array"


def ref(type_: str) -> str:
    return f"reference to a {type_}"


class _Fault(Exception):
    def __init__(self, pc: int, message: str):
        self.pc, self.message = pc, message


def _type(v) -> str:
    return L if v.type == "long" else D


def verify(img: ProgramImage) -> None:
    """Raise ImageError if ``img`` is not an image the controller can run safely."""
    _check_tables(img)
    try:
        _Flow(img).run()
    except _Fault as fault:
        op = img.code[2 * fault.pc]
        name = Op(op).name if op in _OPS else "?"
        raise ImageError(f"instruction {fault.pc} ({name}): {fault.message}", code_index=2 * fault.pc) from None


# --- tables -------------------------------------------------------------------------------------------------------
def _check_tables(img: ProgramImage) -> None:
    def need(ok: bool, field: str, message: str) -> None:
        if not ok:
            raise ImageError(f"{field}: {message}", field=field)

    need(len(img.code) % 2 == 0, "code", "an odd number of entries")
    need(0 < len(img.code) // 2 <= MAX_CODE, "code", f"1 to {MAX_CODE} instructions needed")
    for k, value in enumerate(img.doubles):
        need(math.isfinite(value), f"doubles[{k}]", f"{value} is not a finite DOUBLE")
    total = 0
    for table in ("globals", "arrays", "dims"):
        for k, v in enumerate(getattr(img, table)):
            field = f"{table}[{k}]"
            need(v.type in ("long", "double"), field + ".type", f"{v.type!r} is neither 'long' nor 'double'")
            shape = (0,) if table == "globals" else (1, 2)
            need(len(v.dims) in shape if table != "globals" else not v.dims, field + ".dims",
                 f"{v.dims} is not the shape of a {'scalar' if table == 'globals' else 'array'}")
            need(all(1 <= d <= MAX_VARIABLE_ELEMENTS for d in v.dims), field + ".dims", f"{v.dims}: sizes 1 to "
                 f"{MAX_VARIABLE_ELEMENTS}")
            if table == "arrays":
                total += math.prod(v.dims)
    need(total <= MAX_VARIABLE_ELEMENTS, "arrays", f"{total} elements; variable arrays hold at most "
                                                   f"{MAX_VARIABLE_ELEMENTS}")
    for k, v in enumerate(img.dims):
        need(v.type == "long", f"dims[{k}].type", "DIM arrays are LONG")
    n = len(img.code) // 2
    for k, f in enumerate(img.functions):
        field = f"functions[{k}]"
        need(f.type in ("long", "double"), field + ".type", f"{f.type!r} is neither 'long' nor 'double'")
        need(f.entry == -1 or 0 <= f.entry < n, field + ".entry", f"{f.entry} is outside the code (0..{n - 1})")
        need(len(f.locals) >= len(f.params), field + ".locals", "fewer locals than parameters")
        for j, p in enumerate(f.params):
            need(p.type in ("long", "double") and p.dims in ([], [0]), f"{field}.params[{j}]", "not a LONG or "
                 "DOUBLE scalar or array parameter")
            need(f.locals[j] == p, f"{field}.locals[{j}]", "the locals must start with the parameters")
        for j, v in enumerate(f.locals[len(f.params):], len(f.params)):
            need(v.type in ("long", "double") and len(v.dims) <= 2 and all(d >= 1 for d in v.dims),
                 f"{field}.locals[{j}]", "not a LONG or DOUBLE variable or array")
    for k, s in enumerate(img.subprograms):
        need(0 <= s.entry < n, f"subprograms[{k}].entry", f"{s.entry} is outside the code (0..{n - 1})")
    commands = command_table()
    for k, c in enumerate(img.calls):
        field = f"calls[{k}]"
        cmd = commands.get(c.command)
        need(cmd is not None and cmd.kind in ("command", "function", "sysvar"), field + ".command",
             f"{c.command!r} is not a controller command")
        assert cmd is not None  # need() raised otherwise
        need(c.returns == cmd.returns, field + ".returns", f"{c.command} returns {cmd.returns}, not {c.returns}")
        least = sum(1 for a in cmd.args if not a.optional)
        most = math.inf if any(a.repeat for a in cmd.args) else len(cmd.args)
        need(least <= c.argc <= most, field + ".argc", f"{c.command} takes {least}"
             + ("" if most == least else f" to {most}") + f" arguments, not {c.argc}")
    for k, i in enumerate(img.interrupts):
        field = f"interrupts[{k}]"
        need(i.kind in INTERRUPT_KINDS, field + ".kind", f"unknown interrupt {i.kind!r}")
        need(i.sign in (1, -1), field + ".sign", f"{i.sign} is not +1 or -1")
        need(-1 <= i.subprogram < len(img.subprograms), field + ".subprogram",
             f"{i.subprogram} is not a subprogram (0..{len(img.subprograms) - 1}, or -1 with SETOUT)")
        need(i.subprogram >= 0 or i.setout or i.delete, field + ".subprogram", "no subprogram and no SETOUT")
    for k, (slot, target) in enumerate(img.loops):
        need(0 <= slot < len(img.globals) and img.globals[slot].type == "long", f"loops[{k}][0]",
             f"{slot} is not a LONG variable")
        need(0 <= target < n, f"loops[{k}][1]", f"{target} is outside the code (0..{n - 1})")
    previous = -1
    for k, e in enumerate(img.lines):
        need(0 <= e.file < max(1, len(img.files)) and e.pc >= previous and e.pc >= 0, f"lines[{k}]",
             "not in pc order or naming no file")
        previous = e.pc


# --- code ---------------------------------------------------------------------------------------------------------
class _Flow:
    """Follows the code from every entry with the operand stack's types (relative to the entry's stack)."""

    def __init__(self, img: ProgramImage):
        self.img = img
        self.n = len(img.code) // 2
        self.owner: dict[int, str] = {}        # pc → the program part it belongs to
        self.state: dict[int, tuple] = {}      # pc → the stack's types before the instruction

    def run(self) -> None:
        self.follow("the main program", 0, None)
        for s in self.img.subprograms:
            self.follow(f"SUBPROG {s.name}", s.entry, None)
        for k, f in enumerate(self.img.functions):
            if f.entry >= 0:
                self.follow(f"function {f.name}", f.entry, k)
        for pc in range(self.n):  # code no entry reaches: never executed, but still no nonsense
            if pc not in self.state:
                op, arg = self.img.code[2 * pc], self.img.code[2 * pc + 1]
                if op not in _OPS:
                    raise _Fault(pc, f"unknown instruction {op}")
                if op in (Op.JMP, Op.JZ, Op.JNZ) and not 0 <= arg < self.n:
                    raise _Fault(pc, f"refers to instruction {arg}, the image has {self.n}")

    def follow(self, part: str, entry: int, function: int | None) -> None:
        if self.owner.get(entry) == part:
            return
        work = [(entry, ())]
        while work:
            pc, stack = work.pop()
            if pc >= self.n:
                raise _Fault(pc - 1, f"{part} runs past the end of the code")
            owner = self.owner.get(pc)
            if owner is not None and owner != part:
                raise _Fault(pc, f"reached from {part} but belongs to {owner}")
            if pc in self.state:
                if self.state[pc] != stack:
                    raise _Fault(pc, f"the operand stack differs where paths meet: {_show(self.state[pc])} and "
                                     f"{_show(stack)}")
                continue
            self.owner[pc] = part
            self.state[pc] = stack
            for successor in self.step(pc, list(stack), part, function):
                work.append(successor)

    def step(self, pc: int, stack: list, part: str, function: int | None):  # noqa: C901 - one case per instruction
        img = self.img
        op, arg = img.code[2 * pc], img.code[2 * pc + 1]
        try:
            op = Op(op)
        except ValueError:
            raise _Fault(pc, f"unknown instruction {op}") from None

        def pop(*allowed: str) -> str:
            if not stack:
                raise _Fault(pc, "pops from an empty operand stack")
            have = stack.pop()
            if allowed and not any(_fits(have, a) for a in allowed):
                raise _Fault(pc, f"needs a {' or '.join(allowed)} operand, finds a {have}")
            return have

        def index(limit: int, what: str) -> None:
            if not 0 <= arg < limit:
                raise _Fault(pc, f"refers to {what} {arg}, the image has {limit}")

        def local(want_array: bool | None = None):
            if function is None:
                raise _Fault(pc, f"uses a local variable outside a function (in {part})")
            locals_ = img.functions[function].locals
            index(len(locals_), "local")
            v = locals_[arg]
            if want_array is not None and bool(v.dims) != want_array:
                raise _Fault(pc, f"local {v.name} is {'not ' if want_array else ''}an array")
            return v

        nxt = [(pc + 1, None)]
        if op == Op.PUSH:
            if not INT32[0] <= arg <= INT32[1]:
                raise _Fault(pc, f"{arg} is not a 32-bit LONG")
            stack.append(L)
        elif op == Op.PUSHD:
            index(len(img.doubles), "DOUBLE constant")
            stack.append(D)
        elif op == Op.PUSHS:
            index(len(img.strings), "text")
            stack.append(S)
        elif op in _VARIABLE_OPS:
            if op in (Op.LOADG, Op.STOREG, Op.REFG):
                index(len(img.globals), "variable")
                t = _type(img.globals[arg])
            else:
                t = _type(local(False))
            if op in (Op.LOADG, Op.LOADL):
                stack.append(t)
            elif op in (Op.STOREG, Op.STOREL):
                pop(t)
            else:
                stack.append(ref(t))
        elif op == Op.ARRDIM:
            index(len(img.dims), "DIM array")
            stack.append(array(L))
        elif op == Op.ARRG:
            index(len(img.arrays), "variable array")
            stack.append(array(_type(img.arrays[arg])))
        elif op == Op.ARRL:
            stack.append(array(_type(local(True))))
        elif op in (Op.LOADE, Op.LOADE2, Op.REFE):
            pop(L)
            if op == Op.LOADE2:
                pop(L)
            t = pop("array").split()[0]
            stack.append(ref(t) if op == Op.REFE else t)
        elif op in (Op.STOREE, Op.STOREE2):
            value = pop(L, D)
            pop(L)
            if op == Op.STOREE2:
                pop(L)
            t = pop("array").split()[0]
            if value != t:
                raise _Fault(pc, f"stores a {value} into a {t} array")
        elif op == Op.LOADP:
            index(len(PSEUDO_ARRAYS), "pseudo-array")
            pop(L)
            stack.append(L)
        elif op == Op.STOREP:
            index(len(PSEUDO_ARRAYS), "pseudo-array")
            pop(L)
            pop(L)
        elif op in (Op.NEG, Op.BNOT, Op.LNOT, Op.ABS):
            pop(L)
            stack.append(L)
        elif op in (Op.NEGD, Op.FABS):
            pop(D)
            stack.append(D)
        elif op == Op.MATH:
            index(len(MATH_FUNCTIONS), "DOUBLE function")
            pop(D)
            stack.append(D)
        elif op == Op.I2D:
            pop(L)
            stack.append(D)
        elif op == Op.D2I:
            pop(D)
            stack.append(L)
        elif op in (Op.BIN, Op.BIND):
            index(len(BinOp), "operator")
            name = OPERATOR_OF[BinOp(arg)]
            t = L if op == Op.BIN else D
            if (op == Op.BIN and name == "EXP") or (op == Op.BIND and name in LONG_ONLY):
                raise _Fault(pc, f"operator {name.lower()} is not defined on {t} values")
            pop(t)
            pop(t)
            stack.append(L if op == Op.BIN or name in COMPARISONS or name in ("AND", "OR") else D)
        elif op == Op.BITGET:
            index(len(SELECTOR_CODES), "bit selector")
            pop(L)
            pop(L)
            stack.append(L)
        elif op == Op.BITSET:
            index(len(SELECTOR_CODES), "bit selector")
            pop(L)
            pop(L)
            pop(L)
            stack.append(L)
        elif op in (Op.JMP, Op.JZ, Op.JNZ):
            index(self.n, "instruction")
            if op == Op.JMP:
                nxt = [(arg, None)]
            else:
                pop(L)
                nxt.append((arg, None))
        elif op == Op.DUP:
            stack.append(pop())
            stack.append(stack[-1])
        elif op == Op.POP:
            pop()
        elif op == Op.CALL:
            index(len(img.functions), "function")
            f = img.functions[arg]
            if f.entry < 0:
                raise _Fault(pc, f"calls function {f.name}, which has no body")
            for p in reversed(f.params):
                pop(array(_type(p)) if p.dims else _type(p))
            stack.append(_type(f))
        elif op == Op.RET:
            if function is None:
                raise _Fault(pc, f"returns from a function in {part}")
            if stack != [_type(img.functions[function])]:
                raise _Fault(pc, f"returns with the operand stack {_show(stack)}, not one "
                                 f"{_type(img.functions[function])}")
            nxt = []
        elif op == Op.GOSUB:
            index(len(img.subprograms), "subprogram")
        elif op == Op.RETSUB:
            if stack:
                raise _Fault(pc, f"returns from a subprogram with {_show(stack)} left on the operand stack")
            nxt = []
        elif op == Op.CMD:
            index(len(img.calls), "command call")
            self.command(pc, img.calls[arg], pop)
            if img.calls[arg].returns != "none":
                stack.append(L if img.calls[arg].returns == "long" else D)
        elif op == Op.PRINTV:
            pop(L, D)
        elif op == Op.PRINTS:
            index(len(img.strings), "text")
        elif op == Op.PRINTC:
            pop(L)
        elif op == Op.PRINTNL:
            if arg not in (0, 1):
                raise _Fault(pc, f"argument {arg} is not 0 or 1")
        elif op == Op.INTR:
            index(len(img.interrupts), "interrupt")
            i = img.interrupts[arg]
            for _ in range(int(i.has_value) + int(i.setout) + int(i.toin)):
                pop(L)
        elif op == Op.LOOP:
            index(len(img.loops), "LOOP")
            pop(L)
            nxt.append((img.loops[arg][1], None))
        elif op == Op.STMT:
            index(len(img.lines), "line")
        elif op == Op.END:
            nxt = []
        elif op == Op.COPYA:
            source = pop("array")
            if pop("array") != source:
                raise _Fault(pc, "copies between arrays of different types")
        elif op == Op.NOP:
            pass
        else:
            raise _Fault(pc, "is reserved and not used by format version 1")
        after = tuple(stack)
        return [(target, after) for target, _ in nxt]

    def command(self, pc: int, call, pop) -> None:
        cmd = command_table().get(call.command)
        assert cmd is not None  # verify() ran _check_tables first: every call names a controller command
        specs = list(cmd.args)
        if specs and specs[-1].repeat:
            specs = specs[:-1] + [specs[-1]] * max(1, call.argc - len(specs) + 1)
        for spec in reversed(specs[:call.argc]):
            allowed = set(_ARG_TYPES.get(spec.kind, {L}))
            if spec.kind == "expr" and cmd.name in ("OUT", "IN"):
                allowed.add(S)  # a connector pin, X59/3
            if spec.kind == "array" and cmd.name == "TESTSETDEST":
                allowed.add(S)  # DYNMEM
            pop(*sorted(allowed))
        if call.axis:
            pop(L)


def _fits(have: str, allowed: str) -> bool:
    """``allowed`` is a type, or "array" / "ref" for an array / reference of either type."""
    if allowed == "array":
        return have.endswith(" array")
    if allowed == "ref":
        return have.startswith("reference")
    return have == allowed


def _show(stack) -> str:
    return "[" + ", ".join(stack) + "]" if stack else "empty"
