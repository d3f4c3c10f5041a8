"""APOSS abstract syntax tree. Every node has the Location of its first token."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from motiontool.language.ast import Node  # the shared base: loc, the place of its first token
from motiontool.language.diagnostics import Location

LONG, DOUBLE = "long", "double"


# --- expressions ------------------------------------------------------------------------------------
@dataclass(eq=False)
class Expr(Node):
    pass


@dataclass(eq=False)
class Num(Expr):
    value: int | float


@dataclass(eq=False)
class Str(Expr):
    value: str


@dataclass(eq=False)
class Name(Expr):
    """A variable (or, as an argument, a whole array)."""

    name: str  # upper case key
    text: str  # as written


@dataclass(eq=False)
class Index(Expr):
    """Array element: name[i] or name[i][j]."""

    name: str
    text: str
    indices: list[Expr]


@dataclass(eq=False)
class Pseudo(Expr):
    """SYSVAR[n], PCD[n], PDO[n]."""

    name: str
    index: Expr


@dataclass(eq=False)
class Call(Expr):
    """Call of a user function: name(a, b)."""

    name: str
    text: str
    args: list[Expr]


@dataclass(eq=False)
class CmdExpr(Expr):
    """A command used for its value (IN 3, GET 1900, APOS, sqrt(x)), or a command statement's call."""

    command: Any  # commands.Command
    args: list[Expr]
    axis: Expr | None = None


@dataclass(eq=False)
class ParamRef(Expr):
    """A parameter given by its code name (GET KPROP); `number` is its index (3260)."""

    name: str
    number: int


@dataclass(eq=False)
class Word(Expr):
    """A keyword argument (NOWAIT ON, DISABLE ALL, SET PID KPROP)."""

    word: str


@dataclass(eq=False)
class OutRef(Expr):
    """A variable or array element written by a command (output by reference)."""

    target: Expr


@dataclass(eq=False)
class ArrayArg(Expr):
    """A whole array passed by reference (SETCURVE curve, f(myarray))."""

    name: str
    text: str


@dataclass(eq=False)
class Unary(Expr):
    op: str  # "-", "~", "NOT", "(long)", "(double)"
    operand: Expr


@dataclass(eq=False)
class Binary(Expr):
    op: str  # "+", "-", "*", "%", "MOD", "RND", "EXP", "^", "&", "|", "<<", ">>", comparisons, "AND", "OR"
    left: Expr
    right: Expr


@dataclass(eq=False)
class BitSel(Expr):
    """e.n / e.i n / e.b n / e.w n / e.l n / e.ub n / e.sb n / e.uw n / e.sw n (1-based)."""

    kind: str  # "i", "b", "w", "l", "ub", "sb", "uw", "sw" ("i" also for the plain .n form)
    base: Expr
    index: Expr


@dataclass(eq=False)
class PostIncrement(Expr):
    op: str  # "++" | "--"
    target: Expr


# --- statements -------------------------------------------------------------------------------------
@dataclass(eq=False)
class Stmt(Node):
    pass


@dataclass(eq=False)
class Assign(Stmt):
    target: Expr  # Name, Index, Pseudo or BitSel of those
    value: Expr


@dataclass(eq=False)
class ArrayCopy(Stmt):
    dest: str
    source: str
    dest_text: str
    source_text: str


@dataclass(eq=False)
class ExprStmt(Stmt):
    """x++ / x-- as a statement, or a function call whose value is dropped."""

    expr: Expr


@dataclass(eq=False)
class Command(Stmt):
    call: CmdExpr


@dataclass(eq=False)
class PrintStmt(Stmt):
    items: list[Expr]
    newline: bool
    device: Expr | None = None  # PRINTDEV n …


@dataclass(eq=False)
class If(Stmt):
    branches: list[tuple[Expr, list[Stmt]]]
    orelse: list[Stmt] | None


@dataclass(eq=False)
class While(Stmt):
    cond: Expr
    body: list[Stmt]


@dataclass(eq=False)
class Repeat(Stmt):
    body: list[Stmt]
    cond: Expr


@dataclass(eq=False)
class Switch(Stmt):
    value: Expr
    cases: list[tuple[list[Expr], list[Stmt], Location]]  # ([] for DEFAULT, body, loc)


@dataclass(eq=False)
class Label(Stmt):
    name: str
    text: str


@dataclass(eq=False)
class Goto(Stmt):
    label: str
    text: str


@dataclass(eq=False)
class Loop(Stmt):
    count: Expr
    label: str
    text: str


@dataclass(eq=False)
class Gosub(Stmt):
    name: str
    text: str


@dataclass(eq=False)
class Break(Stmt):
    pass


@dataclass(eq=False)
class Exit(Stmt):
    pass


@dataclass(eq=False)
class Return(Stmt):
    """RETURN of a subprogram (value None) or return(expr) of a function."""

    value: Expr | None


