"""Expression parsing: the manual's priority table (DG 6789-6806), commands used as functions, arguments.

Priority, highest first (same line = same priority, left to right):
  unary (- ~ NOT casts) · exp · * % mod rnd and the bit selectors .n .b n … · + - · << >> ·
  < <= > >= · == != · & · ^ · | · AND · OR
A command used as a function takes one operand per argument (DG 6062: ``IN 3 == 1`` is ``(IN 3) == 1``).
"""

from __future__ import annotations

import re

from motiontool.aposs import ast
from motiontool.aposs.commands import ArgSpec, Command, CommandTable
from motiontool.aposs.lexer import EOF, FLOAT, IDENT, INT, NEWLINE, OP, STRING, TERMINAL, Token
from motiontool.language.diagnostics import CompileError

_BINARY_LEVELS: list[tuple[str, ...]] = [
    ("OR",), ("AND",), ("|",), ("^",), ("&",), ("==", "!="), ("<", "<=", ">", ">="), ("<<", ">>"),
    ("+", "-"), ("*", "%", "MOD", "RND", "."),
]
_LEVEL_OF = {op: level for level, ops in enumerate(_BINARY_LEVELS) for op in ops}
_WORD_OPS = {"OR", "AND", "MOD", "RND", "EXP", "NOT"}
_SELECTOR = re.compile(r"^(I|B|W|L|UB|SB|UW|SW)(\d*)$")
# Words that end an expression (so an optional argument never swallows them).
_STOP_WORDS = {"THEN", "DO", "GOSUB", "SETOUT", "TOIN", "ELSE", "ELSEIF", "ENDIF", "ENDWHILE", "UNTIL"}


