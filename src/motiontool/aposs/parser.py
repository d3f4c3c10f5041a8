"""APOSS statement parser: tokens (from the preprocessor) → ast.Program.

One statement per line. Program layout (DG 6086-6180): DIM first, pragmas directly after it, declarations,
functions and main code in any order outside the one SUBMAINPROG … ENDPROG area, which holds only
SUBPROG name … RETURN blocks.
"""

from __future__ import annotations

from motiontool.aposs import ast, constexpr, semantics
from motiontool.aposs.commands import CommandTable, command_table
from motiontool.aposs.constexpr import fold_int
from motiontool.aposs.exprparse import ExpressionParser, describe
from motiontool.aposs.lexer import EOF, IDENT, NEWLINE, PRAGMA, Token
from motiontool.aposs.shadow import shadowed_commands, subprogram_name_warning
from motiontool.language.diagnostics import Cancelled, CompileError, Location

_POSITION_KINDS = ("APOS", "IPOS", "MAPOS", "MCPOS", "MIPOS")
_VALUE_KINDS = ("INT", "PERIOD", "TIME", "COMBIT", "STATBIT", "PARAM", "CANINPUT")
_PLAIN_KINDS = ("ERROR", "KEYPRESSED", "CANMSG")
_BLOCK_END = {"ENDIF", "ELSEIF", "ELSE", "ENDWHILE", "UNTIL", "CASE", "DEFAULT", "ENDSWITCH", "RETURN",
              "ENDPROG", "SUBPROG", "SUBMAINPROG"}


