"""The program image: what the compiler produces and a controller executes (docs/formats/program-image.md).

A stack machine: `code` is a flat list [op, arg, op, arg, …]; pc counts instructions (pc*2 indexes `code`).
The image is versioned and serialised as ``MTIMG`` + version byte + zlib-compressed JSON.
"""

from __future__ import annotations

import json
import zlib
from dataclasses import asdict, dataclass, field
from enum import IntEnum

MAGIC = b"MTIMG"
FORMAT_VERSION = 1


class Op(IntEnum):
    NOP = 0
    PUSH = 1        # push LONG arg
    PUSHD = 2       # push doubles[arg]
    PUSHS = 3       # push strings[arg] (text and keyword arguments of commands)
    LOADG = 4       # push global scalar slot arg
    STOREG = 5      # pop → global scalar slot arg (converted to the slot's type)
    LOADL = 6       # push local slot arg of the current function frame
    STOREL = 7
    ARRDIM = 8      # push handle of DIM array arg (controller array memory, identity by position)
    ARRG = 9        # push handle of global variable array arg
    ARRL = 10       # push the array handle held in local slot arg (local array or long[] parameter)
    LOADE = 11      # pop index, handle → push element (1-based; error 171 outside)
    STOREE = 12     # pop value, index, handle → store
    LOADE2 = 13     # pop col, row, handle → push element of a 2-D array
    STOREE2 = 14    # pop value, col, row, handle
    LOADP = 15      # pop index → push pseudo-array element; arg 0 SYSVAR, 1 PCD, 2 PDO
    STOREP = 16     # pop value, index
    REFG = 17       # push a reference to global slot arg (output arguments of commands)
    REFL = 18       # push a reference to local slot arg
    REFE = 19       # pop index, handle → push a reference to that element
    NEG = 20
    BNOT = 21       # ~
    LNOT = 22       # NOT
    I2D = 23
    D2I = 24        # truncation toward zero
    BIN = 25        # pop b, a → push a OP b on LONG values; arg = BinOp
    BIND = 26       # the same on DOUBLE values (arithmetic and comparisons)
    NEGD = 27
    BITGET = 28     # pop n, value → field; arg = Selector
    BITSET = 29     # pop new, n, old → updated value; arg = Selector
    MATH = 30       # DOUBLE function; arg = MathFn
    ABS = 31
    FABS = 32
    JMP = 33
    JZ = 34         # pop; jump if zero
    JNZ = 35
    DUP = 36
    POP = 37
    CALL = 38       # call functions[arg]; its arguments are on the stack
    RET = 39        # return from a function with the value on the stack
    GOSUB = 40      # call subprograms[arg]
    RETSUB = 41
    CMD = 42        # run calls[arg]: a controller command; arguments on the stack; pushes a value if it returns one
    PRINTV = 43     # pop and print a LONG or DOUBLE value
    PRINTS = 44     # print strings[arg]
    PRINTC = 45     # pop and print the character with that code
    PRINTNL = 46    # end the PRINT line (arg 1) or not (arg 0, a trailing ';')
    INTR = 47       # define an interrupt: interrupts[arg]; its value / SETOUT / TOIN operands on the stack
    LOOP = 48       # pop count; loops[arg] = [counter slot, target pc]: jump back count times
    STMT = 49       # debug builds: a statement starts here (arg = index into lines)
    END = 50        # end of the program (also EXIT)
    COPYA = 51      # pop source handle, destination handle → copy min(size) elements
    INCG = 52       # not used by version 1 (reserved)


class BinOp(IntEnum):
    ADD = 0
    SUB = 1
    MUL = 2
    DIV = 3   # %  (division)
    MOD = 4
    RND = 5
    AND = 6   # &
    OR = 7    # |
    XOR = 8   # ^
    SHL = 9
    SHR = 10
    EQ = 11
    NE = 12
    LT = 13
    LE = 14
    GT = 15
    GE = 16
    LAND = 17  # AND
    LOR = 18   # OR
    POW = 19   # exp (DOUBLE only)


BINOP_OF = {"+": BinOp.ADD, "-": BinOp.SUB, "*": BinOp.MUL, "%": BinOp.DIV, "MOD": BinOp.MOD,
            "RND": BinOp.RND, "&": BinOp.AND, "|": BinOp.OR, "^": BinOp.XOR, "<<": BinOp.SHL,
            ">>": BinOp.SHR, "==": BinOp.EQ, "!=": BinOp.NE, "<": BinOp.LT, "<=": BinOp.LE, ">": BinOp.GT,
            ">=": BinOp.GE, "AND": BinOp.LAND, "OR": BinOp.LOR, "EXP": BinOp.POW}
OPERATOR_OF = {v: k for k, v in BINOP_OF.items()}
SELECTOR_CODES = ["i", "b", "w", "l", "ub", "sb", "uw", "sw"]
MATH_FUNCTIONS = ["SQRT", "SIN", "COS", "TAN", "ACOS", "ASIN", "ATAN", "GRAD", "RAD", "LN", "ROUND"]
PSEUDO_ARRAYS = ["SYSVAR", "PCD", "PDO"]


class ImageError(ValueError):
    """A program image that cannot be read; the message names the byte offset or the field."""


@dataclass
class Variable:
    name: str
    type: str                   # "long" | "double"
    dims: list[int] = field(default_factory=list)  # [] scalar, [n] or [rows, cols] array


@dataclass
class Function:
    name: str
    type: str
    entry: int                  # pc
    params: list[Variable]      # array parameters have dims [0]
    locals: list[Variable]      # params first, then declared locals (and hidden temporaries)


