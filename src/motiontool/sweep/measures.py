"""`--measure EXPRESSION`: one number per run computed from the signals the run recorded, in a small language of
its own (never Python's eval: a sweep file may come from someone else and runs on every worker of a cluster).

    expression := term (('+' | '-') term)*      term := unary (('*' | '/') unary)*      unary := '-' unary | primary
    primary    := NUMBER | SIGNAL | FUNCTION '(' expression (',' expression)* ')' | '(' expression ')'

A SIGNAL is a name the controller streams (APOS, TRACKERR, KPROP, APC_FB_POS) or any signal name in brackets
([32-60], [4097], [18.12]); it is the series of its values, one per recorded ms. max, min, mean, rms, first, last
and final (= last) make one number of a series; abs works on either; settle_time(SIGNAL, TARGET, TOLERANCE) is
the time in ms from the start of the program after which SIGNAL stays within TOLERANCE of TARGET (nan when it
has not settled by the end). A measure must be one number.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

MAX_LENGTH = 1000   # characters of one measure
MAX_DEPTH = 50      # nested parentheses and operators; the parser recurses
_TOKEN = re.compile(r"\s*(?:(?P<number>(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?)"
                    r"|(?P<name>[A-Za-z_][A-Za-z0-9_]*)|(?P<bracket>\[[A-Za-z0-9_.#\-]{1,40}\])"
                    r"|(?P<op>[-+*/(),]))", re.ASCII)
REDUCERS: dict[str, Callable[[np.ndarray], float]] = {
    "max": np.max, "min": np.min, "mean": np.mean, "first": lambda s: s[0], "last": lambda s: s[-1],
    "final": lambda s: s[-1], "rms": lambda s: np.sqrt(np.mean(np.square(s)))}
FUNCTIONS = sorted([*REDUCERS, "abs", "settle_time"])


class MeasureError(ValueError):
    """A measure that cannot be read; ``position`` is the 1-based character it concerns."""

    def __init__(self, message: str, position: int):
        super().__init__(message)
        self.position = position


class EvaluationError(ArithmeticError):
    """A measure that has no value for one run (division by zero, no samples): that point's error."""


@dataclass(frozen=True)
class Node:
    kind: str              # number, signal, call, neg, + - * /
    position: int
    value: float = 0.0
    name: str = ""
    args: tuple[Node, ...] = ()
    series: bool = False   # a series of values (one per sample), else one number


@dataclass(frozen=True)
class Measure:
    text: str
    root: Node
    signals: tuple[str, ...]  # in order of first mention


class _Parser:
    def __init__(self, text: str):
        self.tokens: list[tuple[str, str, int]] = []
        pos = 0
        while pos < len(text):
            m = _TOKEN.match(text, pos)
            if m is None or m.end() == pos:
                if text[pos:].strip():
                    at = pos + len(text[pos:]) - len(text[pos:].lstrip())
                    raise MeasureError(f"unexpected character '{text[at]}'", at + 1)
                break
            kind = m.lastgroup or ""
            self.tokens.append((kind, m.group(kind), m.start(kind) + 1))
            pos = m.end()
        self.end = len(text) + 1
        self.k = 0
        self.depth = 0
        self.signals: list[str] = []

    def peek(self) -> tuple[str, str, int]:
        return self.tokens[self.k] if self.k < len(self.tokens) else ("end", "", self.end)

    def take(self, op: str) -> None:
        kind, text, pos = self.peek()
        if text != op or kind != "op":
            raise MeasureError(f"expected '{op}'" + (f", got '{text}'" if text else " before the end"), pos)
        self.k += 1

    def expression(self) -> Node:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise MeasureError(f"nested deeper than {MAX_DEPTH} levels", self.peek()[2])
        node = self.binary(("+", "-"), lambda: self.binary(("*", "/"), self.unary))
        self.depth -= 1
        return node

    def binary(self, ops: tuple[str, ...], operand) -> Node:
        node = operand()
        while self.peek()[0] == "op" and self.peek()[1] in ops:
            op, pos = self.peek()[1], self.peek()[2]
            self.k += 1
            right = operand()
            node = Node(op, pos, args=(node, right), series=node.series or right.series)
        return node

    def unary(self) -> Node:
        kind, text, pos = self.peek()
        if kind == "op" and text == "-":
            self.k += 1
            self.depth += 1
            if self.depth > MAX_DEPTH:
                raise MeasureError(f"nested deeper than {MAX_DEPTH} levels", pos)
            inner = self.unary()
            self.depth -= 1
            return Node("neg", pos, args=(inner,), series=inner.series)
        return self.primary()

    def primary(self) -> Node:
        kind, text, pos = self.peek()
        self.k += 1
        if kind == "number":
            value = float(text)
            if not math.isfinite(value):
                raise MeasureError(f"the number {text[:20]} is too large", pos)
            return Node("number", pos, value=value)
        if kind == "bracket":
            return self.signal(text[1:-1], pos)
        if kind == "name":
            if self.peek()[1] == "(" and self.peek()[0] == "op":
                return self.call(text, pos)
            if text.lower() in FUNCTIONS:
                raise MeasureError(f"{text} is a function: write {text}(…)", pos)
            return self.signal(text, pos)
        if kind == "op" and text == "(":
            node = self.expression()
            self.take(")")
            return node
        raise MeasureError("expected a number, a signal or a function" + (f", got '{text}'" if text else
                                                                            " before the end"), pos)

    def signal(self, name: str, pos: int) -> Node:
        if name not in self.signals:
            self.signals.append(name)
        return Node("signal", pos, name=name, series=True)

    def call(self, name: str, pos: int) -> Node:
        fn = name.lower()
        if fn not in FUNCTIONS:
            raise MeasureError(f"unknown function {name}(): use {', '.join(FUNCTIONS)}", pos)
        self.take("(")
        args = [self.expression()]
        while self.peek()[:2] == ("op", ","):
            self.k += 1
            args.append(self.expression())
        self.take(")")
        wanted = 3 if fn == "settle_time" else 1
        if len(args) != wanted:
            form = "settle_time(SIGNAL, TARGET, TOLERANCE)" if wanted == 3 else f"{fn}(SIGNAL)"
            raise MeasureError(f"{fn}() takes {wanted} argument{'s' if wanted > 1 else ''}: {form}", pos)
        if fn == "settle_time":
            if not args[0].series:
                raise MeasureError("settle_time() needs a signal first: settle_time(APOS, 204800, 10)",
                                   args[0].position)
            for arg in args[1:]:
                if arg.series:
                    raise MeasureError("TARGET and TOLERANCE of settle_time() are numbers, not signals", arg.position)
        series = args[0].series if fn == "abs" else False
        return Node("call", pos, name=fn, args=tuple(args), series=series)


