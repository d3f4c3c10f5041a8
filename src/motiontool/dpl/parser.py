"""DPL parser: tokens → ast.Program. Stops at the first syntax error with one precise diagnostic.

A program is a set of task blocks (``Initial { … }``, ``Background { … }``, ``Pos0 { … }``, ``Pos1 { … }``,
``Notes { … }``); one statement per line. Expression priorities, lowest first (docs/decisions.md A51):
OR; AND; NOT; comparisons ``= <> < > <= >=``; bitwise ``& |``; ``+ -``; ``* /``; unary ``-``; bit access
``Name%.n``.
"""

from __future__ import annotations

from motiontool.dpl import ast
from motiontool.dpl.lexer import EOF, FLOAT, IDENT, INT, NEWLINE, NOTES, OP, PARAM, STRING, Token
from motiontool.language.diagnostics import CompileError

# Task names as SyPT writes them; the checks decide which ones the simulator runs.
TASKS = {"INITIAL": "Initial", "BACKGROUND": "Background", "POS0": "Pos0", "POS1": "Pos1", "CLOCK": "Clock",
         "EVENT": "Event", "EVENT1": "Event1", "EVENT2": "Event2", "EVENT3": "Event3", "ERROR": "Error",
         "NOTES": "Notes"}
KEYWORDS = frozenset({"IF", "THEN", "ELSEIF", "ELSE", "ENDIF", "GOTO", "REINIT", "DIM", "CONST", "AND", "OR",
                      "NOT"})
# DPL words the manual's programs never use: refused by name rather than as a strange syntax error.
UNSUPPORTED = frozenset({"WHILE", "ENDWHILE", "FOR", "TO", "STEP", "NEXT", "DO", "LOOP", "UNTIL", "SELECT",
                         "CASE", "ENDSELECT", "GOSUB", "RETURN", "BREAK", "PRINT", "FUNCTION", "ENDFUNCTION"})
_COMPARE = ("=", "<>", "<", ">", "<=", ">=")
MAX_NESTING = 100  # IF blocks and parentheses; deeper programs get an error instead of exhausting Python's stack
_BLOCK_END = ("ELSEIF", "ELSE", "ENDIF")


def parse(tokens: list[Token]) -> ast.Program:
    return Parser(tokens).program()


