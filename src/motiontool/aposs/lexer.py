"""APOSS lexer: source text → tokens with exact file:line:col.

Statements end at line ends, so NEWLINE is a token. A line whose first character (after blanks) is ``#`` is
a preprocessor directive and becomes one DIRECTIVE token holding the rest of the (spliced) line.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from motiontool.language import tokens
from motiontool.language.diagnostics import CompileError, Diagnostic, Location
from motiontool.language.tokens import EOF, FLOAT, IDENT, INT, NEWLINE, OP, STRING, lookalike_hint

DIRECTIVE, TERMINAL = "DIRECTIVE", "TERMINAL"
PRAGMA = "PRAGMA"  # made by the preprocessor from #pragma for the parser: value = "IMPLICIT" | "NOIMPLICIT"


@dataclass(slots=True, repr=False)  # the shared repr, without the macro fields
class Token(tokens.Token):
    # Macro names this token came out of (no re-expansion inside its own expansion) and
    # the chain of macro uses that produced it, shown as notes in diagnostics.
    hide: frozenset[str] = frozenset()
    origin: tuple[tuple[str, Location], ...] = ()


# Blanks before a token are part of its match (half as many matches); the token starts at its group.
_TOKEN = re.compile(r"""
 [ \t\f\r]*(?:
 (?P<ws>(?:\\\r?\n[ \t\f\r]*)+)
|(?P<nl>\n)
|(?P<lc>//[^\n]*)
|(?P<bc>/\*)
|(?P<float>\d+\.\d+(?:[eE][+-]?\d+)?|\d+[eE][+-]?\d+)
|(?P<terminal>[Xx]\d+/\d+)
|(?P<hex>0[xX][0-9A-Fa-f]+)
|(?P<int>\d+)
|(?P<ident>[A-Za-z_][A-Za-z0-9_]*)
|(?P<str>"[^"\n]*")
|(?P<chr>'[^'\n]')
|(?P<op><<|>>|==|!=|<=|>=|\+\+|--|[-+*%^&|~<>=()\[\]{},;:.!])
|(?P<end>\Z))
""", re.VERBOSE | re.ASCII)  # ASCII: \d must not take other scripts' digits ("٥" is not 5 in APOSS)
_DIRECTIVE = re.compile(r"[ \t\f\r]*#((?:[^\n\\]|\\\r?\n|\\(?!\r?\n))*)")
_BAD_NUMBER_TAIL = re.compile(r"[A-Za-z0-9_]")


# The FC 300 parameter number right after these is read in decimal also with a leading 0: CR 4047 writes par. 0-25
# as `025` (as CR 1405 writes 4-13 as `413`), where DG 6413's octal rule would make it 0-21 (decision L1).
_FC_PARAMETER_COMMANDS = frozenset({"GETVLT", "GETVLTSUB", "SETVLT", "SETVLTSUB"})


def tokenize(text: str, file: str, line: int = 1, col: int = 1,
             warnings: list[Diagnostic] | None = None) -> list[Token]:
    """Split `text` into tokens; the first character is at (line, col). Ends with NEWLINE and EOF.

    Raises CompileError at the offending place for characters or literals that are not APOSS.
    Warnings (octal constants) are appended to `warnings` when given.
    """
    tokens: list[Token] = []
    pos, n = 0, len(text)
    line_start = -(col - 1)  # offset of the current line's first character
    at_line_start = True
    match = _TOKEN.match
    append = tokens.append

    def loc_at(p: int) -> Location:
        return Location(file, line, p - line_start + 1)

    while pos < n:
        if at_line_start:
            d = _DIRECTIVE.match(text, pos)
            if d:
                body = d.group(1)
                hash_pos = text.index("#", pos)
                append(Token(DIRECTIVE, body, body, loc_at(hash_pos)))
                for piece in re.finditer(r"\\\r?\n", body):  # spliced lines still count
                    line += 1
                    line_start = d.start(1) + piece.end()
                pos = d.end()
                at_line_start = False
                continue
        m = match(text, pos)
        if m is None:
            while text[pos] in " \t\f\r":  # the blanks before the offending character
                pos += 1
            ch = text[pos]
            if ch == '"':
                raise CompileError("missing closing '\"' of the string", loc_at(pos))
            if ch == "'":
                raise CompileError("character constant must be one character in apostrophes, e.g. 'A'",
                                   loc_at(pos))
            detail = lookalike_hint(ch)
            if ch == "/":
                detail = " (APOSS divides with '%')"
            raise CompileError(f"unexpected character '{ch}'{detail}", loc_at(pos))
        kind = m.lastgroup
        assert kind is not None and m.lastindex is not None  # each alternative of _TOKEN is a named group
        start, end = m.start(m.lastindex), m.end()
        if kind == "ident":
            word = text[start:end]
            append(Token(IDENT, word, word.upper(), Location(file, line, start - line_start + 1)))
            at_line_start = False
        elif kind == "op":
            word = text[start:end]
            append(Token(OP, word, word, Location(file, line, start - line_start + 1)))
            at_line_start = False
        elif kind == "end":
            pass
        elif kind == "ws":
            blanks = m.group("ws")  # line continuations (backslash-newline) with the blanks after them
            line += blanks.count("\n")
            line_start = blanks.rfind("\n") + start + 1
        elif kind == "nl":
            append(Token(NEWLINE, "\n", None, Location(file, line, start - line_start + 1)))
            line += 1
            line_start = end
            at_line_start = True
        elif kind == "lc":
            pass
        elif kind == "bc":
            close = text.find("*/", end)
            if close < 0:
                raise CompileError("unterminated comment: '/*' without '*/'", loc_at(start))
            inner = text.find("/*", end, close)
            if inner >= 0:
                inner_line = line + text.count("\n", start, inner)
                inner_col = inner - (text.rfind("\n", 0, inner) + 1) + 1 if inner_line != line else \
                    inner - line_start + 1
                raise CompileError("nested comments are not allowed ('/*' inside a comment)",
                                   Location(file, inner_line, inner_col))
            newlines = text.count("\n", start, close)
            if newlines:  # a comment over several lines ends the statement on its first line
                append(Token(NEWLINE, "\n", None, loc_at(start)))
                line += newlines
                line_start = text.rfind("\n", start, close) + 1
                at_line_start = False
            end = close + 2
        elif kind == "terminal":  # OUT X59/3 1: a connector pin (CR 3152-3155)
            append(Token(TERMINAL, text[start:end], text[start:end].upper(), loc_at(start)))
            at_line_start = False
        elif kind == "str":
            append(Token(STRING, text[start:end], text[start:end][1:-1], loc_at(start)))
            at_line_start = False
        elif kind == "chr":
            append(Token(INT, text[start:end], ord(text[start:end][1]), loc_at(start)))
            at_line_start = False
        else:  # numbers
            word = text[start:end]
            if end < n and _BAD_NUMBER_TAIL.match(text, end):
                tail_match = re.match(r"[A-Za-z0-9_]*", text[end:])
                assert tail_match is not None  # '*' matches even no character
                tail = tail_match.group()
                raise CompileError(f"invalid number '{word}{tail}'", loc_at(start))
            negated = bool(tokens) and tokens[-1].is_op("-")
            if kind == "int" and word[0] == "0" and tokens and tokens[-1].kind == IDENT \
                    and tokens[-1].value in _FC_PARAMETER_COMMANDS and word.isdigit():
                kind = "fc_parameter"   # 025 = FC 300 par. 0-25, the LCP number without its dash (L1)
            append(_number(kind, word, loc_at(start), warnings, negated))
            at_line_start = False
        pos = end
    append(Token(NEWLINE, "\n", None, loc_at(pos)))
    append(Token(EOF, "", None, loc_at(pos)))
    return tokens


def _number(kind: str, word: str, loc: Location, warnings: list[Diagnostic] | None,
            negated: bool = False) -> Token:
    if kind == "float":
        value = float(word)
        if value == float("inf"):
            raise CompileError(f"DOUBLE constant '{word}' is too large", loc)
        return Token(FLOAT, word, value, loc)
    if kind == "hex":
        value = int(word, 16)
    elif kind == "fc_parameter":
        value = int(word)
    elif len(word) > 1 and word[0] == "0":
        # DG 6413: a leading 0 makes an octal constant (0100 = 64).
        bad = next((c for c in word if c in "89"), None)
        if bad:
            raise CompileError(f"invalid digit '{bad}' in octal constant '{word}' (a leading 0 means octal)",
                               loc)
        value = int(word, 8)
        if warnings is not None:
            warnings.append(Diagnostic("warning", f"'{word}' is an octal constant (= {value}) because it "
                                       "starts with 0", loc))
    else:
        if len(word) > 10:  # certainly beyond the range; int() of a huge literal would also be slow or refused
            raise CompileError(f"constant '{word[:20]}...' is outside the LONG range -2147483648 … 2147483647", loc)
        value = int(word)
        # DG 6397: LONG is -2147483648 … 2147483647; 2147483648 only after a minus sign
        if value > (1 << 31) or (value == (1 << 31) and not negated):
            raise CompileError(f"constant '{word}' is outside the LONG range -2147483648 … 2147483647", loc)
    if value > 0xFFFFFFFF:
        raise CompileError(f"constant '{word}' does not fit in 32 bits", loc)
    if value > 0x7FFFFFFF:  # 0xFFFFFFFF is -1, as on the controller's 32-bit registers
        value -= 1 << 32
    return Token(INT, word, value, loc)