class Parser(ExpressionParser):
    def __init__(self, tokens: list[Token], commands: CommandTable | None = None,
                 parameter_lookup=None):
        self.toks = tokens
        self.i = 0
        self.commands = commands or command_table()
        self.function_names: set[str] = set()
        self._parameter_lookup = parameter_lookup
        self._in_function = False
        self.cancelled = None  # a callable: True when the caller no longer wants the result
        # command names the program uses as its variables (L14): those names are not commands here
        self.shadowed, self.warnings = shadowed_commands(tokens, self.commands)

    def parameter_number(self, name: str) -> int | None:
        return self._parameter_lookup(name) if self._parameter_lookup else None

    # --- program ------------------------------------------------------------------------------------
    def parse_program(self) -> ast.Program:
        program = ast.Program(self.tok.loc, [], [], [])
        while True:
            self._skip_newlines()
            t = self.tok
            if t.kind == EOF:
                return program
            if self.cancelled is not None and self.cancelled():
                raise Cancelled
            if t.is_word("SUBMAINPROG"):
                if program.subarea is not None:
                    raise self.error(f"only one SUBMAINPROG area is allowed (the first is at {program.subarea})")
                program.subarea = t.loc
                program.end_of_main_loc = t.loc
                program.subprograms = self._subprogram_area()
                program.order.append(("subarea", None))
            elif t.is_word("ENDPROG"):
                raise self.error("ENDPROG without SUBMAINPROG")
            elif t.is_word("SUBPROG"):
                raise self.error("SUBPROG must stand inside the SUBMAINPROG … ENDPROG area")
            elif t.is_word("RETURN"):
                raise self.error("RETURN outside a subprogram (SUBPROG name … RETURN)")
            elif t.is_word("LONG", "DOUBLE") and self.peek().kind == IDENT and self.peek(2).is_op("("):
                program.functions.append(self._function())
                program.order.append(("func", program.functions[-1]))
            else:
                stmt = self.statement()
                if stmt is not None:
                    program.statements.append(stmt)
                    program.order.append(("stmt", stmt))

    def _skip_newlines(self) -> None:
        while self.tok.kind == NEWLINE:
            self.advance()

    def _end_statement(self, what: str = "") -> None:
        if self.tok.kind in (NEWLINE, EOF):
            self.advance()
            return
        t = self.tok
        if t.kind == "OP" and t.text in ("+", "-", "*", "%", "&", "|", "^", "<<", ">>", "==", "<", ">") or \
                t.is_word("MOD", "RND", "AND", "OR", "EXP"):
            raise self.error(f"a command argument that is an expression must be in parentheses, "
                             f"e.g. POSA (a + 5); found {describe(t)}")
        raise self.error(f"unexpected {describe(t)} after {what or 'the statement'}; one statement per line")

    # --- blocks ---------------------------------------------------------------------------------------
    def block(self, terminators: tuple[str, ...], opener: Token, closing: str) -> tuple[list[ast.Stmt], Token]:
        body: list[ast.Stmt] = []
        while True:
            self._skip_newlines()
            t = self.tok
            if t.kind == EOF:
                raise self.error(f"{opener.text.upper()} at {opener.loc} is not closed: missing {closing}", opener)
            if (t.kind == IDENT and t.value in terminators) or (t.is_op("}") and "}" in terminators):
                return body, t
            if t.kind == IDENT and t.value in _BLOCK_END and not (t.value == "RETURN" and self._in_function):
                raise self.error(f"{t.text} does not belong here: {opener.text.upper()} at {opener.loc} "
                                 f"needs {closing} first")
            if t.is_op("}"):
                raise self.error("'}' without a function body")
            stmt = self.statement()
            if isinstance(stmt, ast.Dim):
                raise CompileError("DIM must come before all other statements (DG 6439), not inside a block or "
                                   "function", stmt.loc)
            if isinstance(stmt, ast.Pragma):
                raise CompileError("#pragma must stand directly after the DIM statement (DG 6090)", stmt.loc)
            if stmt is not None:
                body.append(stmt)

    # --- statements ---------------------------------------------------------------------------------
    def statement(self) -> ast.Stmt | None:
        t = self.tok
        if t.kind == PRAGMA:
            self.advance()
            self._end_statement()
            return ast.Pragma(t.loc, t.value)
        if t.kind != IDENT:
            if t.is_op("{"):
                raise self.error("'{' without a function header: long name(...) or double name(...)")
            raise self.error(f"a statement cannot start with {describe(t)}")
        if self.peek().is_op(":") and t.value not in ("CASE", "DEFAULT"):
            self.advance()
            self.advance()
            if self.commands.get(t.value) is not None:
                raise self.error(f"'{t.text}' is a command name and cannot be a label", t)
            stmt = ast.Label(t.loc, t.value, t.text)
            self._end_statement(f"the label '{t.text}:'")
            return stmt
        handler = getattr(self, "_stmt_" + t.value.lower(), None)
        if handler is not None and t.value in _KEYWORD_HANDLERS:
            return handler()
        command = self.match_command()
        if command is not None:
            return self._command_statement(command, t)
        if t.value in ("LONG", "DOUBLE"):
            return self._declaration()
        if t.value in ("SUBMAINPROG", "ENDPROG", "SUBPROG"):
            raise self.error(f"{t.text} cannot stand inside a block or function")
        return self._assignment_or_call()

    def _command_statement(self, command, t: Token) -> ast.Stmt:
        if command.kind == "pseudoarray":
            return self._assignment_or_call()
        if self.peek(len(command.words)).is_op("=") and not command.args:
            raise self.error(f"'{t.text}' is a command name and cannot be used as a variable", t)
        if not command.statement:
            raise self.error(f"'{command.name}' only gives a value; use it in an expression, e.g. "
                             f"x = {command.syntax}", t)
        if any(a.kind == "print" for a in command.args):
            return self._print(command)
        if self.peek(len(command.words)).is_op("="):
            raise self.error(f"'{t.text}' is a command name and cannot be used as a variable", t)
        call = self.command_call(command, in_expression=False)
        if command.name == "SETVLT" and not self.at_end_of_statement():   # CR 4047 prints SETVLT 025 1 100 (L1)
            raise self.error("SETVLT takes a parameter number and a value; set an element of an indexed parameter "
                             "with SETVLTSUB par indxno v (CR 4031)")
        self._end_statement(command.name)
        return ast.Command(t.loc, call)

    def _print(self, command) -> ast.Stmt:
        t = self.tok
        for _ in command.words:
            self.advance()
        device = None
        if command.args[0].kind != "print":  # PRINTDEV n items
            device = self.argument(command.args[0], command)
            if self.tok.is_op(","):
                self.advance()
        items: list[ast.Expr] = []
        newline = True
        if not self.at_end_of_statement():
            items.append(self.expression())
            while self.tok.is_op(","):
                self.advance()
                items.append(self.expression())
        if self.tok.is_op(";"):  # C:3524-3529: a trailing ';' suppresses the line feed
            self.advance()
            newline = False
        self._end_statement("PRINT")
        return ast.PrintStmt(t.loc, items, newline, device)

    def _assignment_or_call(self) -> ast.Stmt:
        t = self.tok
        if self.peek().is_op("[") and self.peek(2).is_op("]"):
            self.i += 3
            self.expect_op("=", " in the array copy 'a[] = b[]'")
            src = self.expect_ident("the source array of the copy")
            self.expect_op("[", " (write the source as 'b[]')")
            self.expect_op("]", " (write the source as 'b[]')")
            self._end_statement("the array copy")
            return ast.ArrayCopy(t.loc, t.value, src.value, t.text, src.text)
        if t.value in _OPENER_OF:
            raise self.error(f"{t.text} without {_OPENER_OF[t.value]}", t)
        if (entry := self.commands.get(t.value)) is not None and self.match_command() is None and \
                entry.kind in ("keyword", "operator", "interrupt"):
            raise self.error(f"'{t.text}' cannot start a statement here", t)
        command = self.match_command()
        if command is not None and command.kind == "pseudoarray":
            self.advance()
            self.expect_op("[", f" after {command.name}")
            index = self.expression()
            self.expect_op("]", " to close the index")
            target: ast.Expr = ast.Pseudo(t.loc, command.name, index)
        else:
            target = self.variable_or_call()
        if isinstance(target, ast.Call):
            self._end_statement(f"the call of '{t.text}'")
            return ast.ExprStmt(t.loc, target)
        if self.tok.is_op("++", "--"):
            op = self.advance().text
            self._end_statement()
            return ast.ExprStmt(t.loc, ast.PostIncrement(t.loc, op, target))
        if self.tok.is_op("."):
            target = self._selector(target, self.advance())
        if not self.tok.is_op("="):
            if isinstance(target, ast.Name) and self.at_end_of_statement():
                raise self.error(f"unknown command '{t.text}'", t)
            if isinstance(target, ast.Name) and not self.tok.kind == "OP":
                raise self.error(f"unknown command '{t.text}'", t)
            raise self.error(f"expected '=' after '{t.text}', found {describe(self.tok)}")
        self.advance()
        value = self.expression()
        self._end_statement("the assignment")
        return ast.Assign(t.loc, target, value)

    # --- control structures -----------------------------------------------------------------------------
    def _stmt_if(self) -> ast.Stmt:
        opener = self.advance()
        branches: list[tuple[ast.Expr, list[ast.Stmt]]] = []
        cond = self._condition("IF", "THEN")
        first: list[ast.Stmt] = []
        if self.tok.is_word("ENDIF", "ELSE", "ELSEIF"):
            pass  # IF c THEN ENDIF on one line: an empty body
        elif not self.at_end_of_statement():  # C:2427: IF … THEN statement / ENDIF
            stmt = self.statement()
            first = [stmt] if stmt else []
        else:
            self.advance()
        body, end = self.block(("ELSEIF", "ELSE", "ENDIF"), opener, "ENDIF")
        branches.append((cond, first + body))
        orelse = None
        while True:
            t = self.advance()
            if t.value == "ELSEIF":
                cond = self._condition("ELSEIF", "THEN")
                self._end_statement("THEN")
                body, end = self.block(("ELSEIF", "ELSE", "ENDIF"), opener, "ENDIF")
                branches.append((cond, body))
            elif t.value == "ELSE":
                if self.tok.is_word("IF"):
                    raise self.error("write ELSEIF as one word")
                self._end_statement("ELSE")
                orelse, end = self.block(("ENDIF",), opener, "ENDIF")
                if end.value != "ENDIF":
                    raise self.error("ELSE must be the last branch before ENDIF", end)
            else:
                self._end_statement("ENDIF")
                return ast.If(opener.loc, branches, orelse)

    def _condition(self, keyword: str, closing: str) -> ast.Expr:
        if self.at_end_of_statement():
            raise self.error(f"{keyword} needs a condition")
        cond = self.expression()
        if not self.tok.is_word(closing):
            raise self.error(f"{keyword} condition must end with {closing}; found {describe(self.tok)}")
        self.advance()
        return cond

    def _stmt_while(self) -> ast.Stmt:
        opener = self.advance()
        cond = self._condition("WHILE", "DO")
        self._end_statement("DO")
        body, _ = self.block(("ENDWHILE",), opener, "ENDWHILE")
        self.advance()
        self._end_statement("ENDWHILE")
        return ast.While(opener.loc, cond, body)

    def _stmt_repeat(self) -> ast.Stmt:
        opener = self.advance()
        self._end_statement("REPEAT")
        body, _ = self.block(("UNTIL",), opener, "UNTIL")
        self.advance()
        if self.at_end_of_statement():
            raise self.error("UNTIL needs a condition")
        cond = self.expression()
        self._end_statement("the UNTIL condition")
        return ast.Repeat(opener.loc, body, cond)

    def _stmt_switch(self) -> ast.Stmt:
        opener = self.advance()
        if self.at_end_of_statement():
            raise self.error("SWITCH needs a value")
        value = self.expression()
        self._end_statement("the SWITCH value")
        cases: list[tuple[list[ast.Expr], list[ast.Stmt], Location]] = []
        self._skip_newlines()
        while not self.tok.is_word("ENDSWITCH"):
            t = self.tok
            if t.is_word("CASE"):
                self.advance()
                label = [self.expression()]
            elif t.is_word("DEFAULT"):
                self.advance()
                label = []
                if any(not c[0] for c in cases):
                    raise self.error("only one DEFAULT in a SWITCH", t)
            elif t.kind == EOF:
                raise self.error(f"SWITCH at {opener.loc} is not closed: missing ENDSWITCH", opener)
            else:
                raise self.error(f"expected CASE, DEFAULT or ENDSWITCH inside SWITCH, found {describe(t)}")
            self.expect_op(":", f" after {t.text.upper()}")
            if not self.at_end_of_statement():
                first = [self.statement()]
            else:
                self.advance()
                first = []
            body, _ = self.block(("CASE", "DEFAULT", "ENDSWITCH"), opener, "ENDSWITCH")
            cases.append((label, [s for s in first if s] + body, t.loc))
        self.advance()
        self._end_statement("ENDSWITCH")
        return ast.Switch(opener.loc, value, cases)

    def _stmt_loop(self) -> ast.Stmt:
        t = self.advance()
        if self.at_end_of_statement():
            raise self.error("LOOP needs a count and a label: LOOP n label")
        count = self.expression()
        label = self.expect_ident("the label LOOP jumps back to")
        self._end_statement("LOOP")
        return ast.Loop(t.loc, count, label.value, label.text)

    def _stmt_goto(self) -> ast.Stmt:
        t = self.advance()
        label = self.expect_ident("a label after GOTO")
        self._end_statement("GOTO")
        return ast.Goto(t.loc, label.value, label.text)

    def _stmt_gosub(self) -> ast.Stmt:
        t = self.advance()
        name = self.expect_ident("a subprogram name after GOSUB")
        self._end_statement("GOSUB")
        return ast.Gosub(t.loc, name.value, name.text)

    def _stmt_break(self) -> ast.Stmt:
        t = self.advance()
        self._end_statement("BREAK")
        return ast.Break(t.loc)

    def _stmt_exit(self) -> ast.Stmt:
        t = self.advance()
        self._end_statement("EXIT")
        return ast.Exit(t.loc)

    def _stmt_return(self) -> ast.Stmt:
        t = self.advance()
        if not self._in_function:
            raise self.error("RETURN outside a subprogram; a subprogram has exactly one RETURN, at its end", t)
        value = None if self.at_end_of_statement() else self.expression()
        self._end_statement("return")
        return ast.Return(t.loc, value)

    def _stmt_dim(self) -> ast.Stmt:
        t = self.advance()
        arrays = [self._declarator(array_required=True)]
        while self.tok.is_op(","):
            self.advance()
            arrays.append(self._declarator(array_required=True))
        self._end_statement("DIM")
        return ast.Dim(t.loc, arrays)

    def _declaration(self) -> ast.Stmt:
        t = self.advance()
        names = [self._declarator(array_required=False)]
        while self.tok.is_op(","):
            self.advance()
            names.append(self._declarator(array_required=False))
        if self.tok.is_op("="):
            raise self.error("declarations cannot give a value; assign it on the next line")
        self._end_statement("the declaration")
        return ast.VarDecl(t.loc, t.value.lower(), names)

    def _declarator(self, array_required: bool) -> ast.Declarator:
        name = self.expect_ident("a name")
        if self.commands.get(name.value) is not None and name.value not in self.shadowed:
            raise self.error(f"'{name.text}' is a command name and cannot name a variable or array", name)
        dims: list[int] = []
        while self.tok.is_op("["):
            self.advance()
            size = fold_int(self.expression())
            if size is None or size < 1:
                raise self.error("an array size must be a positive constant", name)
            dims.append(size)
            self.expect_op("]", " to close the array size")
        if array_required and not dims:
            raise self.error(f"DIM needs a size: DIM {name.text}[n]", name)
        if len(dims) > 2:
            raise self.error("arrays have at most two dimensions", name)
        return ast.Declarator(name.loc, name.value, name.text, dims)

    # --- interrupts ----------------------------------------------------------------------------------------
    def _stmt_on(self) -> ast.Stmt:
        t = self.advance()
        delete = False
        if self.tok.is_word("DELETE"):
            self.advance()
            delete = True
        sign = 1
        if self.tok.is_op("+", "-") and self.peek().is_word(*_POSITION_KINDS):
            sign = -1 if self.advance().text == "-" else 1
        kind_tok = self.tok
        value: ast.Expr | None = None
        if kind_tok.is_word(*_POSITION_KINDS):
            kind = self.advance().value
            if not (delete and self.tok.is_word("SETOUT", "GOSUB")):  # ON DELETE +APOS SETOUT 1 (C:2603)
                value = self._on_value(kind)
        elif delete:
            kind = "POSITION"  # ON DELETE pos GOSUB name / ON DELETE pos SETOUT n (C:2601-2628)
            value = self._on_value("DELETE")
        elif kind_tok.is_word(*_VALUE_KINDS):
            kind = self.advance().value
            value = self._on_value(kind)
        elif kind_tok.is_word(*_PLAIN_KINDS):
            kind = self.advance().value
        else:
            raise self.error("unknown interrupt: expected ON ERROR, INT, APOS, IPOS, MAPOS, MCPOS, MIPOS, PERIOD, "
                             f"TIME, COMBIT, STATBIT, PARAM, KEYPRESSED, CANMSG, CANINPUT or DELETE; found "
                             f"{describe(kind_tok)}")
        if self.tok.is_word("GOSUB"):
            self.advance()
            name = self.expect_ident("a subprogram name after GOSUB")
            self._end_statement("the ON statement")
            return ast.OnInterrupt(t.loc, kind, sign, value, name.value, name.text, delete=delete)
        if self.tok.is_word("SETOUT") and (kind in _POSITION_KINDS or kind == "POSITION"):
            self.advance()
            out = self.unary()
            toin = None
            if self.tok.is_word("TOIN"):
                self.advance()
                toin = self.unary()
            self._end_statement("the ON statement")
            return ast.OnInterrupt(t.loc, kind, sign, value, None, None, out, toin, delete)
        raise self.error(f"expected GOSUB after ON {kind_tok.text}; found {describe(self.tok)}")

    def _on_value(self, kind: str) -> ast.Expr:
        if self.tok.is_word("GOSUB", "SETOUT") or self.at_end_of_statement():
            what = {"INT": "an input number", "PERIOD": "a period in ms", "TIME": "a time in ms",
                    "COMBIT": "a bit number", "STATBIT": "a bit number", "PARAM": "a parameter number",
                    "CANINPUT": "an identifier (0)"}.get(kind, "a position")
            raise self.error(f"ON {kind} needs {what} before {describe(self.tok)}")
        return self.expression()

    # --- subprograms and functions -----------------------------------------------------------------------
    def _subprogram_area(self) -> list[ast.Subprogram]:
        opener = self.advance()
        self._end_statement("SUBMAINPROG")
        subs: list[ast.Subprogram] = []
        while True:
            self._skip_newlines()
            t = self.tok
            if t.is_word("ENDPROG"):
                self.advance()
                self._end_statement("ENDPROG")
                return subs
            if t.kind == EOF:
                raise self.error(f"SUBMAINPROG at {opener.loc} is not closed: missing ENDPROG", opener)
            if t.is_word("LONG", "DOUBLE") and self.peek(2).is_op("("):
                raise self.error("functions cannot be defined inside SUBMAINPROG … ENDPROG (DG 6090)")
            if not t.is_word("SUBPROG"):
                raise self.error(f"only SUBPROG name … RETURN blocks may stand between SUBMAINPROG and "
                                 f"ENDPROG; found {describe(t)}")
            self.advance()
            name = self.expect_ident("the subprogram's name")
            if (entry := self.commands.get(name.value)) is not None:
                self.warnings.append(subprogram_name_warning(name, entry.kind))
            self._end_statement("SUBPROG name")
            body, end = self.block(("RETURN",), t, "RETURN")
            self.advance()
            self._end_statement("RETURN")
            subs.append(ast.Subprogram(t.loc, name.value, name.text, body, end.loc))

    def _function(self) -> ast.Function:
        type_tok = self.advance()
        name = self.advance()
        if self.commands.get(name.value) is not None:
            raise self.error(f"'{name.text}' is a command name and cannot name a function", name)
        self.expect_op("(")
        params: list[ast.Param] = []
        if not self.tok.is_op(")"):
            params.append(self._param())
            while self.tok.is_op(","):
                self.advance()
                params.append(self._param())
        self.expect_op(")", " to close the parameter list")
        self.function_names.add(name.value)
        func = ast.Function(type_tok.loc, type_tok.value.lower(), name.value, name.text, params, None)
        if self.tok.is_op(";"):
            self.advance()
            self._end_statement("the function declaration")
            return func
        self._skip_newlines()
        opener = self.expect_op("{", " to open the function body (or ';' to end a declaration)")
        if not self.at_end_of_statement():
            raise self.error("write the function body on the lines after '{'")
        self._in_function = True
        try:
            body, _ = self.block(("}",), opener, "'}'")
        finally:
            self._in_function = False
        self.advance()
        self._end_statement("'}'")
        func.body = body
        return func

    def _param(self) -> ast.Param:
        t = self.tok
        if not t.is_word("LONG", "DOUBLE"):
            raise self.error(f"a parameter needs a type, LONG, DOUBLE or LONG[]; found {describe(t)}")
        self.advance()
        is_array = False
        if self.tok.is_op("["):
            self.advance()
            self.expect_op("]", " in the array parameter type 'long[]'")
            is_array = True
        name = self.expect_ident("the parameter's name")
        if self.commands.get(name.value) is not None and name.value not in self.shadowed:
            raise self.error(f"'{name.text}' is a command name and cannot name a parameter", name)
        return ast.Param(t.loc, t.value.lower(), name.value, name.text, is_array)


