"""Find / Replace / Find in Files for the program editor (Qt-free; ide-spec 1.32-1.36).

Three search modes:

- ``"plain"``: the text is searched literally (the default of the Find dialog).
- ``"pattern"``: the Find/Replace pattern syntax of the MCO 305 Design Guide, translated to Python ``re`` by
  :func:`translate_pattern`.
- ``"regex"``: a Python regular expression, used as it is (an extension; the manual does not have it).

The manual's pattern syntax (Design Guide ``seeds/000_de8489130b22ed63.txt``) and its translation:

====================  ===========================  ===============================================================
manual (DG line)      Python ``re``                 note
====================  ===========================  ===============================================================
``?`` (L2310)         ``.``                         "any single character"; not a line break (searches stay in a
                                                    line, as in the editor)
``+`` (L2310)         ``+``                         "one or more" of the preceding item; literal ``+`` when there
                                                    is no preceding item (pattern start, after ``(`` or ``|``)
``*`` (L2310)         ``*``                         "zero or more" of the preceding item; literal like ``+``
``[...]`` (L2311)     ``[...]``                     character set with ranges ``[a-c]``; ``\\t`` etc. inside are
                                                    escapes; DECISION: ``[^...]`` negates as in every regex
                                                    dialect; other characters are taken literally
``|`` (L2312)         ``|``                         logical OR of sub-expressions
``( )`` (L2313)       ``( )``                       a group; an unbalanced parenthesis is a PatternError
``\\t`` (L2314)        tab                           also ``\\n`` (line break), ``\\r``; ``\\\\`` is a backslash
``\\x`` (DECISION)     ``x`` literally               any other escaped character stands for itself, so ``\\?``,
                                                    ``\\+``, ``\\[`` search for ``?``, ``+``, ``[``
anything else         ``re.escape(char)``           ``.``, ``^``, ``$``, ``{`` ``}`` are ordinary characters
====================  ===========================  ===============================================================

The examples of L2318-2324 are test vectors (``tests/ui/editor/test_search.py``). The OCR of L2323 lost the
pipe: ``(vel) (acc)`` is read as ``(vel)|(acc)`` (ide-spec 1.34).

Replacement text (ide-spec 1.35): plain mode inserts it literally; pattern mode substitutes the escapes
``\\t \\n \\r \\\\`` (DECISION: the manual names no back-references, so ``\\1`` is a literal ``1``); regex mode
uses Python's ``match.expand`` (``\\1``, ``\\g<name>``).

Zero-length matches (``x*`` can match the empty string) are skipped: find and replace act only on non-empty
matches.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

MODES = ("plain", "pattern", "regex")
_WORD_CHAR = "A-Za-z0-9_"
_ESCAPES = {"t": "\t", "n": "\n", "r": "\r", "\\": "\\"}


class PatternError(ValueError):
    """The search text is not a valid pattern; ``pos`` is the 0-based offset of the problem (or None)."""

    def __init__(self, message: str, pos: int | None = None) -> None:
        super().__init__(message)
        self.pos = pos


@dataclass(frozen=True)
class SearchOptions:
    mode: str = "plain"          # "plain" | "pattern" | "regex"
    match_case: bool = False
    whole_word: bool = False
    backward: bool = False       # search up
    wrap: bool = True            # continue at the other end of the text

    def __post_init__(self) -> None:
        if self.mode not in MODES:
            raise ValueError(f"mode must be one of {', '.join(MODES)}, got {self.mode!r}")


class Hit(NamedTuple):
    start: int
    end: int
    wrapped: bool = False


class FileHit(NamedTuple):
    path: Path
    line: int    # 1-based
    col: int     # 1-based
    text: str    # the whole line, without its line break


def escape_pattern(text: str) -> str:
    """Manual-syntax pattern that matches `text` literally (the inverse of translate_pattern for plain text)."""
    out = []
    for ch in text:
        if ch in "?+*[]|()\\":
            out.append("\\" + ch)
        elif ch == "\t":
            out.append("\\t")
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\r":
            out.append("\\r")
        else:
            out.append(ch)
    return "".join(out)


def _escape_char(pattern: str, i: int) -> tuple[str, int]:
    """The literal character of the escape at pattern[i] == '\\' and the index after it."""
    if i + 1 >= len(pattern):
        return "\\", i + 1  # a lone trailing backslash is itself
    nxt = pattern[i + 1]
    return _ESCAPES.get(nxt, nxt), i + 2


def _translate_set(pattern: str, i: int) -> tuple[str, int]:
    """Translate the set starting at pattern[i] == '['; return the re text and the index after ']'."""
    start, i = i, i + 1
    out = ["["]
    if i < len(pattern) and pattern[i] == "^":
        out.append("^")
        i += 1
    first = True
    while i < len(pattern):
        ch = pattern[i]
        if ch == "]" and not first:  # a ']' right after '[' or '[^' is literal
            out.append("]")
            return "".join(out), i + 1
        if ch == "\\":
            lit, i = _escape_char(pattern, i)
        else:
            lit, i = ch, i + 1
        # '-' between two characters is a range; everything else is literal inside the set
        out.append("-" if lit == "-" and ch == "-" and not first and i < len(pattern) and pattern[i] != "]"
                   else re.escape(lit))
        first = False
    raise PatternError("missing ']' of the character set", start)


def translate_pattern(pattern: str) -> str:
    """Translate a pattern in the manual's Find/Replace syntax (module docstring) into Python ``re`` text."""
    out: list[str] = []
    depth = 0
    can_repeat = False  # is there an item before a '+' or '*'?
    i = 0
    while i < len(pattern):
        ch = pattern[i]
        if ch == "\\":
            lit, i = _escape_char(pattern, i)
            out.append(re.escape(lit))
            can_repeat = True
            continue
        if ch == "[":
            text, i = _translate_set(pattern, i)
            out.append(text)
            can_repeat = True
            continue
        if ch in "+*":
            if can_repeat and out and out[-1] not in ("+", "*"):
                out.append(ch)
            else:
                out.append(re.escape(ch))
                can_repeat = True
        elif ch == "?":
            out.append(".")
            can_repeat = True
        elif ch == "(":
            out.append("(")
            depth += 1
            can_repeat = False
        elif ch == ")":
            if depth == 0:
                raise PatternError("')' without '('", i)
            out.append(")")
            depth -= 1
            can_repeat = True
        elif ch == "|":
            out.append("|")
            can_repeat = False
        else:
            out.append(re.escape(ch))
            can_repeat = True
        i += 1
    if depth:
        raise PatternError("missing ')'", len(pattern))
    return "".join(out)


