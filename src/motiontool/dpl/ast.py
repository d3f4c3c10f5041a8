"""DPL syntax tree. Every node has the Location of its first token; names are kept upper case (DPL names
ignore case, docs/decisions.md A52) together with the text as written."""

from __future__ import annotations

from dataclasses import dataclass, field

from motiontool.language.ast import Node  # the shared base: loc, the place of its first token
from motiontool.language.diagnostics import Location


# --- expressions ------------------------------------------------------------------------------------------------
@dataclass(eq=False)
class Expr(Node):
    pass


@dataclass(eq=False)
class Num(Expr):
    value: int


@dataclass(eq=False)
class Var(Expr):
    """An integer variable ``Count%`` or a PLC register ``_P01%``."""

    name: str
    text: str


@dataclass(eq=False)
class Alias(Expr):
    """A definition of the manual's §11.5 (``APC_FB_POS`` = 48) or a name the checks could not resolve."""

    name: str
    text: str


@dataclass(eq=False)
class Elem(Expr):
    """An array element ``InArray%[i]``."""

    name: str
    text: str
    index: Expr


@dataclass(eq=False)
class Param(Expr):
    """A drive parameter ``#18.11``."""

    menu: int
    number: int

    @property
    def text(self) -> str:
        return f"#{self.menu:02d}.{self.number:02d}"


@dataclass(eq=False)
class Bit(Expr):
    """Bit access ``Control%.0`` on a variable, element or parameter."""

    base: Expr
    bit: int


@dataclass(eq=False)
class Call(Expr):
    """A built-in function call; used in an expression it gives its first result."""

    name: str
    text: str
    args: list[Expr]


@dataclass(eq=False)
class Unary(Expr):
    op: str  # "-" | "NOT"
    operand: Expr


@dataclass(eq=False)
class Binary(Expr):
    op: str  # + - * / & | = <> < > <= >= AND OR
    left: Expr
    right: Expr


# --- statements -------------------------------------------------------------------------------------------------
@dataclass(eq=False)
class Stmt(Node):
    pass


@dataclass(eq=False)
class Assign(Stmt):
    target: Expr  # Var | Elem | Param | Bit
    value: Expr


@dataclass(eq=False)
class TupleAssign(Stmt):
    """``(Value%, Status%) = APCReadPar(48)``: one target per result, in order."""

    targets: list[Expr]
    call: Call


@dataclass(eq=False)
class CallStmt(Stmt):
    call: Call


@dataclass(eq=False)
class If(Stmt):
    """IF … THEN / ELSEIF … THEN / ELSE / ENDIF, or the one-line ``IF c THEN statement``."""

    branches: list[tuple[Expr, list[Stmt]]]
    orelse: list[Stmt] | None = None


@dataclass(eq=False)
class Label(Stmt):
    name: str
    text: str


@dataclass(eq=False)
class Goto(Stmt):
    name: str
    text: str


@dataclass(eq=False)
class Reinit(Stmt):
    """REINIT: the module takes over the #81 set-up parameters written so far (L4678-4723)."""


@dataclass(eq=False)
class Dim(Stmt):
    """``DIM Name%[n]``: a variable array in RAM; also a statement (it clears the array when executed)."""

    name: str
    text: str
    size: Expr


@dataclass(eq=False)
class ConstArray(Stmt):
    """``CONST Name%[n] = { v, … }``: an array in flash, read-only (L1500-1506). A declaration: where it
    stands does not matter and it does nothing when reached."""

    name: str
    text: str
    size: Expr | None
    values: list[Expr]


# --- the program -----------------------------------------------------------------------------------------------
@dataclass(eq=False)
class Task(Node):
    """A task block such as ``Pos0 { … }``; `name` is the canonical spelling (Initial, Background, Pos0, …)."""

    name: str
    text: str
    body: list[Stmt]
    end: Location


@dataclass(eq=False)
class Program(Node):
    tasks: dict[str, Task] = field(default_factory=dict)
    notes: str = ""
    consts: list[ConstArray] = field(default_factory=list)
