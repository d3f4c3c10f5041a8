"""The instruction set of a program image: the operations, the binary operators, the selectors, the built-in
functions and pseudo-arrays, and the error an image that cannot be read or run raises. aposs/image.py (the
container) and aposs/verify.py (its checks) both build on this; neither imports the other's module for it.
"""

from __future__ import annotations

from enum import IntEnum


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
    """A program image that cannot be read or run; the message names the byte offset, the field or the instruction.

    ``field`` (a path such as ``functions[2].entry``) or ``code_index`` (an entry of ``code``) say where, so that
    ProgramImage.from_bytes can add the byte offset in the inflated body."""

    def __init__(self, message: str, field: str | None = None, code_index: int | None = None):
        super().__init__(message)
        self.field = field if field is not None else (f"code[{code_index}]" if code_index is not None else None)