class Parser:
    def __init__(self, tokens: list[Token]):
        self.toks = tokens
        self.i = 0
        self.depth = 0

    # --- token helpers ---------------------------------------------------------------------------------------
    @property
    def tok(self) -> Token:
        return self.toks[self.i]

    def peek(self, k: int = 1) -> Token:
        return self.toks[min(self.i + k, len(self.toks) - 1)]

    def advance(self) -> Token:
        t = self.toks[self.i]
        if t.kind != EOF:
            self.i += 1
        return t

    def error(self, message: str, tok: Token | None = None) -> CompileError:
        return CompileError(message, (tok or self.tok).loc)

    def expect_op(self, op: str, what: str) -> Token:
        if not self.tok.is_op(op):
            raise self.error(f"expected '{op}' {what}, found {describe(self.tok)}")
        return self.advance()

    def end_of_line(self, what: str) -> None:
        if self.tok.kind != NEWLINE:
            raise self.error(f"expected the end of the line after {what}, found {describe(self.tok)}")
        self.advance()

    def skip_newlines(self) -> None:
        while self.tok.kind == NEWLINE:
            self.advance()

    # --- program and tasks -----------------------------------------------------------------------------------
    def program(self) -> ast.Program:
        program = ast.Program(self.tok.loc)
        self._program = program
        while True:
            self.skip_newlines()
            t = self.tok
            if t.kind == EOF:
                return program
            if t.kind == NOTES:
                self.advance()
                self.expect_op("}", "closing the Notes task")
                program.notes += _name(t)
                continue
            if t.kind == IDENT and t.value in TASKS and self._task_opens():
                self._task(program)
                continue
            if t.kind == IDENT and t.value == "CONST":
                program.consts.append(self._const())
                continue
            raise self.error("statements belong inside a task: Initial { … }, Background { … }, Pos0 { … } "
                             f"or Pos1 {{ … }}; found {describe(t)}")

    def _task_opens(self) -> bool:
        k = 1
        while self.peek(k).kind == NEWLINE:
            k += 1
        return self.peek(k).is_op("{")

    def _task(self, program: ast.Program) -> None:
        name_tok = self.advance()
        name = TASKS[_name(name_tok)]
        if name in program.tasks:
            raise self.error(f"a second {name} task (the first is at {program.tasks[name].loc})", name_tok)
        self.skip_newlines()
        self.expect_op("{", f"after the task name {name}")
        body = self.block(until=("}",), owner=f"the {name} task")
        end = self.expect_op("}", f"closing the {name} task").loc
        program.tasks[name] = ast.Task(name_tok.loc, name, name_tok.text, body, end)
        if self.tok.kind not in (NEWLINE, EOF):
            raise self.error(f"expected the end of the line after the '}}' of {name}, found {describe(self.tok)}")

    def block(self, until: tuple[str, ...], owner: str) -> list[ast.Stmt]:
        """Statements up to (not including) a '}' or one of the words in `until`."""
        body: list[ast.Stmt] = []
        while True:
            self.skip_newlines()
            t = self.tok
            if t.kind == EOF:
                raise self.error(f"end of file inside {owner}: its closing "
                                 + ("'}'" if "}" in until else "ENDIF") + " is missing")
            if t.is_op("}"):
                if "}" in until:
                    return body
                raise self.error(f"'}}' inside {owner}: ENDIF is missing")
            if t.kind == IDENT and t.value in until:
                return body
            if t.kind == IDENT and t.value in _BLOCK_END:
                raise self.error(f"{t.value} without IF … THEN")
            body.append(self.statement())

    # --- statements ------------------------------------------------------------------------------------------
    def statement(self) -> ast.Stmt:
        t = self.tok
        if t.kind == IDENT and self.peek().is_op(":") and not _name(t).endswith("%"):
            self.advance()
            self.advance()
            return ast.Label(t.loc, _name(t), t.text)
        stmt = self.simple_statement()
        if not isinstance(stmt, ast.If):
            self.end_of_line(describe_stmt(stmt))
        return stmt

    def simple_statement(self) -> ast.Stmt:
        t = self.tok
        if t.kind == IDENT:
            word = _name(t)
            if word == "IF":
                return self._if()
            if word == "GOTO":
                self.advance()
                label = self.tok
                if label.kind != IDENT or _name(label).endswith("%"):
                    raise self.error(f"GOTO needs a label name, found {describe(label)}")
                self.advance()
                if self.tok.is_op(":"):
                    self.advance()
                return ast.Goto(t.loc, _name(label), label.text)
            if word == "REINIT":
                self.advance()
                return ast.Reinit(t.loc)
            if word == "DIM":
                return self._dim()
            if word == "CONST":
                const = self._const()
                self._program.consts.append(const)
                return const
            if word in UNSUPPORTED:
                raise self.error(f"'{t.text}' is not supported by this DPL simulator (the APC manual's programs "
                                 "do not use it); write the loop with a label and GOTO")
            if word in KEYWORDS:
                raise self.error(f"'{t.text}' cannot start a statement")
            if not word.endswith("%") and self.peek().is_op("("):
                return ast.CallStmt(t.loc, self.call())
        if t.is_op("("):
            return self._tuple_assign()
        target = self.target()
        if not self.tok.is_op("="):
            raise self.error(f"expected '=' after {describe_target(target)}, found {describe(self.tok)}")
        self.advance()
        return ast.Assign(t.loc, target, self.expression())

    def target(self) -> ast.Expr:
        t = self.tok
        if t.kind == PARAM:
            self.advance()
            return self._bit(ast.Param(t.loc, *_param(t)))
        if t.kind == IDENT and _name(t).endswith("%"):
            return self._bit(self._variable())
        if t.kind == IDENT and t.value not in KEYWORDS:
            raise self.error(f"'{t.text}' cannot be assigned: integer variables end with '%' (floating-point "
                             "variables are not supported by this simulator)")
        raise self.error(f"expected a statement, found {describe(t)}")

    def _variable(self) -> ast.Expr:
        t = self.advance()
        if self.tok.is_op("["):
            self.advance()
            index = self.expression()
            self.expect_op("]", f"after the index of {t.text}")
            return ast.Elem(t.loc, _name(t), t.text, index)
        return ast.Var(t.loc, _name(t), t.text)

    def _bit(self, base: ast.Expr) -> ast.Expr:
        if not self.tok.is_op("."):
            return base
        self.advance()
        t = self.tok
        if t.kind != INT or not 0 <= _int(t) <= 31:
            raise self.error(f"a bit number 0..31 follows '.', found {describe(t)}")
        self.advance()
        return ast.Bit(base.loc, base, _int(t))

    def _tuple_assign(self) -> ast.Stmt:
        start = self.advance()
        targets = [self.target()]
        while self.tok.is_op(","):
            self.advance()
            targets.append(self.target())
        self.expect_op(")", "closing the list of results")
        self.expect_op("=", "after the list of results")
        t = self.tok
        if t.kind != IDENT or _name(t).endswith("%") or not self.peek().is_op("("):
            raise self.error(f"a list of results takes the results of a function call, found {describe(t)}")
        return ast.TupleAssign(start.loc, targets, self.call())

    def _if(self) -> ast.If:
        start = self.advance()
        self._nest(start)
        try:
            return self._if_body(start)
        finally:
            self.depth -= 1

    def _nest(self, tok: Token) -> None:
        self.depth += 1
        if self.depth > MAX_NESTING:
            raise self.error(f"nested deeper than {MAX_NESTING} levels (IF blocks and parentheses)", tok)

    def _if_body(self, start: Token) -> ast.If:
        branches: list[tuple[ast.Expr, list[ast.Stmt]]] = []
        cond = self._condition()
        if self.tok.kind != NEWLINE:  # IF c THEN statement: one line, no ENDIF
            stmt = self.simple_statement()
            if isinstance(stmt, ast.If):
                raise self.error("a one-line IF takes one simple statement, not another IF", start)
            self.end_of_line(describe_stmt(stmt))
            return ast.If(start.loc, [(cond, [stmt])])
        self.advance()
        branches.append((cond, self.block(until=_BLOCK_END, owner=f"the IF at {start.loc}")))
        orelse = None
        while True:
            t = self.tok
            if t.value == "ELSEIF":
                self.advance()
                cond = self._condition()
                self.end_of_line("ELSEIF … THEN")
                branches.append((cond, self.block(until=_BLOCK_END, owner=f"the IF at {start.loc}")))
            elif t.value == "ELSE":
                if orelse is not None:
                    raise self.error(f"a second ELSE in the IF at {start.loc}")
                self.advance()
                if self.tok.is_word("IF"):
                    raise self.error("write ELSEIF as one word (ELSE IF would need its own ENDIF)")
                self.end_of_line("ELSE")
                orelse = self.block(until=_BLOCK_END, owner=f"the IF at {start.loc}")
                if self.tok.value != "ENDIF":
                    raise self.error(f"{self.tok.value} after ELSE: ENDIF expected")
            else:  # ENDIF
                self.advance()
                self.end_of_line("ENDIF")
                return ast.If(start.loc, branches, orelse)

    def _condition(self) -> ast.Expr:
        cond = self.expression()
        if not self.tok.is_word("THEN"):
            raise self.error(f"expected THEN after the condition, found {describe(self.tok)}")
        self.advance()
        return cond

    def _dim(self) -> ast.Stmt:
        start = self.advance()
        t = self.tok
        if t.kind != IDENT or not _name(t).endswith("%"):
            raise self.error(f"DIM needs an integer array name ending in '%', found {describe(t)}")
        self.advance()
        self.expect_op("[", f"after DIM {t.text}")
        size = self.expression()
        self.expect_op("]", f"after the size of {t.text}")
        return ast.Dim(start.loc, _name(t), t.text, size)

    def _const(self) -> ast.ConstArray:
        start = self.advance()
        t = self.tok
        if t.kind != IDENT or not _name(t).endswith("%"):
            raise self.error(f"CONST needs an integer array name ending in '%', found {describe(t)}")
        self.advance()
        self.expect_op("[", f"after CONST {t.text}")
        size = None if self.tok.is_op("]") else self.expression()
        self.expect_op("]", f"after the size of {t.text}")
        self.expect_op("=", f"before the values of {t.text}")
        self.skip_newlines()
        self.expect_op("{", f"opening the values of {t.text}")
        values: list[ast.Expr] = []
        while True:
            self.skip_newlines()
            if self.tok.is_op("}") and not values:
                break
            values.append(self.expression())
            self.skip_newlines()
            if self.tok.is_op(","):
                self.advance()
                continue
            break
        self.expect_op("}", f"closing the values of {t.text}")
        return ast.ConstArray(start.loc, _name(t), t.text, size, values)

    # --- expressions -----------------------------------------------------------------------------------------
    def expression(self) -> ast.Expr:
        return self._binary(0)

    _LEVELS: tuple[tuple[str, ...], ...] = (("OR",), ("AND",), (), _COMPARE, ("&", "|"), ("+", "-"), ("*", "/"))

    def _binary(self, level: int) -> ast.Expr:
        if level == len(self._LEVELS):
            return self._unary()
        if level == 2:  # NOT binds looser than comparisons: NOT a = b is NOT (a = b)
            if self.tok.is_word("NOT"):
                t = self.advance()
                return ast.Unary(t.loc, "NOT", self._binary(2))
            return self._binary(3)
        ops = self._LEVELS[level]
        left = self._binary(level + 1)
        while (self.tok.kind == OP and self.tok.text in ops) or (self.tok.kind == IDENT and self.tok.value in ops):
            t = self.advance()
            op = _name(t) if t.kind == IDENT else t.text
            left = ast.Binary(t.loc, op, left, self._binary(level + 1))
        return left

    def _unary(self) -> ast.Expr:
        t = self.tok
        if t.is_op("-"):
            self.advance()
            self._nest(t)
            operand = self._unary()
            self.depth -= 1
            if isinstance(operand, ast.Num):
                return ast.Num(t.loc, -operand.value)
            return ast.Unary(t.loc, "-", operand)
        if t.is_op("+"):
            self.advance()
            return self._unary()
        return self._bit(self._primary())

    def _primary(self) -> ast.Expr:
        t = self.tok
        if t.kind == INT:
            self.advance()
            if t.value == 1 << 31:
                raise self.error(f"constant '{t.text}' is outside the integer range", t)
            return ast.Num(t.loc, _int(t))
        if t.kind == PARAM:
            self.advance()
            return ast.Param(t.loc, *_param(t))
        if t.kind == IDENT:
            if _name(t).endswith("%"):
                return self._variable()
            if self.peek().is_op("("):
                return self.call()
            if t.value in KEYWORDS or t.value in UNSUPPORTED:
                raise self.error(f"expected a value, found {describe(t)}")
            self.advance()
            return ast.Alias(t.loc, _name(t), t.text)
        if t.is_op("("):
            self.advance()
            self._nest(t)
            inner = self.expression()
            self.depth -= 1
            self.expect_op(")", "closing the parenthesis")
            return inner
        if t.kind == FLOAT:
            raise self.error(f"'{t.text}': floating-point values are not supported by this simulator "
                             "(DPL integer programs only)")
        if t.kind == STRING:
            raise self.error("strings are not supported by this DPL simulator")
        raise self.error(f"expected a value, found {describe(t)}")

    def call(self) -> ast.Call:
        name = self.advance()
        self.expect_op("(", f"after {name.text}")
        args: list[ast.Expr] = []
        if not self.tok.is_op(")"):
            args.append(self.expression())
            while self.tok.is_op(","):
                self.advance()
                args.append(self.expression())
        self.expect_op(")", f"closing the arguments of {name.text}")
        return ast.Call(name.loc, _name(name), name.text, args)


# The shared APOSS Token keeps its value as `object`; the DPL lexer stores a str for IDENT and NOTES, an int
# for INT and a (menu, parameter) pair for PARAM. These accessors state that to the type checker.
def _name(t: Token) -> str:
    assert isinstance(t.value, str), t
    return t.value


def _int(t: Token) -> int:
    assert isinstance(t.value, int), t
    return t.value


def _param(t: Token) -> tuple[int, int]:
    assert isinstance(t.value, tuple), t
    return t.value


def describe(t: Token) -> str:
    if t.kind == NEWLINE:
        return "the end of the line"
    if t.kind == EOF:
        return "the end of the file"
    if t.kind == NOTES:
        return "a Notes task"
    return f"'{t.text}'"


def describe_target(target: ast.Expr) -> str:
    if isinstance(target, ast.Bit):
        return f"{describe_target(target.base)}.{target.bit}"
    return f"'{getattr(target, 'text', '?')}'"


def describe_stmt(stmt: ast.Stmt) -> str:
    if isinstance(stmt, ast.Assign):
        return "the assignment"
    if isinstance(stmt, ast.CallStmt | ast.TupleAssign):
        return "the call"
    return type(stmt).__name__.upper()
