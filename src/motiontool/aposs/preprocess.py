"""APOSS preprocessor (DG 6814-6994): continuation lines, #include, #define/#undef, conditional compilation,
#pragma. Works on tokens, so every token keeps the file:line:col where it was written; tokens made by a
macro carry the place of the macro's use plus notes naming the macro.
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

from motiontool.aposs.lexer import DIRECTIVE, EOF, IDENT, INT, NEWLINE, OP, PRAGMA, STRING, Token, tokenize
from motiontool.aposs.parser import evaluate_tokens
from motiontool.fileio import MiB
from motiontool.language import source
from motiontool.language.diagnostics import Cancelled, CompileError, Diagnostic, Location

MAX_INCLUDE_DEPTH = 32
# Macro expansion is bounded, so a small file cannot stall or exhaust the compiler (20 doubling #defines are 2^20
# tokens) - and the IDE compiles after every edit (decisions L22).
MAX_LINE_TOKENS = 10_000       # tokens one source line may expand to
MAX_EXPANDED_TOKENS = 200_000  # tokens all macro uses of a program may produce together (100x a 10 000-line one)
MAX_MACRO_DEPTH = 100          # macros inside macros inside macros ...
MAX_SOURCE_BYTES = 16 * MiB    # a program or include file (decisions R4)
_DIRECTIVES = ("include", "define", "undef", "if", "ifdef", "ifndef", "elif", "else", "endif", "pragma")
_NAME = r"[A-Za-z_][A-Za-z0-9_]*"


@dataclass
class Macro:
    name: str
    params: tuple[str, ...] | None  # None for an object-like macro
    body: list[Token]
    loc: Location


@dataclass
class _Cond:
    active: bool        # lines in the current branch are compiled
    taken: bool         # some branch of this #if chain was already true
    parent_active: bool
    loc: Location
    seen_else: bool = False


@dataclass
class SourceFile:
    path: str
    text: str


@dataclass
class PreprocessResult:
    tokens: list[Token]
    files: list[SourceFile] = field(default_factory=list)  # every file read, main file first
    warnings: list[Diagnostic] = field(default_factory=list)


def read_source(path: Path) -> str:
    """Read a program or include file: UTF-8, falling back to Latin-1 (old APOSS files), line ends normalised."""
    return source.read_source(path, MAX_SOURCE_BYTES, "program file")


class Preprocessor:
    def __init__(self, include_dirs: list[Path] | None = None, defines: dict[str, str] | None = None):
        self.include_dirs = list(include_dirs or [])
        self.macros: dict[str, Macro] = {}
        self.result = PreprocessResult([])
        self._stamp = time.localtime()
        self._expanded = 0  # tokens made by macro expansion so far (MAX_EXPANDED_TOKENS)
        self.cancelled = None  # a callable: True when the caller no longer wants the result (checked per line)
        for name, value in (defines or {}).items():
            loc = Location("<command line>", 1, 1)
            self.macros[name] = Macro(name, None, tokenize(value, "<command line>")[:-2], loc)

    # --- entry points -----------------------------------------------------------------------------
    def run_file(self, path: Path) -> PreprocessResult:
        try:
            text = read_source(path)
        except OSError as exc:
            raise CompileError(f"cannot read '{path}': {exc.strerror}", Location(str(path), 1, 1)) from None
        return self.run_text(text, str(path))

    def run_text(self, text: str, name: str) -> PreprocessResult:
        out: list[Token] = []
        self._process(text, name, out, depth=0)
        out.append(Token(EOF, "", None, out[-1].loc if out else Location(name, 1, 1)))
        self.result.tokens = out
        return self.result

    # --- per file ---------------------------------------------------------------------------------
    def _process(self, text: str, name: str, out: list[Token], depth: int) -> None:
        self.result.files.append(SourceFile(name, text))
        tokens = tokenize(text, name, warnings=self.result.warnings)
        conds: list[_Cond] = []
        line: list[Token] = []
        for tok in tokens:
            if tok.kind == EOF:
                break
            if tok.kind != NEWLINE:
                line.append(tok)
                continue
            if self.cancelled is not None and self.cancelled():
                raise Cancelled
            if line and line[0].kind == DIRECTIVE:
                self._directive(line[0], name, conds, out, depth)
            elif line and (not conds or conds[-1].active):
                try:
                    out.extend(self._expand(line, name))
                except RecursionError:
                    raise CompileError("macro expansion nested too deeply", line[0].loc) from None
                out.append(tok)
            elif not line and (not conds or conds[-1].active):
                out.append(tok)  # keep empty lines: the parser counts statements by NEWLINE
            line = []
        if conds:
            raise CompileError("#if without #endif", conds[-1].loc)

    def _directive(self, tok: Token, name: str, conds: list[_Cond], out: list[Token], depth: int) -> None:
        body = re.sub(r"\\\r?\n", " ", tok.value)
        plain = re.sub(r"/\*.*?\*/", " ", body.split("//")[0])  # directive arguments without comments
        m = re.match(r"\s*([A-Za-z_]\w*)?\s*(.*)$", body, re.S)
        assert m is not None  # every part of the pattern may match nothing
        word, rest = (m.group(1) or ""), m.group(2).strip()
        active = not conds or conds[-1].active
        if word.lower() == "include" and word != "include":
            # DG 7061 lists "#INCLUDE file" (the old spelling, DG 6864) against DG 6825 "lower case only" (L16)
            self.result.warnings.append(Diagnostic(
                "warning", "write #include: preprocessor directives are lower case (DG 6825)", tok.loc))
            word = "include"
        if word.lower() in _DIRECTIVES and word != word.lower():
            raise CompileError(f"preprocessor directives must be lower case: write '#{word.lower()}'", tok.loc)
        if word.upper() == "DEBUG" and word == "DEBUG":
            if active:  # DG 3432-3434: #DEBUG lines are ignored since MCO 5.00 (breakpoints instead)
                self.result.warnings.append(Diagnostic("warning", "#DEBUG is ignored (use breakpoints)", tok.loc))
            return
        if word in ("if", "ifdef", "ifndef"):
            if not active:
                conds.append(_Cond(False, True, False, tok.loc))
                return
            value = self._condition(word, rest, tok, name)
            conds.append(_Cond(value, value, True, tok.loc))
            return
        if word in ("elif", "else", "endif"):
            if not conds:
                raise CompileError(f"#{word} without #if", tok.loc)
            top = conds[-1]
            if word == "endif":
                conds.pop()
                return
            if top.seen_else:
                raise CompileError(f"#{word} after #else", tok.loc)
            if word == "else":
                top.seen_else = True
                top.active = top.parent_active and not top.taken
            else:
                value = top.parent_active and not top.taken and self._condition("if", rest, tok, name)
                top.active = value
            top.taken = top.taken or top.active
            return
        if not active:
            return
        if word == "include":
            self._include(rest, tok, name, out, depth)
        elif word == "define":
            self._define(rest, tok)
        elif word == "undef":
            name = plain.split(None, 1)[1].strip() if len(plain.split(None, 1)) > 1 else ""
            if not re.fullmatch(_NAME, name):
                raise CompileError("#undef needs a macro name", tok.loc)
            self.macros.pop(name, None)
        elif word == "pragma":
            arg = (plain.split(None, 1)[1] if len(plain.split(None, 1)) > 1 else "").strip().upper()
            if arg not in ("IMPLICIT", "NOIMPLICIT"):
                raise CompileError(f"unknown pragma '{rest}' (known: IMPLICIT, NOIMPLICIT)", tok.loc)
            out.append(Token(PRAGMA, "#pragma " + arg, arg, tok.loc))
            out.append(Token(NEWLINE, "\n", None, tok.loc))
        elif not word:
            raise CompileError("'#' must be followed by a preprocessor directive", tok.loc)
        else:
            raise CompileError(f"unknown preprocessor directive '#{word}'", tok.loc)

    # --- #include ---------------------------------------------------------------------------------
    def _include(self, rest: str, tok: Token, name: str, out: list[Token], depth: int) -> None:
        m = re.match(r'"([^"]+)"|<([^>]+)>|([^\s"<>/]\S*)', rest)
        if not m:
            raise CompileError('#include needs a file name: #include "file" or #include <file>', tok.loc)
        quoted, system, bare = m.groups()
        if bare:  # DG 6864: old programs wrote the name without quotes
            self.result.warnings.append(Diagnostic("warning", f'write #include "{bare}"', tok.loc))
        target = (quoted or system or bare).replace("\\", "/")
        here = Path(name).parent if Path(name).parent != Path("") else Path(".")
        search = ([] if system else [here]) + self.include_dirs
        try:
            found = next((d / target for d in search if (d / target).is_file()), None)
        except OSError as exc:  # e.g. a name longer than the file system allows
            shown = target if len(target) <= 60 else target[:57] + "..."
            raise CompileError(f"cannot use include file name '{shown}': {exc.strerror}", tok.loc) from None
        if found is None:
            where = ", ".join(str(d) for d in search) or "no include directory"
            raise CompileError(f"cannot find include file '{target}' (searched: {where})", tok.loc)
        if depth + 1 > MAX_INCLUDE_DEPTH:
            raise CompileError(f"#include nested more than {MAX_INCLUDE_DEPTH} deep (recursive include?)",
                               tok.loc)
        try:
            text = read_source(found)
        except OSError as exc:
            raise CompileError(f"cannot read include file '{found}': {exc.strerror}", tok.loc) from None
        self._process(text, str(found), out, depth + 1)

    # --- #define and expansion --------------------------------------------------------------------
    def _define(self, rest: str, tok: Token) -> None:
        m = re.match(rf"({_NAME})(\(([^)]*)\))?(.*)$", rest, re.S)
        if not m:
            raise CompileError("#define needs a macro name", tok.loc)
        macro_name, has_params, params_text, body_text = m.groups()
        params = None
        if has_params is not None:
            params = tuple(p.strip() for p in params_text.split(",")) if params_text.strip() else ()
            for p in params:
                if not re.fullmatch(_NAME, p):
                    raise CompileError(f"bad parameter '{p}' in macro '{macro_name}'", tok.loc)
            if len(set(params)) != len(params):
                raise CompileError(f"duplicate parameter in macro '{macro_name}'", tok.loc)
        col = tok.loc.col + 1 + tok.value.find(body_text) if body_text else tok.loc.col
        body = tokenize(body_text, tok.loc.file, tok.loc.line, col)[:-2]  # drop NEWLINE, EOF
        if any(t.kind == NEWLINE for t in body):
            raise CompileError(f"macro '{macro_name}' body cannot hold a multi-line comment", tok.loc)
        self.macros[macro_name] = Macro(macro_name, params, body, tok.loc)

    def _expand(self, tokens: list[Token], file: str, nesting: int = 0) -> list[Token]:
        """Expand macros in one line; the result is rescanned (DG 6904), a macro never inside itself. ``nesting``:
        how deep this is inside the arguments of other macro calls (F(F(F(…))) costs the square of the depth)."""
        toks = list(tokens)
        i = 0
        while i < len(toks):
            t = toks[i]
            if t.kind != IDENT:
                i += 1
                continue
            if t.text in ("__LINE__", "__FILE__", "__DATE__", "__TIME__"):
                toks[i] = self._predefined(t, file)
                i += 1
                continue
            macro = self.macros.get(t.text)  # macro names are case-sensitive, like C (decisions.md)
            if macro is None or macro.name in t.hide:
                i += 1
                continue
            end = i + 1
            args: list[list[Token]] = []
            if macro.params is not None:
                if end >= len(toks) or not toks[end].is_op("("):
                    i += 1  # a function-like macro name without '(' is left alone, as in C
                    continue
                if nesting >= MAX_MACRO_DEPTH:
                    raise CompileError(f"macro '{macro.name}' is called inside the arguments of more than "
                                       f"{MAX_MACRO_DEPTH} other macro calls", t.loc, t.origin[:3])
                args, end = self._collect_args(toks, end, macro, t)
                args = [self._expand(a, file, nesting + 1) for a in args]
            if len(t.origin) >= MAX_MACRO_DEPTH:
                raise CompileError(f"macro '{macro.name}' is expanded inside more than {MAX_MACRO_DEPTH} other "
                                   "macros (recursive definitions?)", t.loc, t.origin[:3])
            origin = t.origin + ((f"in expansion of macro '{macro.name}' (defined at {macro.loc})", t.loc),)
            hide = t.hide | {macro.name}
            made = []
            for b in macro.body:
                if macro.params and b.kind == IDENT and b.text in macro.params:
                    for a in args[macro.params.index(b.text)]:
                        made.append(replace(a, hide=a.hide | t.hide))
                else:
                    made.append(replace(b, loc=t.loc, hide=hide, origin=origin))
            for k, m in enumerate(made):
                if macro.name not in m.hide:
                    made[k] = replace(m, hide=m.hide | {macro.name})
            self._expanded += len(made)
            if len(toks) - (end - i) + len(made) > MAX_LINE_TOKENS or self._expanded > MAX_EXPANDED_TOKENS:
                limit = (f"more than {MAX_LINE_TOKENS} tokens on one line" if self._expanded <= MAX_EXPANDED_TOKENS
                         else f"more than {MAX_EXPANDED_TOKENS} tokens in the program")
                raise CompileError(f"macro '{_outermost(t, macro)}' expands to {limit} (doubling or recursive "
                                   "macros?)", t.loc, t.origin[:3])
            toks[i:end] = made
        return toks

    def _collect_args(self, toks: list[Token], start: int, macro: Macro, use: Token) -> tuple[list[list[Token]], int]:
        assert macro.params is not None  # _expand collects arguments only for a function-like macro
        depth, j = 0, start + 1
        args: list[list[Token]] = []
        current: list[Token] = []
        while j < len(toks):
            t = toks[j]
            if t.is_op("(", "["):
                depth += 1
            elif t.is_op(")", "]") and depth > 0:
                depth -= 1
            elif t.is_op(")"):
                args.append(current)
                break
            elif t.is_op(",") and depth == 0:
                args.append(current)
                current = []
                j += 1
                continue
            current.append(t)
            j += 1
        else:
            raise CompileError(f"missing ')' in the use of macro '{macro.name}'", use.loc)
        if args == [[]] and not macro.params:
            args = []
        if len(args) != len(macro.params):
            raise CompileError(f"macro '{macro.name}' takes {len(macro.params)} argument(s), "
                               f"{len(args)} given", use.loc)
        return args, j + 1

    def _predefined(self, t: Token, file: str) -> Token:
        if t.text == "__LINE__":
            return replace(t, kind=INT, text=str(t.loc.line), value=t.loc.line)
        value = {"__FILE__": Path(file).name, "__DATE__": time.strftime("%b %d %Y", self._stamp),
                 "__TIME__": time.strftime("%H:%M:%S", self._stamp)}[t.text]
        return replace(t, kind=STRING, text=f'"{value}"', value=value)

    # --- #if ----------------------------------------------------------------------------------------
    def _condition(self, word: str, rest: str, tok: Token, file: str) -> bool:
        expr_text = rest.split("//")[0]
        if word in ("ifdef", "ifndef"):
            ident = expr_text.strip()
            if not re.fullmatch(_NAME, ident):
                raise CompileError(f"#{word} needs one macro name", tok.loc)
            return (ident in self.macros) == (word == "ifdef")
        col = tok.loc.col + 1 + tok.value.find(rest) if rest else tok.loc.col
        toks = tokenize(expr_text, tok.loc.file, tok.loc.line, col)[:-2]
        if not toks:
            raise CompileError(f"#{word} needs an expression", tok.loc)
        toks = self._replace_defined(toks)
        toks = self._expand(toks, file)
        # Names left after expansion count as 0, as in C.
        toks = [replace(t, kind=INT, text="0", value=0)
                if t.kind == IDENT and t.value not in ("AND", "OR", "NOT", "MOD", "RND", "EXP") else t for t in toks]

        try:
            return evaluate_tokens(toks, tok.loc) != 0
        except RecursionError:
            raise CompileError(f"#{word} condition nested too deeply", tok.loc) from None

    def _replace_defined(self, toks: list[Token]) -> list[Token]:
        out, i = [], 0
        while i < len(toks):
            t = toks[i]
            if t.kind == IDENT and t.text == "defined":
                if i + 1 < len(toks) and toks[i + 1].is_op("("):
                    if i + 3 >= len(toks) or toks[i + 2].kind != IDENT or not toks[i + 3].is_op(")"):
                        raise CompileError("defined() needs one macro name", t.loc)
                    name, i = toks[i + 2].text, i + 4
                elif i + 1 < len(toks) and toks[i + 1].kind == IDENT:
                    name, i = toks[i + 1].text, i + 2
                else:
                    raise CompileError("defined needs a macro name", t.loc)
                value = int(name in self.macros)
                out.append(replace(t, kind=INT, text=str(value), value=value))
                continue
            out.append(t)
            i += 1
        return out


def _outermost(t: Token, macro: Macro) -> str:
    """The name of the macro written in the source that ``t`` came out of (or ``macro`` itself)."""
    if t.origin:
        m = re.match(r"in expansion of macro '([^']*)'", t.origin[0][0])
        if m:
            return m.group(1)
    return macro.name


def preprocess_file(path: Path, include_dirs: list[Path] | None = None) -> PreprocessResult:
    return Preprocessor(include_dirs).run_file(path)


def preprocess_text(text: str, name: str = "<input>",
                    include_dirs: list[Path] | None = None) -> PreprocessResult:
    return Preprocessor(include_dirs).run_text(text, name)


__all__ = ["PRAGMA", "Macro", "PreprocessResult", "Preprocessor", "SourceFile", "preprocess_file",
           "preprocess_text", "read_source", "OP", "STRING"]