def compile_search(text: str, options: SearchOptions = SearchOptions()) -> re.Pattern[str]:
    """The compiled regular expression for search text `text` under `options`; PatternError if invalid."""
    if not text:
        raise PatternError("empty search text", 0)
    if options.mode == "plain":
        body = re.escape(text)
    elif options.mode == "pattern":
        body = translate_pattern(text)
    else:
        body = text
    if options.whole_word:
        body = rf"(?<![{_WORD_CHAR}])(?:{body})(?![{_WORD_CHAR}])"
    try:
        return re.compile(body, 0 if options.match_case else re.IGNORECASE)
    except re.error as exc:
        raise PatternError(f"invalid regular expression: {exc.msg}", exc.pos) from None


def _matches(rx: re.Pattern[str], text: str, pos: int = 0) -> Iterator[re.Match[str]]:
    """Non-empty matches from `pos`; after an empty match the search goes on one character later."""
    while pos <= len(text):
        m = rx.search(text, pos)
        if m is None:
            return
        if m.end() > m.start():
            yield m
            pos = m.end()
        else:
            pos = m.start() + 1


def _forward(rx: re.Pattern[str], text: str, pos: int) -> re.Match[str] | None:
    return next(_matches(rx, text, pos), None)


def _backward(rx: re.Pattern[str], text: str, pos: int) -> re.Match[str] | None:
    """The last non-empty match that starts before `pos` (overlapping candidates included)."""
    best = None
    start = 0
    while start < pos:
        m = rx.search(text, start)
        if m is None or m.start() >= pos:
            break
        if m.end() > m.start():
            best = m
        start = m.start() + 1
    return best


