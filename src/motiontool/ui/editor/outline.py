"""Program outline and symbols of an APOSS program, by regular expressions over lines (Qt-free, fast).

:func:`outline` lists labels, subprograms (``SUBPROG name``) and function definitions (``LONG name(...)``
without the ``;`` of a prototype) for an outline view; :func:`program_symbols` adds variables, arrays and
``#define`` macros for completion. Neither needs a program that compiles: they run on every edit.
"""

from __future__ import annotations

import re
from functools import lru_cache
from typing import NamedTuple

from motiontool.aposs.commands import command_table

_IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
_LABEL_RE = re.compile(rf"\s*({_IDENT})\s*:\s*$")
_SUBPROG_RE = re.compile(rf"\s*SUBPROG\s+({_IDENT})", re.IGNORECASE)
_FUNC_RE = re.compile(rf"\s*(?:LONG|DOUBLE)\s+({_IDENT})\s*\(", re.IGNORECASE)
_DECL_RE = re.compile(r"\s*(?:LONG|DOUBLE|DIM)\s+(.*)", re.IGNORECASE)
_DECL_ITEM_RE = re.compile(rf"\s*({_IDENT})\s*(\[)?")
_ASSIGN_RE = re.compile(rf"\s*({_IDENT})\s*(\[[^\]]*\]\s*)*=(?!=)")
_DEFINE_RE = re.compile(rf"\s*#\s*define\s+({_IDENT})")
_SPECIAL = re.compile(r"""//|/\*|"|'""")


class OutlineItem(NamedTuple):
    kind: str   # "label" | "subprog" | "function"
    name: str   # as written
    line: int   # 1-based


@lru_cache(maxsize=1)
def _reserved() -> frozenset[str]:
    names = {word for cmd in command_table() for word in cmd.words}
    return frozenset(names | {"CASE", "DEFAULT"})


def strip_code(text: str) -> list[str]:
    """The lines of `text` with comments, strings and character constants blanked (columns are kept)."""
    lines = text.split("\n")
    out: list[str] = []
    in_comment = False
    for line in lines:
        if not in_comment and not _SPECIAL.search(line):
            out.append(line)
            continue
        chars = list(line)
        i, n = 0, len(line)
        while i < n:
            if in_comment:
                close = line.find("*/", i)
                stop = n if close < 0 else close + 2
                chars[i:stop] = " " * (stop - i)
                in_comment = close < 0
                i = stop
                continue
            m = _SPECIAL.search(line, i)
            if m is None:
                break
            i = m.start()
            token = m.group()
            if token == "//":
                chars[i:] = " " * (n - i)
                break
            if token == "/*":
                in_comment = True
                continue
            close = line.find(token, i + 1)  # string or character constant (one line)
            stop = n if close < 0 else close + 1
            chars[i:stop] = " " * (stop - i)
            i = stop
        out.append("".join(chars))
    return out


def _items(lines: list[str]) -> list[OutlineItem]:
    reserved = _reserved()
    items: list[OutlineItem] = []
    for number, line in enumerate(lines, 1):
        if not line or line.isspace():
            continue
        if m := _LABEL_RE.match(line):
            if m.group(1).upper() not in reserved:
                items.append(OutlineItem("label", m.group(1), number))
        elif m := _SUBPROG_RE.match(line):
            items.append(OutlineItem("subprog", m.group(1), number))
        elif (m := _FUNC_RE.match(line)) and not line.rstrip().endswith(";"):
            items.append(OutlineItem("function", m.group(1), number))
    return items


def outline(text: str) -> list[OutlineItem]:
    """Labels, subprograms and function definitions of `text`, in line order."""
    return _items(strip_code(text))


def _split_top_level(text: str) -> list[str]:
    """Split at commas outside brackets and parentheses."""
    parts, depth, start = [], 0, 0
    for i, ch in enumerate(text):
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return parts


def program_symbols(text: str) -> dict[str, str]:
    """The program's own names → kind ("label", "subprog", "function", "variable", "array", "macro").

    Variables are the declared ones (``LONG a, b``, ``DOUBLE c``, ``DIM arr[10]``) and the implicitly
    declared ones (``name = ...`` at the start of a statement). The first spelling of a name wins; command
    names are never symbols.
    """
    reserved = _reserved()
    lines = strip_code(text)
    symbols: dict[str, str] = {}
    seen: set[str] = set()

    def add(name: str, kind: str) -> None:
        if name.upper() not in reserved and name.upper() not in seen:
            seen.add(name.upper())
            symbols[name] = kind

    for item in _items(lines):
        add(item.name, item.kind)
    for line in lines:
        if "=" not in line and "#" not in line and not _DECL_RE.match(line):
            continue
        if m := _DEFINE_RE.match(line):
            add(m.group(1), "macro")
        elif (m := _DECL_RE.match(line)) and not _FUNC_RE.match(line):
            for part in _split_top_level(m.group(1)):
                if d := _DECL_ITEM_RE.match(part):
                    add(d.group(1), "array" if d.group(2) else "variable")
        elif m := _ASSIGN_RE.match(line):
            add(m.group(1), "array" if m.group(2) else "variable")
    return symbols