class ExpressionParser:
    _in_argument = False
    toks: list[Token]
    i: int
    commands: CommandTable
    function_names: set[str]
    shadowed: set[str]      # command names the program uses as variables (shadow.py, L14)

    # --- token helpers ----------------------------------------------------------------------------
    @property
    def tok(self) -> Token:
        return self.toks[self.i]

    def peek(self, k: int = 1) -> Token:
        j = min(self.i + k, len(self.toks) - 1)
        return self.toks[j]

    def advance(self) -> Token:
        t = self.toks[self.i]
        if t.kind != EOF:
            self.i += 1
        return t

    def error(self, message: str, tok: Token | None = None) -> CompileError:
        tok = tok or self.tok
        return CompileError(message, tok.loc, tok.origin)

    def expect_op(self, op: str, what: str = "") -> Token:
        if not self.tok.is_op(op):
            raise self.error(f"expected '{op}'{what}, found {describe(self.tok)}")
        return self.advance()

    def expect_ident(self, what: str) -> Token:
        if self.tok.kind != IDENT:
            raise self.error(f"expected {what}, found {describe(self.tok)}")
        return self.advance()

    def at_end_of_statement(self) -> bool:
        return self.tok.kind in (NEWLINE, EOF)

    # --- expressions --------------------------------------------------------------------------------
    def expression(self) -> ast.Expr:
        return self._binary(0)

    def _binary(self, min_level: int) -> ast.Expr:
        """Precedence climbing over the priority table: an operator binds when its level is at least
        `min_level`; the right operand takes only tighter operators, so equal priorities go left to right.
        (One call per operand rather than one per table row: a 10 000-line program parses twice as fast.)"""
        left = self._power()
        while True:
            t = self.toks[self.i]
            kind = t.kind
            level = _LEVEL_OF.get(t.value if kind == IDENT else t.text) if kind in (IDENT, OP) else None
            if level is None or level < min_level:
                return left
            self.advance()
            if t.kind == OP and t.text == ".":
                left = self._selector(left, t)
            else:
                op = t.value if kind == IDENT else t.text
                left = ast.Binary(t.loc, op, left, self._binary(level + 1))

    def _selector(self, base: ast.Expr, dot: Token) -> ast.Expr:
        t = self.advance()
        if t.kind == INT:
            return ast.BitSel(dot.loc, "i", base, ast.Num(t.loc, t.value))
        m = _SELECTOR.match(t.value) if t.kind == IDENT else None
        if not m and (t.kind == IDENT or t.is_op("(")):  # DG 6734: expr1.expr2 = bit expr2 of expr1
            self.i -= 1
            return ast.BitSel(dot.loc, "i", base, self._power())
        if not m:
            raise self.error("expected a bit selector after '.': a bit number (.3) or .i .b .w .l .ub .sb .uw .sw "
                             "with a number", t)
        kind, digits = m.group(1).lower(), m.group(2)
        index = ast.Num(t.loc, int(digits)) if digits else self._power()
        return ast.BitSel(dot.loc, kind, base, index)

    def _power(self) -> ast.Expr:
        left = self.unary()
        toks = self.toks
        while toks[self.i].kind == IDENT and toks[self.i].value == "EXP":
            t = self.advance()
            left = ast.Binary(t.loc, "EXP", left, self.unary())
        return left

    def unary(self) -> ast.Expr:
        """One operand: a primary, optionally with - ~ NOT or a cast in front (also a command argument)."""
        t = self.toks[self.i]  # token kinds tested first: this runs for every operand of every expression
        kind = t.kind
        if kind == OP:
            text = t.text
            if text == "-" or text == "~":
                self.advance()
                return ast.Unary(t.loc, text, self.unary())
            if text == "+":
                self.advance()
                return self.unary()
            if text == "(" and self.peek().is_word("LONG", "DOUBLE") and self.peek(2).is_op(")"):
                self.advance()
                cast = self.advance().value.lower()
                self.advance()
                return ast.Unary(t.loc, f"({cast})", self.unary())
        elif kind == IDENT and t.value == "NOT":
            self.advance()
            return ast.Unary(t.loc, "NOT", self.unary())
        return self._postfix(self.primary())

    def _postfix(self, expr: ast.Expr) -> ast.Expr:
        t = self.toks[self.i]
        if t.kind == OP and (t.text == "++" or t.text == "--") and isinstance(expr, (ast.Name, ast.Index)):
            return ast.PostIncrement(t.loc, self.advance().text, expr)
        return expr

    def primary(self) -> ast.Expr:
        t = self.tok
        if t.kind in (INT, FLOAT):
            self.advance()
            return ast.Num(t.loc, t.value)
        if t.kind == STRING:
            self.advance()
            return ast.Str(t.loc, t.value)
        if t.is_op("("):
            self.advance()
            inner = self.expression()
            self.expect_op(")", " to close '('")
            return inner
        if t.kind != IDENT:
            raise self.error(f"expected a value, found {describe(t)}")
        if t.value in ("ON", "OFF"):
            self.advance()
            return ast.Num(t.loc, 1 if t.value == "ON" else 0)
        if t.value in _WORD_OPS:
            raise self.error(f"expected a value, found the operator '{t.text}'")
        command = self.match_command()
        if command is not None:
            return self.command_value(command, t)
        return self.variable_or_call()

    def variable_or_call(self) -> ast.Expr:
        t = self.advance()
        known = self.commands.get(t.value)
        if known is not None and known.kind in ("keyword", "command", "interrupt", "sysvar", "function") \
                and t.value not in ("LONG", "DOUBLE") and t.value not in self.shadowed:
            what = "a keyword" if known.kind == "keyword" else "a command name"
            raise self.error(f"'{t.text}' is {what} and cannot be used as a variable", t)
        # In a command argument `x (s)` is a variable and a parenthesised argument unless x is a function.
        if self.tok.is_op("(") and not (self._in_argument and t.value not in self.function_names):
            self.advance()
            args: list[ast.Expr] = []
            if not self.tok.is_op(")"):
                args.append(self.expression())
                while self.tok.is_op(","):
                    self.advance()
                    args.append(self.expression())
            self.expect_op(")", f" to close the call of '{t.text}'")
            return ast.Call(t.loc, t.value, t.text, args)
        if self.tok.is_op("["):
            indices = []
            while self.tok.is_op("["):
                self.advance()
                if self.tok.is_op("]"):
                    raise self.error(f"'{t.text}[]' means the whole array; it is only allowed in an array "
                                     "copy 'a[] = b[]'")
                indices.append(self.expression())
                self.expect_op("]", " to close the index")
            if len(indices) > 2:
                raise self.error("arrays have at most two dimensions", t)
            return ast.Index(t.loc, t.value, t.text, indices)
        return ast.Name(t.loc, t.value, t.text)

    # --- commands -------------------------------------------------------------------------------------
    def match_command(self) -> Command | None:
        """The longest command whose words start here (MOTOR ON before MOTOR), or None."""
        t = self.tok
        if t.kind != IDENT or t.value in self.shadowed:
            return None
        for command in self.commands.starting_with(t.value):
            if command.kind in ("keyword", "interrupt", "operator"):
                continue
            words = command.words
            if all(self.peek(k).kind == IDENT and self.peek(k).value == w for k, w in enumerate(words[1:], 1)):
                return command
        return None

    def command_value(self, command: Command, t: Token) -> ast.Expr:
        """A command inside an expression: it must return a value."""
        if command.returns == "none":
            raise self.error(f"'{command.name}' does not return a value and cannot stand in an expression", t)
        if command.kind == "pseudoarray":
            self.advance()
            self.expect_op("[", f" after {command.name}")
            index = self.expression()
            self.expect_op("]", " to close the index")
            return ast.Pseudo(t.loc, command.name, index)
        return self.command_call(command, in_expression=True)

    def command_call(self, command: Command, in_expression: bool) -> ast.CmdExpr:
        start = self.tok
        for _ in command.words:
            self.advance()
        axis = None
        if (self.tok.is_word("X") and self.peek().is_op("(") and "X" not in self.function_names
                and command.kind == "command" and (not command.args or command.name.endswith("DIFF"))):
            self.advance()
            self.advance()
            axis = self.expression()  # legacy axis designator x(1) (C:620, C:826)
            self.expect_op(")", " to close the axis designator x(...)")
        args: list[ast.Expr] = []
        for spec in command.args:
            count = 0
            while True:
                if args and self.tok.is_op(","):
                    self.advance()
                required = not spec.optional and count == 0
                if not required and not self._argument_follows(in_expression):
                    break
                if required and self.at_end_of_statement():
                    raise self.error(f"{command.name} needs more arguments (syntax: {command.syntax})", start)
                args.append(self.argument(spec, command))
                count += 1
                if not spec.repeat:
                    break
        return ast.CmdExpr(start.loc, command, args, axis)

    def _argument_follows(self, in_expression: bool) -> bool:
        t = self.tok
        if t.kind in (NEWLINE, EOF) or t.is_op(";", ")", "]", ":"):
            return False
        if t.kind == IDENT and (t.value in _STOP_WORDS or t.value in _WORD_OPS):
            return False
        # In an expression a following '-' is subtraction, not a negative argument.
        return not (in_expression and t.kind == OP and not t.is_op("(", "~"))

    def argument(self, spec: ArgSpec, command: Command) -> ast.Expr:
        t = self.tok
        kind = spec.kind
        if kind == "word":
            if t.kind == IDENT and t.value in spec.words:
                self.advance()
                return ast.Word(t.loc, t.value)
            raise self.error(f"{command.name} expects {' or '.join(spec.words)} here, found {describe(t)}")
        if kind == "string":
            if t.kind != STRING:
                raise self.error(f"{command.name} expects a text in quotes here, found {describe(t)}")
            self.advance()
            return ast.Str(t.loc, t.value)
        if kind == "array":
            if t.is_word("DYNMEM") and command.name == "TESTSETDEST":  # DG 7120: or keyword DYNMEM
                self.advance()
                return ast.Word(t.loc, "DYNMEM")
            name = self.expect_ident(f"the name of an array for {command.name}")
            if self.tok.is_op("[") and self.peek().is_op("]"):
                self.advance()
                self.advance()
            return ast.ArrayArg(name.loc, name.value, name.text)
        if kind == "var":
            if t.kind != IDENT or self.match_command() is not None:
                raise self.error(f"{command.name} writes its result into a variable here; found {describe(t)}")
            target = self.variable_or_call()
            if isinstance(target, ast.Call):
                raise self.error("a function call cannot receive a result", t)
            if self.tok.is_op("."):
                dot = self.advance()
                target = self._selector(target, dot)
            return ast.OutRef(t.loc, target)
        if kind == "param" and t.kind == IDENT and self.match_command() is None:
            number = self.parameter_number(t.value)
            if number is not None:
                self.advance()
                return ast.ParamRef(t.loc, t.value, number)
        if kind == "print":
            raise self.error("PRINT items are parsed by the statement parser", t)
        if t.kind == STRING:
            raise self.error(f"{command.name} does not take a text here", t)
        if t.kind == TERMINAL:
            if command.name not in ("OUT", "IN"):
                raise self.error(f"a connector pin like {t.text} is only allowed in OUT and IN", t)
            self.advance()
            return ast.Str(t.loc, t.value)
        self._in_argument = True
        try:
            value = self.unary()
        finally:
            self._in_argument = False
        while self.tok.is_op("."):  # OUT 1 flags.3: a selector needs no parentheses in an argument
            value = self._selector(value, self.advance())
        return value

    def parameter_number(self, name: str) -> int | None:  # overridden by the statement parser
        return None


def describe(t: Token) -> str:
    if t.kind == NEWLINE:
        return "end of line"
    if t.kind == EOF:
        return "end of file"
    if t.kind == STRING:
        return f"text {t.text}"
    if t.kind == TERMINAL:
        return f"connector pin {t.text}"
    return f"'{t.text}'"