def find(text: str, search: str | re.Pattern[str], pos: int = 0,
         options: SearchOptions = SearchOptions()) -> Hit | None:
    """The next hit at or after `pos` (or, with options.backward, the last one starting before `pos`).

    With options.wrap the search continues at the other end of the text; ``Hit.wrapped`` tells it did.
    """
    rx = compile_search(search, options) if isinstance(search, str) else search
    pos = max(0, min(pos, len(text)))
    step = _backward if options.backward else _forward
    m = step(rx, text, pos)
    wrapped = False
    if m is None and options.wrap:
        m = step(rx, text, len(text) if options.backward else 0)
        wrapped = True
    return None if m is None else Hit(m.start(), m.end(), wrapped)


def find_all(text: str, search: str | re.Pattern[str], options: SearchOptions = SearchOptions()) -> list[Hit]:
    """Every non-empty, non-overlapping hit from the start of `text`."""
    rx = compile_search(search, options) if isinstance(search, str) else search
    return [Hit(m.start(), m.end()) for m in _matches(rx, text)]


def expand_replacement(match: re.Match[str], replacement: str, mode: str) -> str:
    """The text that replaces `match` (module docstring: per-mode rules)."""
    if mode == "regex":
        try:
            return match.expand(replacement)
        except (re.error, IndexError) as exc:
            raise PatternError(f"invalid replacement: {exc}") from None
    if mode == "pattern":
        out, i = [], 0
        while i < len(replacement):
            if replacement[i] == "\\":
                lit, i = _escape_char(replacement, i)
                out.append(lit)
            else:
                out.append(replacement[i])
                i += 1
        return "".join(out)
    return replacement


def replacements(text: str, search: str | re.Pattern[str], replacement: str,
                 options: SearchOptions = SearchOptions()) -> list[tuple[int, int, str]]:
    """(start, end, new text) for every hit in `text`, in text order; apply them from the last one."""
    rx = compile_search(search, options) if isinstance(search, str) else search
    return [(m.start(), m.end(), expand_replacement(m, replacement, options.mode)) for m in _matches(rx, text)]


def replace_all(text: str, search: str | re.Pattern[str], replacement: str,
                options: SearchOptions = SearchOptions()) -> tuple[str, int]:
    """`text` with every hit replaced, and the number of replacements."""
    parts, last = [], 0
    edits = replacements(text, search, replacement, options)
    for start, end, new in edits:
        parts += [text[last:start], new]
        last = end
    parts.append(text[last:])
    return "".join(parts), len(edits)


def _read_text(path: Path) -> str | None:
    try:
        data = path.read_bytes()
    except OSError:
        return None
    if b"\0" in data[:4096]:
        return None  # binary file
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("cp1252", errors="replace")  # programs from the Windows IDE


def find_in_files(root: str | Path, pattern: str, glob: str = "*.m",
                  options: SearchOptions = SearchOptions()) -> list[FileHit]:
    """Search the files on disk under `root` (recursively; or `root` itself if it is a file) line by line.

    Unsaved editor buffers are not searched (ide-spec 1.36). Hits are sorted by path, line and column;
    unreadable and binary files are skipped.
    """
    rx = compile_search(pattern, options)
    root = Path(root)
    files = [root] if root.is_file() else sorted(p for p in root.rglob(glob) if p.is_file())
    hits: list[FileHit] = []
    for path in files:
        text = _read_text(path)
        if text is None:
            continue
        for number, line in enumerate(text.splitlines(), 1):
            hits.extend(FileHit(path, number, m.start() + 1, line) for m in _matches(rx, line))
    return hits