@dataclass(eq=False)
class OnInterrupt(Stmt):
    """ON ... GOSUB / ON ... SETOUT; `kind` ERROR INT APOS IPOS MAPOS MCPOS MIPOS PERIOD TIME COMBIT
    STATBIT PARAM KEYPRESSED CANMSG CANINPUT; `sign` +1/-1 for position interrupts."""

    kind: str
    sign: int
    value: Expr | None
    handler: str | None          # subprogram name (upper case)
    handler_text: str | None
    setout: Expr | None = None
    toin: Expr | None = None
    delete: bool = False          # ON DELETE ...


@dataclass(eq=False)
class Declarator(Node):
    name: str
    text: str
    dims: list[int] = field(default_factory=list)


@dataclass(eq=False)
class Dim(Stmt):
    arrays: list[Declarator]


@dataclass(eq=False)
class VarDecl(Stmt):
    type: str  # LONG / DOUBLE
    names: list[Declarator]


@dataclass(eq=False)
class Param(Node):
    type: str
    name: str
    text: str
    is_array: bool


@dataclass(eq=False)
class Function(Stmt):
    type: str
    name: str
    text: str
    params: list[Param]
    body: list[Stmt] | None  # None for a prototype


@dataclass(eq=False)
class Subprogram(Node):
    name: str
    text: str
    body: list[Stmt]
    end: Location  # its RETURN


@dataclass(eq=False)
class Pragma(Stmt):
    value: str


@dataclass(eq=False)
class Program(Node):
    statements: list[Stmt]          # main program code in source order (declarations included)
    subprograms: list[Subprogram]
    functions: list[Function]       # definitions and prototypes in source order
    subarea: Location | None = None  # where SUBMAINPROG stands
    end_of_main_loc: Location | None = None
    # Top-level items in source order: ("stmt", Stmt) | ("func", Function) | ("subarea", None).
    order: list[tuple[str, Any]] = field(default_factory=list)


def child_blocks(stmt: Stmt) -> list[list[Stmt]]:
    """The statement lists nested in a statement."""
    if isinstance(stmt, If):
        return [body for _, body in stmt.branches] + ([stmt.orelse] if stmt.orelse is not None else [])
    if isinstance(stmt, (While, Repeat)):
        return [stmt.body]
    if isinstance(stmt, Switch):
        return [body for _, body, _ in stmt.cases]
    return []


def walk(body: list[Stmt]):
    """Every statement in a body, depth first, in source order."""
    for stmt in body:
        yield stmt
        for inner in child_blocks(stmt):
            yield from walk(inner)


def _children_function(node: Node) -> Callable[[Any], list[Expr]]:
    """How to list the child expressions of nodes of this type."""
    if isinstance(node, (Unary,)):
        return lambda node: [node.operand]
    if isinstance(node, Binary):
        return lambda node: [node.left, node.right]
    if isinstance(node, BitSel):
        return lambda node: [node.base, node.index]
    if isinstance(node, (Index,)):
        return lambda node: list(node.indices)
    if isinstance(node, Pseudo):
        return lambda node: [node.index]
    if isinstance(node, Call):
        return lambda node: list(node.args)
    if isinstance(node, CmdExpr):
        return lambda node: ([node.axis] if node.axis else []) + list(node.args)
    if isinstance(node, (OutRef, PostIncrement)):
        return lambda node: [node.target]
    if isinstance(node, Assign):
        return lambda node: [node.target, node.value]
    if isinstance(node, ExprStmt):
        return lambda node: [node.expr]
    if isinstance(node, Command):
        return lambda node: [node.call]
    if isinstance(node, PrintStmt):
        return lambda node: ([node.device] if node.device else []) + list(node.items)
    if isinstance(node, If):
        return lambda node: [cond for cond, _ in node.branches]
    if isinstance(node, (While, Repeat)):
        return lambda node: [node.cond]
    if isinstance(node, Switch):
        return lambda node: [node.value] + [v for values, _, _ in node.cases for v in values]
    if isinstance(node, Loop):
        return lambda node: [node.count]
    if isinstance(node, Return):
        return lambda node: [node.value] if node.value else []
    if isinstance(node, OnInterrupt):
        return lambda node: [e for e in (node.value, node.setout, node.toin) if e is not None]
    return lambda node: []


_CHILDREN_BY_TYPE: dict[type, Callable[[Any], list[Expr]]] = {}


def child_exprs(node: Node) -> list[Expr]:
    # one dict lookup per node instead of up to 18 isinstance tests (the compiler walks every expression)
    fn = _CHILDREN_BY_TYPE.get(type(node))
    if fn is None:
        fn = _CHILDREN_BY_TYPE[type(node)] = _children_function(node)
    return fn(node)


def walk_exprs(node: Node):
    """Every expression below a statement or expression, depth first (an explicit stack: nested generators
    cost a frame per level and value)."""
    stack = child_exprs(node)[::-1]
    while stack:
        e = stack.pop()
        yield e
        children = child_exprs(e)
        if children:
            stack.extend(reversed(children))