@dataclass
class Subprogram:
    name: str
    entry: int


@dataclass
class CommandCall:
    command: str                # the command's name in the command table, e.g. "POSA", "MOTOR ON"
    argc: int
    axis: bool                  # an axis designator x(n) was pushed before the arguments
    returns: str                # "none" | "long" | "double"


@dataclass
class Interrupt:
    kind: str                   # ERROR INT APOS IPOS MAPOS MCPOS MIPOS POSITION PERIOD TIME COMBIT STATBIT ...
    sign: int                   # +1 / -1 for position interrupts
    subprogram: int             # index into subprograms, -1 for SETOUT forms
    has_value: bool
    setout: bool
    toin: bool
    delete: bool


@dataclass
class LineEntry:
    pc: int
    file: int                   # index into files
    line: int
    col: int


@dataclass
class ProgramImage:
    name: str
    debug: bool = False
    code: list[int] = field(default_factory=list)
    doubles: list[float] = field(default_factory=list)
    strings: list[str] = field(default_factory=list)
    globals: list[Variable] = field(default_factory=list)       # scalars by slot
    arrays: list[Variable] = field(default_factory=list)        # global variable arrays (long a[10])
    dims: list[Variable] = field(default_factory=list)          # DIM arrays in DIM order
    functions: list[Function] = field(default_factory=list)
    subprograms: list[Subprogram] = field(default_factory=list)
    calls: list[CommandCall] = field(default_factory=list)
    interrupts: list[Interrupt] = field(default_factory=list)
    loops: list[list[int]] = field(default_factory=list)        # [counter global slot, target pc]
    files: list[str] = field(default_factory=list)
    lines: list[LineEntry] = field(default_factory=list)        # sorted by pc: the source of each statement
    version: int = FORMAT_VERSION

    def __len__(self) -> int:
        return len(self.code) // 2

    def line_of(self, pc: int) -> LineEntry | None:
        """The statement that instruction pc belongs to."""
        lo, hi, found = 0, len(self.lines) - 1, None
        while lo <= hi:
            mid = (lo + hi) // 2
            if self.lines[mid].pc <= pc:
                found, lo = self.lines[mid], mid + 1
            else:
                hi = mid - 1
        return found

    # --- serialisation ------------------------------------------------------------------------------
    def to_bytes(self) -> bytes:
        payload = json.dumps(asdict(self), separators=(",", ":"), allow_nan=False).encode("utf-8")
        return MAGIC + bytes([FORMAT_VERSION]) + zlib.compress(payload, 9)

    @classmethod
    def from_bytes(cls, data: bytes) -> ProgramImage:
        if data[:5] != MAGIC:
            raise ImageError("not a motiontool program image: bytes 0-4 are not 'MTIMG'")
        if len(data) < 6:
            raise ImageError("truncated program image: no version byte at offset 5")
        if data[5] != FORMAT_VERSION:
            raise ImageError(f"program image version {data[5]} (byte 5) is not supported; "
                             f"this motiontool reads version {FORMAT_VERSION}")
        try:
            raw = json.loads(zlib.decompress(data[6:]).decode("utf-8"))
        except (zlib.error, UnicodeDecodeError, json.JSONDecodeError) as exc:
            raise ImageError(f"corrupt program image body after byte 6: {exc}") from None
        try:
            image = cls(
                name=raw["name"], debug=bool(raw["debug"]), code=list(raw["code"]),
                doubles=[float(x) for x in raw["doubles"]], strings=list(raw["strings"]),
                globals=[Variable(**v) for v in raw["globals"]], arrays=[Variable(**v) for v in raw["arrays"]],
                dims=[Variable(**v) for v in raw["dims"]],
                functions=[Function(f["name"], f["type"], f["entry"], [Variable(**p) for p in f["params"]],
                                    [Variable(**v) for v in f["locals"]]) for f in raw["functions"]],
                subprograms=[Subprogram(**s) for s in raw["subprograms"]],
                calls=[CommandCall(**c) for c in raw["calls"]],
                interrupts=[Interrupt(**i) for i in raw["interrupts"]],
                loops=[list(x) for x in raw["loops"]], files=list(raw["files"]),
                lines=[LineEntry(**e) for e in raw["lines"]], version=raw["version"])
        except (KeyError, TypeError, ValueError) as exc:
            raise ImageError(f"program image field missing or malformed: {exc}") from None
        image.validate()
        return image

    def validate(self) -> None:
        """Refuse an image whose instructions point outside its tables."""
        if len(self.code) % 2:
            raise ImageError("code has an odd number of entries")
        limits = {Op.PUSHD: len(self.doubles), Op.PUSHS: len(self.strings), Op.PRINTS: len(self.strings),
                  Op.LOADG: len(self.globals), Op.STOREG: len(self.globals), Op.REFG: len(self.globals),
                  Op.ARRDIM: len(self.dims), Op.ARRG: len(self.arrays), Op.CALL: len(self.functions),
                  Op.GOSUB: len(self.subprograms), Op.CMD: len(self.calls), Op.INTR: len(self.interrupts),
                  Op.LOOP: len(self.loops), Op.JMP: len(self), Op.JZ: len(self), Op.JNZ: len(self)}
        for pc in range(len(self)):
            op, arg = self.code[2 * pc], self.code[2 * pc + 1]
            try:
                op = Op(op)
            except ValueError:
                raise ImageError(f"unknown instruction {op} at pc {pc}") from None
            limit = limits.get(op)
            if limit is not None and not 0 <= arg < limit:
                raise ImageError(f"instruction {op.name} at pc {pc} refers to entry {arg} of {limit}")