def parse(text: str) -> Measure:
    """The measure `text`, or MeasureError (the only exception this raises) with the position it concerns."""
    if len(text) > MAX_LENGTH:
        raise MeasureError(f"longer than {MAX_LENGTH} characters", MAX_LENGTH + 1)
    if not text.strip():
        raise MeasureError("empty: give e.g. max(abs(TRACKERR))", 1)
    parser = _Parser(text)
    root = parser.expression()
    kind, token, pos = parser.peek()
    if kind != "end":
        raise MeasureError(f"unexpected '{token}' after a complete measure", pos)
    if root.series:
        raise MeasureError("a measure is one number: make the signal one with max(), min(), mean(), rms(), first(), "
                           "last() or settle_time()", root.position)
    return Measure(text, root, tuple(parser.signals))


def evaluate(measure: Measure, times: np.ndarray, signals: dict[str, np.ndarray]) -> float:
    """The value of the measure for one run: `times` in ms from the program's start, one series per signal."""
    if len(times) == 0:
        raise EvaluationError("no samples were recorded (the run ended at once)")
    with np.errstate(all="ignore"):
        return float(_eval(measure.root, times, signals))


def _eval(node: Node, times: np.ndarray, signals: dict[str, np.ndarray]):
    if node.kind == "number":
        return node.value
    if node.kind == "signal":
        return signals[node.name]
    args = [_eval(a, times, signals) for a in node.args]
    if node.kind == "neg":
        return -args[0]
    if node.kind in "+-*":
        a, b = args
        return a + b if node.kind == "+" else a - b if node.kind == "-" else a * b
    if node.kind == "/":
        if np.any(np.asarray(args[1]) == 0):
            raise EvaluationError(f"division by zero (position {node.position})")
        return args[0] / args[1]
    if node.name == "abs":
        return np.abs(args[0])
    if node.name == "settle_time":
        return settle_time(times, np.broadcast_to(args[0], times.shape), args[1], args[2], node.position)
    return REDUCERS[node.name](np.atleast_1d(args[0]))


def settle_time(times: np.ndarray, values: np.ndarray, target: float, tolerance: float, position: int = 0) -> float:
    """The time of the first sample from which every later sample is within `tolerance` of `target`."""
    if tolerance < 0:
        raise EvaluationError(f"settle_time(): TOLERANCE {tolerance:g} is below 0 (position {position})")
    outside = np.nonzero(np.abs(values - target) > tolerance)[0]
    if len(outside) == 0:
        return float(times[0])
    if outside[-1] == len(values) - 1:
        return math.nan
    return float(times[outside[-1] + 1])


def format_value(value: float) -> str:
    """A measure in the CSV: whole numbers without a point, others in Python's shortest round-trip form, so the
    same run gives the same bytes everywhere."""
    if math.isnan(value):
        return "nan"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    if value.is_integer() and abs(value) < 2 ** 53:
        return str(int(value))
    return repr(value)
