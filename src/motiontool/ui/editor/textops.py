"""Text operations behind the editor's keyboard functions (Qt-free; ide-spec 1.14-1.18, 1.38).

Positions are indices into a Python string; lines are 0-based lists of strings without line breaks.
"""

from __future__ import annotations

from bisect import bisect_left

_OPEN = {"(": ")", "[": "]", "{": "}"}
_CLOSE = {v: k for k, v in _OPEN.items()}


def expand_tabs(text: str, tab_size: int) -> str:
    """Every tab replaced by spaces up to the next tab stop (columns counted per line) [DG L2354-2358]."""
    return text.expandtabs(tab_size)


def spaces_to_next_stop(column: int, tab_size: int) -> int:
    """How many spaces a tab typed at 0-based `column` stands for."""
    return tab_size - column % tab_size


def display_column(line: str, index: int, tab_size: int) -> int:
    """The 0-based screen column of `line[index]` with tabs expanded."""
    return len(line[:index].expandtabs(tab_size))


def unindent(line: str, tab_size: int) -> str:
    """`line` with one indentation level (a tab, or up to `tab_size` spaces) removed from its start."""
    if line.startswith("\t"):
        return line[1:]
    n = 0
    while n < tab_size and n < len(line) and line[n] == " ":
        n += 1
    if n < tab_size and n < len(line) and line[n] == "\t":
        n += 1  # spaces followed by a tab: the tab ends this level
    return line[n:]


def matching_bracket(text: str, pos: int) -> int | None:
    """Index of the bracket matching the one at `pos` (or, if none is there, at `pos - 1`); None if none.

    Handles ``( ) [ ] { }`` [DG L2112]; brackets inside comments and strings count too (a plain scan).
    """
    for p in (pos, pos - 1):
        if 0 <= p < len(text) and (text[p] in _OPEN or text[p] in _CLOSE):
            break
    else:
        return None
    ch = text[p]
    if ch in _OPEN:
        want, step, same = _OPEN[ch], 1, ch
    else:
        want, step, same = _CLOSE[ch], -1, ch
    depth = 0
    i = p
    while 0 <= i < len(text):
        c = text[i]
        if c == same:
            depth += 1
        elif c == want:
            depth -= 1
            if depth == 0:
                return i
        i += step
    return None


def _blank(line: str) -> bool:
    return not line.strip()


def next_blank_line(lines: list[str], current: int) -> int:
    """Index of the first blank line after `current`; the last line if there is none [DG L2110]."""
    for i in range(current + 1, len(lines)):
        if _blank(lines[i]):
            return i
    return max(len(lines) - 1, 0)


def previous_blank_line(lines: list[str], current: int) -> int:
    """Index of the last blank line before `current`; the first line if there is none [DG L2111]."""
    for i in range(current - 1, -1, -1):
        if _blank(lines[i]):
            return i
    return 0


def paragraph_range(lines: list[str], current: int) -> tuple[int, int]:
    """(first, last) line of the paragraph around `current`: the lines between the blank lines before and
    after it (Ctrl-Alt-K cuts these) [DG L2144]. On a blank line, the run of blank lines."""
    want_blank = _blank(lines[current]) if lines else False
    first = current
    while first > 0 and _blank(lines[first - 1]) == want_blank:
        first -= 1
    last = current
    while last + 1 < len(lines) and _blank(lines[last + 1]) == want_blank:
        last += 1
    return first, last


class Utf16Map:
    """Converts between Python string indices and Qt document positions (UTF-16 code units).

    They differ only after characters outside the Basic Multilingual Plane (emoji), which count twice in Qt.
    """

    def __init__(self, text: str) -> None:
        self._astral = [i for i, ch in enumerate(text) if ord(ch) > 0xFFFF] if not text.isascii() else []

    def to_qt(self, index: int) -> int:
        return index + bisect_left(self._astral, index)

    def from_qt(self, position: int) -> int:
        lo, hi = 0, position
        while lo < hi:  # the smallest index whose Qt position is >= position
            mid = (lo + hi) // 2
            if self.to_qt(mid) < position:
                lo = mid + 1
            else:
                hi = mid
        return lo
