"""The token both lexers make: kind, text as written, value, place. APOSS's adds its macro fields."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from motiontool.language.diagnostics import Location

# The kinds every lexer shares; each language adds its own (APOSS: DIRECTIVE, TERMINAL; DPL: PARAM, NOTES).
IDENT, INT, FLOAT, STRING, OP, NEWLINE, EOF = "IDENT", "INT", "FLOAT", "STRING", "OP", "NEWLINE", "EOF"


@dataclass(slots=True)
class Token:
    kind: str
    text: str           # as written (for IDENT: original case)
    # int / float / str / upper-case identifier / None, as the kind says; Any because every use has checked
    # the kind (IDENT, INT, ...) first, which a type checker cannot follow to the value
    value: Any
    loc: Location

    def is_op(self, *ops: str) -> bool:
        return self.kind == OP and self.text in ops

    def is_word(self, *words: str) -> bool:
        return self.kind == IDENT and self.value in words

    def __repr__(self) -> str:
        return f"Token({self.kind}, {self.text!r}, {self.loc})"


# Typographic characters a word processor puts in for the ASCII ones (text pasted from a manual or a mail).
_LOOKALIKES = {"\u2013": ("EN DASH", "-"), "\u2014": ("EM DASH", "-"),
               "\u201c": ("LEFT DOUBLE QUOTATION MARK", '"'), "\u201d": ("RIGHT DOUBLE QUOTATION MARK", '"'),
               "\u2018": ("LEFT SINGLE QUOTATION MARK", "'"), "\u2019": ("RIGHT SINGLE QUOTATION MARK", "'"),
               "\u00a0": ("NO-BREAK SPACE", " ")}


def lookalike_hint(ch: str) -> str:
    """`` (U+2013 EN DASH); write '-'`` for a typographic stand-in of an ASCII character, else ""."""
    found = _LOOKALIKES.get(ch)
    return f" (U+{ord(ch):04X} {found[0]}); write '{found[1]}'" if found else ""
