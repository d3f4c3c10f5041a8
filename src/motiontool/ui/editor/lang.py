"""What the editor knows about APOSS words (Qt-free): keywords, parameter names, hover help, completion.

Everything comes from the command table (``motiontool.aposs.commands``) and the parameter database
(``motiontool.paramdb``), so the editor never disagrees with the compiler about what a command is.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from html import escape
from typing import NamedTuple

from motiontool.aposs.commands import Command, command_table
from motiontool.paramdb import database
from motiontool.ui.editor.outline import program_symbols

WORD_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


@dataclass(frozen=True)
class Vocabulary:
    single: frozenset[str]        # one-word command names, upper case
    multi_first: frozenset[str]   # first words of multi-word names ("MOTOR" of "MOTOR ON")
    multi_re: re.Pattern[str]     # one multi-word name at a position (longest first, case-insensitive)
    params: frozenset[str]        # parameter code names (KPROP), upper case


@lru_cache(maxsize=1)
def vocabulary() -> Vocabulary:
    names = command_table().names()
    multi = sorted((n for n in names if " " in n), key=lambda n: (-len(n.split()), -len(n)))
    body = "|".join(r"\s+".join(map(re.escape, n.split())) for n in multi) or r"(?!)"
    params = frozenset(p.name.upper() for p in database() if p.name)
    return Vocabulary(
        single=frozenset(n for n in names if " " not in n),
        multi_first=frozenset(n.split()[0] for n in multi),
        multi_re=re.compile(rf"(?:{body})(?![A-Za-z0-9_])", re.IGNORECASE),
        params=params,
    )


def word_span(line: str, index: int) -> tuple[int, int] | None:
    """(start, end) of the identifier at or just before `index` in `line`, or None."""
    for m in WORD_RE.finditer(line):
        if m.start() <= index <= m.end():
            return m.start(), m.end()
        if m.start() > index:
            break
    return None


def command_at(line: str, index: int) -> Command | None:
    """The command whose name covers position `index` of `line` ("ON" in "MOTOR ON" gives MOTOR ON)."""
    vocab = vocabulary()
    table = command_table()
    for m in WORD_RE.finditer(line):
        if m.start() > index:
            break
        if (m.group().upper() in vocab.multi_first and (mm := vocab.multi_re.match(line, m.start()))
                and mm.start() <= index < mm.end()):
            return table.get(mm.group())
    span = word_span(line, index)
    if span is None or not span[0] <= index < span[1]:
        return None
    return table.get(line[span[0]:span[1]])


def hover_text(line: str, index: int) -> str | None:
    """Rich-text tooltip for the command or parameter at `index` of `line`: syntax and help; None if none."""
    cmd = command_at(line, index)
    if cmd is not None:
        return (f"<qt><b>{escape(cmd.syntax)}</b> <i>({escape(cmd.kind)}, {escape(cmd.group)})</i>"
                f"<br/>{escape(cmd.help)}</qt>")
    span = word_span(line, index)
    if span is None or not span[0] <= index < span[1]:
        return None
    word = line[span[0]:span[1]].upper()
    if word in vocabulary().params:
        param = database().get(word)
        return (f"<qt><b>{escape(param.name or word)}</b> <i>(parameter {escape(param.number)})</i>"
                f"<br/>{escape(param.format_line())}</qt>")
    return None


class CompletionItem(NamedTuple):
    name: str    # the text that is inserted
    hint: str    # shown next to the name: the syntax of a command, the number of a parameter, a symbol kind
    kind: str    # a command kind, "parameter", or a program-symbol kind
    help: str = ""


@lru_cache(maxsize=1)
def _static_items() -> tuple[CompletionItem, ...]:
    items = [CompletionItem(c.name, c.syntax, c.kind, c.help) for c in command_table()]
    known = {c.name for c in items}
    items += [CompletionItem(p.name, f"{p.number}  {p.description}", "parameter", p.format_line())
              for p in database() if p.name and p.name.upper() not in known]
    return tuple(items)


def completion_items(text: str = "") -> list[CompletionItem]:
    """Command names, parameter names and the program's own symbols (from `text`), sorted by name."""
    items = list(_static_items())
    known = {i.name.upper() for i in items}
    items += [CompletionItem(name, kind, kind) for name, kind in program_symbols(text).items()
              if name.upper() not in known]
    return sorted(items, key=lambda i: (i.name.casefold(), i.name))
