"""What the editor knows about DPL words (Qt-free): built-in functions, keywords, task names, the APC definitions,
hover help and completion. It reads the DPL front end's tables (``motiontool.dpl``), so the editor never
disagrees with `motiontool check` about what a name is. The same interface as ``lang`` (the APOSS words)."""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from html import escape

from motiontool.dpl.check import register_parameter
from motiontool.dpl.definitions import definitions
from motiontool.dpl.functions import function_table
from motiontool.dpl.parser import KEYWORDS, TASKS
from motiontool.ui.editor.lang import CompletionItem
from motiontool.ui.editor.outline import OutlineItem

WORD_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*%?")
PARAM_RE = re.compile(r"#\d{1,3}\.\d{1,3}")
_LABEL_RE = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*):", re.MULTILINE)
_VARIABLE_RE = re.compile(r"\b[A-Za-z_][A-Za-z0-9_]*%")
_TASK_RE = re.compile(r"^\s*([A-Za-z][A-Za-z0-9]*)\s*\{", re.MULTILINE)


@dataclass(frozen=True)
class Vocabulary:
    keywords: frozenset[str]      # IF THEN … and the task names, upper case
    functions: frozenset[str]     # built-in function names, upper case
    definitions: frozenset[str]   # APC_FB_POS …, upper case


@lru_cache(maxsize=1)
def vocabulary() -> Vocabulary:
    return Vocabulary(frozenset(KEYWORDS) | frozenset(TASKS), frozenset(function_table()),
                      frozenset(definitions()))


def word_at(line: str, index: int) -> tuple[int, int] | None:
    """(start, end) of the name (with its %) or #mm.pp parameter covering position `index`, or None."""
    for regex in (PARAM_RE, WORD_RE):
        for m in regex.finditer(line):
            if m.start() <= index < m.end():
                return m.start(), m.end()
    return None


def hover_text(line: str, index: int) -> str | None:
    """Rich-text tooltip for the built-in function, definition, PLC register or task at `index`; else None."""
    span = word_at(line, index)
    if span is None:
        return None
    word = line[span[0]:span[1]]
    key = word.upper()
    fn = function_table().get(key)
    if fn is not None:
        where = " <i>(POS0/POS1 only)</i>" if fn.tasks == "pos" else ""
        return (f"<qt><b>{escape(fn.syntax)}</b>{where}<br/>{escape(fn.help)}"
                f"<br/><i>APC user guide {escape(fn.src)}</i></qt>")
    d = definitions().get(key)
    if d is not None:
        meaning = f"read parameter [{d.value}]" if d.group == "read parameter" else f"{d.group}: {d.value}"
        note = f"<br/>{escape(d.note)}" if d.note else ""
        return f"<qt><b>{escape(d.name)}</b> = {d.value} <i>({escape(meaning)}, L{d.line})</i>{note}</qt>"
    register = register_parameter(key)
    if register is not None:
        return f"<qt><b>{escape(word)}</b>: PLC register, drive parameter #{register[0]}.{register[1]:02d}</qt>"
    if key in TASKS:
        return f"<qt><b>{escape(TASKS[key])}</b> task</qt>"
    return None


@lru_cache(maxsize=1)
def _static_items() -> tuple[CompletionItem, ...]:
    items = [CompletionItem(f.name, f.syntax, "function", f.help) for f in function_table().values()]
    for d in definitions().values():
        hint = f"[{d.value}]" if d.group == "read parameter" else f"= {d.value}  ({d.group})"
        items.append(CompletionItem(d.name, hint, "definition", d.note))
    items += [CompletionItem(w, "keyword", "keyword") for w in sorted(KEYWORDS)]
    items += [CompletionItem(name, "task", "keyword") for name in TASKS.values()]
    return tuple(items)


def completion_items(text: str = "") -> list[CompletionItem]:
    """Functions, definitions, keywords and task names, plus the program's variables and labels (from `text`)."""
    items = list(_static_items())
    known = {i.name.upper() for i in items}
    symbols = {m.group(): "variable" for m in _VARIABLE_RE.finditer(text)}
    symbols.update({m.group(1): "label" for m in _LABEL_RE.finditer(text) if m.group(1).upper() not in known})
    seen: set[str] = set()
    for name, kind in symbols.items():
        if name.upper() not in known and name.upper() not in seen:
            seen.add(name.upper())
            items.append(CompletionItem(name, kind, kind))
    return sorted(items, key=lambda i: (i.name.casefold(), i.name))


def outline(text: str) -> list[OutlineItem]:
    """The tasks and labels of a DPL program, in line order (labels inside the Notes prose do not count)."""
    items: list[OutlineItem] = []
    notes = False
    for number, line in enumerate(text.split("\n"), 1):
        code = line.split("//")[0]
        if notes:
            notes = "}" not in code
            continue
        task = _TASK_RE.match(code)
        if task and task.group(1).upper() in TASKS:
            items.append(OutlineItem("task", TASKS[task.group(1).upper()], number))
            notes = task.group(1).upper() == "NOTES" and "}" not in code[task.end():]
        elif (label := _LABEL_RE.match(code)) and label.group(1).upper() not in KEYWORDS:
            items.append(OutlineItem("label", label.group(1), number))
    return items
