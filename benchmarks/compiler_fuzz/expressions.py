"""Generators 3 and 4, part 1: the names in scope and the expressions, commands and calls of a generated program."""

from __future__ import annotations

import re

from .chaos import CHAOS_VALUES, CHAOS_VALUES_SYNTAX
from .vocabulary import MATH_DOUBLE, PARAM_NAMES, SYSVARS_LONG, TABLE, chance, recase


class Scope:
    """Names visible to a statement: the globals plus, inside a function, its parameters and locals."""

    def __init__(self, unit: str, longs: list[str], doubles: list[str], arrays: list[str], funcs: list,
                 sub_index: int = -1, breakable: bool = False, labels: list[str] | None = None,
                 func=None):
        self.unit, self.longs, self.doubles, self.arrays, self.funcs = unit, longs, doubles, arrays, funcs
        self.sub_index, self.breakable, self.labels, self.func = sub_index, breakable, labels, func

    def inner(self, breakable: bool | None = None) -> Scope:
        scope = Scope(self.unit, self.longs, self.doubles, self.arrays, self.funcs, self.sub_index,
                       self.breakable if breakable is None else breakable, None, self.func)
        return scope


class ExpressionGenerator:
    """The expressions, commands, calls and wrong values of a ProgramGenerator (programs.py), which sets the
    program's names (macros, dims, garrays, funcs, subs) before it asks for any."""

    def __init__(self, r, loose: bool = False, size: int = 1):
        self.r = r
        self.loose = loose
        self.size = size
        self.counter = 0
        self.chaos_rate = 0.08 if loose else 0.0
        # Loose programs mostly stay parseable, so that the checks and the code generator see them; some also get
        # parse errors and token-level edits.
        self.syntax_chaos = loose and chance(r, 0.3)

    def chaos(self) -> bool:
        return self.loose and chance(self.r, self.chaos_rate)

    def fresh(self, prefix: str) -> str:
        self.counter += 1
        return f"{prefix}{self.counter}"

    def kw(self, word: str) -> str:
        return recase(self.r, word)

    # --- commands --------------------------------------------------------------------------------------------------
    def command(self, scope: Scope, statement: bool) -> str | None:
        """A command from the table with arguments that fit its argument specs."""
        r = self.r
        candidates = [c for c in TABLE if c.kind == "command" and c.name not in ("PRINT", "PRINTDEV")
                      and (c.statement if statement else (not c.statement and c.returns != "none"))]
        cmd = r.choice(candidates)
        args: list[str] = []
        kinds: list[str] = []
        for spec in cmd.args:
            count = 1
            if spec.optional and chance(r, 0.5):
                count = 0
            if spec.repeat:
                count = max(count, 1) + r.randint(0, 2)
            for _ in range(count):
                arg = self.argument(scope, spec)
                if arg is None:
                    return None
                args.append(arg)
                kinds.append(spec.kind)
        # A bare name followed by '(' would read as a function call: put such names in parentheses.
        for k in reversed(range(len(args) - 1)):
            if kinds[k] == "expr" and re.fullmatch(r"[A-Za-z_]\w*", args[k]) and args[k + 1].startswith("("):
                args[k] = f"({args[k]})"
        sep = ", " if any(s.repeat for s in cmd.args) and chance(r, 0.5) else " "
        # The legacy axis designator x(1) (C:826 DEFCORIGIN X(1)), on commands without arguments.
        axis = f" {self.kw('x')}(1)" if chance(r, 0.1) and not cmd.args else ""
        text = " ".join(self.kw(w) for w in cmd.words) + axis + (" " + sep.join(args) if args else "")
        return text if statement else f"({text})"

    def argument(self, scope: Scope, spec) -> str | None:
        r = self.r
        if spec.kind == "word":
            return self.kw(r.choice(spec.words))
        if spec.kind == "string":
            return r.choice(['"text"', '"Par 1"', '""'])
        if spec.kind == "array":
            arrays = [a for a in scope.arrays if len(self.dims.get(a, [1])) == 1]
            return r.choice(arrays) if arrays else None
        if spec.kind == "var":
            if scope.longs and chance(r, 0.8):
                return r.choice(scope.longs)
            return self.element(scope, one_d=True)
        if spec.kind == "param":
            return r.choice(PARAM_NAMES + [str(r.randint(1900, 1999))])
        k = r.randint(0, 3)
        if k == 0:
            return str(r.randint(0, 2000))
        if k == 1:
            return f"({self.lexpr(scope, 2)})"
        if k == 2:
            return f"(-{r.randint(1, 100)})"
        return self.leaf_long(scope)

    def call(self, scope: Scope) -> str | None:
        if not scope.funcs:
            return None
        name, type_, params, _ = self.r.choice(scope.funcs)
        args = []
        for t, _, is_array in params:
            if is_array:
                arrays = [a for a in scope.arrays if len(self.dims.get(a, [1])) == 1]
                if not arrays:
                    return None
                args.append(self.r.choice(arrays))
            else:
                args.append(self.value(scope, t, 1))
        return f"{name}({', '.join(args)})"

    # --- expressions -------------------------------------------------------------------------------------------------
    def value(self, scope: Scope, type_: str, depth: int) -> str:
        return self.dexpr(scope, depth) if type_ == "double" else self.lexpr(scope, depth)

    def selector(self) -> str:
        r = self.r
        kind = r.choice(["", "", "i", "b", "w", "l", "ub", "sb", "uw", "sw"])
        high = {"": 32, "i": 32, "b": 4, "ub": 4, "sb": 4, "w": 2, "uw": 2, "sw": 2, "l": 1}[kind]
        return f".{kind}{r.choice(['', ' '] if kind else [''])}{r.randint(1, high)}"

    def element(self, scope: Scope, one_d: bool = False) -> str | None:
        r = self.r
        arrays = [a for a in scope.arrays if not one_d or len(self.dims.get(a, [1])) == 1]
        if not arrays:
            return None
        name = r.choice(arrays)
        dims = self.dims.get(name) or [self.garrays.get(name, 1)]
        return name + "".join(f"[{self.index(scope, n)}]" for n in dims)

    def index(self, scope: Scope, n: int) -> str:
        if chance(self.r, 0.6):
            return str(self.r.randint(1, n))
        return self.lexpr(scope, 1)

    def leaf_long(self, scope: Scope) -> str:
        r = self.r
        k = r.randint(0, 12)
        if k <= 2 or not scope.longs and k <= 5:
            return r.choice([str(r.randint(0, 1000)), str(r.randint(0, 100000)), hex(r.randint(0, 0xFFFF)),
                             "'A'", "0x7FFFFFFF", "0", "1", "017"])
        if k <= 5:
            return r.choice(scope.longs)
        if k == 6:
            element = self.element(scope)
            return element or "1"
        if k == 7:
            return self.kw(r.choice(SYSVARS_LONG))
        if k == 8 and self.macros:
            return r.choice(self.macros)[0]
        if k == 9:
            return self.command(scope, statement=False) or "2"
        if k == 10:
            return f"{self.kw(r.choice(['IN', 'INB', 'INAD']))} {r.randint(1, 8)}"
        if k == 11:
            return f"{self.kw('GET')} {r.choice(PARAM_NAMES + ['1901'])}"
        return self.kw(r.choice(["ON", "OFF"]))

    def lexpr(self, scope: Scope, depth: int) -> str:
        """A LONG expression (constants stay small, divisors are non-zero literals)."""
        r = self.r
        if self.chaos():
            return self.chaos_value(scope)
        if depth <= 0 or chance(r, 0.3):
            return self.leaf_long(scope)
        k = r.randint(0, 15)
        a = self.lexpr(scope, depth - 1)
        if k <= 4:
            op = r.choice(["+", "-", "*", "&", "|", "^", "<<", ">>", "==", "!=", "<", "<=", ">", ">=", "AND", "OR",
                           "mod", "rnd", "%"])
            if op in ("mod", "rnd", "%"):
                return f"({a} {self.kw(op)} {r.randint(1, 9)})"
            return f"({a} {self.kw(op)} {self.lexpr(scope, depth - 1)})"
        if k == 5:
            return f"{r.choice(['-', '~', self.kw('NOT') + ' '])}({a})"
        if k == 6:
            return f"{self.kw('abs')}({a})"
        if k == 7:
            return f"((long) ({self.dexpr(scope, depth - 1)}))"
        if k == 8:  # '.' binds like '*': (a * b.3) is ((a * b).3), so the selection gets parentheses
            base = f"({a})" if chance(r, 0.5) or not scope.longs else r.choice(scope.longs)
            return f"({base}{self.selector()})"
        if k == 9:
            return f"({self.dexpr(scope, depth - 1)} {r.choice(['<', '>=', '==', '!='])} {self.dexpr(scope, 0)})"
        if k == 10:
            calls = [f for f in scope.funcs if f[1] == "long"]
            if calls:
                name, _, params, _ = r.choice(calls)
                text = self.call(Scope(scope.unit, scope.longs, scope.doubles, scope.arrays,
                                        [f for f in scope.funcs if f[0] == name]))
                if text:
                    return text
            return a
        if k == 11 and self.fmacro:
            return f"{self.fmacro}({a})"
        if k == 12 and scope.longs:
            return f"{r.choice(scope.longs)}{r.choice(['++', '--'])}"
        if k == 13:
            return f"{self.kw('SYSVAR')}[{a}]"
        if k == 14:  # DOUBLE operands of the logical operators
            return f"({self.dexpr(scope, depth - 1)} {self.kw(r.choice(['AND', 'OR']))} {a})"
        if k == 15:
            return f"({self.kw('NOT')} {self.dexpr(scope, depth - 1)})"
        return a

    def dexpr(self, scope: Scope, depth: int) -> str:
        """A DOUBLE expression: small finite constants, so constant folding never overflows."""
        r = self.r
        if self.chaos():
            return self.chaos_value(scope)
        if depth <= 0 or chance(r, 0.3):
            k = r.randint(0, 5)
            if k <= 1 or not scope.doubles and k <= 3:
                return r.choice(["1.5", "0.0", "2.0", "100.25", "0.001", "15.0", "3.0e2", "1e-3"])
            if k <= 3:
                return r.choice(scope.doubles)
            if k == 4:
                return self.kw("PI")
            return f"((double) {self.leaf_long(scope)})"
        k = r.randint(0, 9)
        a = self.dexpr(scope, depth - 1)
        if k <= 3:
            op = r.choice(["+", "-", "*", "%"])
            b = r.choice(["2.0", "0.5", "3", "7.25"]) if op == "%" else self.value(scope, r.choice(["long", "double"]),
                                                                                   depth - 1)
            return f"({a} {op} {b})"
        if k == 4:
            fn = r.choice(MATH_DOUBLE)
            return f"{self.kw(fn)}({a})" if fn != "sqrt" else f"{self.kw('sqrt')}({self.kw('fabs')}({a}))"
        if k == 5:
            return f"{self.kw('ln')}({self.kw('fabs')}({a}) + 1.0)"
        if k == 6:
            return f"{self.kw(r.choice(['asin', 'acos']))}({self.kw('sin')}({a}))"
        if k == 7:
            base = r.choice(scope.doubles + ["2.0", "1.5"])
            return f"({base} {self.kw('exp')} {r.choice(['2.0', '0.5', '3', '1.0'])})"
        if k == 8:
            return f"-({a})"
        calls = [f for f in scope.funcs if f[1] == "double"]
        if calls:
            name = r.choice(calls)[0]
            text = self.call(Scope(scope.unit, scope.longs, scope.doubles, scope.arrays,
                                    [f for f in scope.funcs if f[0] == name]))
            if text:
                return text
        return a

    def cond(self, scope: Scope) -> str:
        r = self.r
        k = r.randint(0, 4)
        if k == 0:
            return f"({self.lexpr(scope, 2)})"
        if k == 1:
            return f"{self.kw('IN')} {r.randint(1, 8)}"
        if k == 2:
            return f"({self.lexpr(scope, 1)} {r.choice(['<', '==', '>=', '!='])} {self.lexpr(scope, 1)})"
        if k == 3:
            return f"(({self.kw('AXEND')} & 2) {self.kw(r.choice(['AND', 'OR']))} NOT ({self.lexpr(scope, 1)}))"
        return f"({self.dexpr(scope, 1)} > {self.dexpr(scope, 0)})"

    # --- loose mode: wrong values (chaos.py) -------------------------------------------------------------------------
    def chaos_fill(self, template: str, scope: Scope) -> str:
        r = self.r
        fields = {
            "undef": r.choice(["undeclared", "zz", "n_99", "Zq_1"]),
            "array": r.choice(scope.arrays or ["noarray"]),
            "dim": r.choice(list(self.dims) or ["nodim"]),
            "long": r.choice(scope.longs or ["nolong"]),
            "double": r.choice(scope.doubles or ["nodouble"]),
            "func": r.choice([f[0] for f in self.funcs] or ["nofunc"]),
            "sub": r.choice(self.subs or ["nosub"]),
            "math": r.choice(MATH_DOUBLE + ["asin", "acos", "ln", "abs", "exp", "chr"]),
        }
        return template.format(**fields)

    def chaos_value(self, scope: Scope) -> str:
        syntax = self.syntax_chaos and chance(self.r, 0.3)
        return self.chaos_fill(self.r.choice(CHAOS_VALUES_SYNTAX if syntax else CHAOS_VALUES), scope)