_OPENER_OF = {"ENDIF": "IF", "ELSE": "IF", "ELSEIF": "IF", "ENDWHILE": "WHILE", "UNTIL": "REPEAT",
              "ENDSWITCH": "SWITCH", "CASE": "SWITCH", "DEFAULT": "SWITCH", "THEN": "IF", "DO": "WHILE"}
_KEYWORD_HANDLERS = {"IF", "WHILE", "REPEAT", "SWITCH", "LOOP", "GOTO", "GOSUB", "BREAK", "EXIT", "RETURN",
                     "DIM", "ON"}


def parse(tokens: list[Token], commands: CommandTable | None = None, parameter_lookup=None,
          cancelled=None, warnings: list | None = None) -> ast.Program:
    """`warnings` (if given) receives the parser's warnings, also when it stops with an error."""
    parser = Parser(tokens, commands, parameter_lookup)
    parser.cancelled = cancelled
    try:
        return parser.parse_program()
    except RecursionError:
        raise CompileError("expression nested too deeply", parser.tok.loc) from None
    finally:
        if warnings is not None:
            warnings.extend(parser.warnings)


def evaluate_tokens(tokens: list[Token], loc: Location) -> int | float:
    """Evaluate a #if condition (tokens after macro expansion)."""
    end = Token(NEWLINE, "\n", None, tokens[-1].loc)
    parser = Parser(tokens + [end, Token(EOF, "", None, end.loc)])
    expr = parser.expression()
    if not parser.at_end_of_statement():
        raise CompileError(f"unexpected '{parser.tok.text}' in the #if condition", parser.tok.loc)
    try:
        return constexpr.fold(expr)
    except constexpr.NotConstant:
        raise CompileError("#if needs a constant integer expression", loc) from None
    except semantics.OperatorError as exc:
        raise CompileError(f"#if condition: {exc}", loc) from None
