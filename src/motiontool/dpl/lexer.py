"""DPL lexer: source text → tokens with exact file:line:col.

One statement per line, so NEWLINE is a token. Integer variables carry their ``%`` in the name (``Speed%``,
``_P01%``); drive parameters are one PARAM token ``#18.11`` holding (menu, parameter). The text of a
``Notes { … }`` task is free prose: it becomes one NOTES token and is never tokenised.
"""

from __future__ import annotations

import math
import re

from motiontool.language.diagnostics import CompileError, Location
from motiontool.language.tokens import EOF, FLOAT, IDENT, INT, NEWLINE, OP, STRING, Token, lookalike_hint

PARAM, NOTES = "PARAM", "NOTES"

INT32_MAX = (1 << 31) - 1

# Blanks before a token are part of its match; the token starts at its group.
_TOKEN = re.compile(r"""
 [ \t\f\r]*(?:
 (?P<nl>\n)
|(?P<lc>//[^\n]*)
|(?P<bc>/\*)
|(?P<param>\#\d{1,3}\.\d{1,3}(?!\d))
|(?P<hash>\#)
|(?P<float>\d+\.\d+(?:[eE][+-]?\d+)?|\d+[eE][+-]?\d+)
|(?P<hex>0[xX][0-9A-Fa-f]+)
|(?P<int>\d+)
|(?P<ident>[A-Za-z_][A-Za-z0-9_]*%?)
|(?P<str>"[^"\n]*")
|(?P<op><>|<=|>=|[-+*/&|<>=()\[\]{},:.])
|(?P<end>\Z))
""", re.VERBOSE | re.ASCII)  # ASCII: \d would take other scripts' digits ("٥٠" as 50; decisions R5)
_NOTES_OPEN = re.compile(r"[ \t\f\r]*(?:\n[ \t\f\r]*)*\{")
_BAD_NUMBER_TAIL = re.compile(r"[A-Za-z_%]")
_WORD_TAIL = re.compile(r"[A-Za-z0-9_%]*")


def tokenize(text: str, file: str) -> list[Token]:
    """Split `text` into tokens. Ends with NEWLINE and EOF. Raises CompileError at the offending place."""
    tokens: list[Token] = []
    pos, n, line, line_start = 0, len(text), 1, 0
    append = tokens.append

    def loc_at(p: int) -> Location:
        return Location(file, line, p - line_start + 1)

    while pos < n:
        m = _TOKEN.match(text, pos)
        if m is None:
            while text[pos] in " \t\f\r":
                pos += 1
            raise CompileError(_bad_character(text[pos]), loc_at(pos))
        kind, group = m.lastgroup, m.lastindex
        assert kind is not None and group is not None  # every alternative of _TOKEN is a named group
        start, end = m.start(group), m.end()
        word = text[start:end]
        if kind == "nl":
            append(Token(NEWLINE, "\n", None, loc_at(start)))
            line += 1
            line_start = end
        elif kind == "lc" or kind == "end":
            pass
        elif kind == "bc":
            close = text.find("*/", end)
            if close < 0:
                raise CompileError("unterminated comment: '/*' without '*/'", loc_at(start))
            newlines = text.count("\n", start, close)
            if newlines:  # a comment over several lines ends the statement on its first line
                append(Token(NEWLINE, "\n", None, loc_at(start)))
                line += newlines
                line_start = text.rfind("\n", start, close) + 1
            end = close + 2
        elif kind == "ident":
            if word.upper() == "NOTES" and _at_line_start(tokens) and (brace := _NOTES_OPEN.match(text, end)):
                end, line, line_start = _notes(text, tokens, start, brace.end(), file, line, line_start)
            else:
                if end < n and text[end] == "%" and word.endswith("%"):
                    raise CompileError(f"'{word}%': a name ends with one '%'", loc_at(end))
                append(Token(IDENT, word, word.upper(), loc_at(start)))
        elif kind == "param":
            menu, _, number = word[1:].partition(".")
            append(Token(PARAM, word, (int(menu), int(number)), loc_at(start)))
        elif kind == "hash":
            raise CompileError("a drive parameter is written #MM.PP without blanks, e.g. #18.11", loc_at(start))
        elif kind == "str":
            append(Token(STRING, word, word[1:-1], loc_at(start)))
        elif kind == "op":
            append(Token(OP, word, word, loc_at(start)))
        else:  # numbers
            if end < n and _BAD_NUMBER_TAIL.match(text, end):
                tail = _WORD_TAIL.match(text[end:])
                assert tail is not None  # the pattern matches the empty string too
                raise CompileError(f"invalid number '{word}{tail.group()}' (names start with a letter or '_')",
                                   loc_at(start))
            append(_number(kind, word, loc_at(start), bool(tokens) and tokens[-1].is_op("-")))
        pos = end
    append(Token(NEWLINE, "\n", None, loc_at(pos)))
    append(Token(EOF, "", None, loc_at(pos)))
    return tokens


def _at_line_start(tokens: list[Token]) -> bool:
    return not tokens or tokens[-1].kind == NEWLINE or tokens[-1].is_op("}")


def _notes(text: str, tokens: list[Token], start: int, body: int, file: str, line: int, line_start: int):
    """The Notes task: prose up to the first '}' (the manual closes it with ``} //Notes``)."""
    loc = Location(file, line, start - line_start + 1)
    close = text.find("}", body)
    if close < 0:
        raise CompileError("Notes task without its closing '}'", loc)
    tokens.append(Token(NOTES, text[start:close + 1], text[body:close], loc))
    newlines = text.count("\n", start, close)
    if newlines:
        line += newlines
        line_start = text.rfind("\n", start, close) + 1
    tokens.append(Token(OP, "}", "}", Location(file, line, close - line_start + 1)))
    return close + 1, line, line_start


def _bad_character(ch: str) -> str:
    if ch == '"':
        return "missing closing '\"' of the string"
    if ch == "%":
        return "unexpected '%': it belongs directly after an integer variable's name (Count%)"
    return f"unexpected character '{ch}'{lookalike_hint(ch)}"


def _number(kind: str, word: str, loc: Location, negated: bool) -> Token:
    if kind == "float":
        value = float(word)
        if not math.isfinite(value):
            raise CompileError(f"constant '{word[:40]}' is outside the floating-point range", loc)
        return Token(FLOAT, word, value, loc)
    if kind != "hex" and len(word.lstrip("0")) > 12:  # int() of 4 300 digits and more raises ValueError (L22)
        raise CompileError(f"constant '{word[:20]}…' ({len(word)} digits) is outside the integer range", loc)
    value = int(word, 16) if kind == "hex" else int(word)
    if kind == "hex":
        if value > 0xFFFFFFFF:
            raise CompileError(f"constant '{word}' does not fit in 32 bits", loc)
        if value > INT32_MAX:  # 0xFFFFFFFF is -1 in the module's 32-bit integers
            value -= 1 << 32
    elif value > INT32_MAX + 1 or (value == INT32_MAX + 1 and not negated):
        raise CompileError(f"constant '{word}' is outside the integer range -2147483648 … 2147483647", loc)
    return Token(INT, word, value, loc)
