"""Readable listing of a program image (motiontool compile --listing, tests, debugging the compiler)."""

from __future__ import annotations

from motiontool.aposs.image import (
    MATH_FUNCTIONS,
    OPERATOR_OF,
    PSEUDO_ARRAYS,
    SELECTOR_CODES,
    BinOp,
    Op,
    ProgramImage,
)


def operand(img: ProgramImage, op: Op, arg: int) -> str:
    if op == Op.PUSHD:
        return repr(img.doubles[arg])
    if op in (Op.PUSHS, Op.PRINTS):
        return repr(img.strings[arg])
    if op in (Op.LOADG, Op.STOREG, Op.REFG):
        return img.globals[arg].name
    if op == Op.ARRDIM:
        return img.dims[arg].name
    if op == Op.ARRG:
        return img.arrays[arg].name
    if op in (Op.BIN, Op.BIND):
        return OPERATOR_OF[BinOp(arg)]
    if op in (Op.BITGET, Op.BITSET):
        return "." + SELECTOR_CODES[arg]
    if op == Op.MATH:
        return MATH_FUNCTIONS[arg]
    if op in (Op.LOADP, Op.STOREP):
        return PSEUDO_ARRAYS[arg]
    if op == Op.CMD:
        call = img.calls[arg]
        return f"{call.command}/{call.argc}" + (" x()" if call.axis else "")
    if op == Op.CALL:
        return img.functions[arg].name
    if op == Op.GOSUB:
        return img.subprograms[arg].name
    if op == Op.INTR:
        i = img.interrupts[arg]
        target = img.subprograms[i.subprogram].name if i.subprogram >= 0 else "SETOUT"
        sign = "+-"[i.sign < 0] if i.kind in ("APOS", "IPOS", "MAPOS", "MCPOS", "MIPOS") else ""
        return f"{'DELETE ' if i.delete else ''}{sign}{i.kind} → {target}"
    if op == Op.LOOP:
        slot, loop_start = img.loops[arg]
        return f"{img.globals[slot].name} → {loop_start}"
    if op in (Op.PUSH, Op.JMP, Op.JZ, Op.JNZ, Op.LOADL, Op.STOREL, Op.REFL, Op.ARRL, Op.PRINTNL, Op.STMT):
        return str(arg)
    return ""


def listing(img: ProgramImage) -> str:
    entries = {s.entry: f"SUBPROG {s.name}" for s in img.subprograms}
    entries.update({f.entry: f"function {f.name}" for f in img.functions})
    out = []
    for pc in range(len(img)):
        if pc in entries:
            out.append(f"; {entries[pc]}")
        op, arg = Op(img.code[2 * pc]), img.code[2 * pc + 1]
        out.append(f"{pc:5d}  {op.name:<8} {operand(img, op, arg)}".rstrip())
    return "\n".join(out)
