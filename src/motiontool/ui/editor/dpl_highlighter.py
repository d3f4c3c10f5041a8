"""Syntax colouring of DPL programs (the APC's language), with the APOSS highlighter's colours and settings.

Element kinds as in ``highlighter.KINDS``: comment (``//``, ``/* */`` and the prose of the ``Notes { … }``
task), keyword (IF … ENDIF, GOTO, DIM, the task names and the built-in functions such as ``APCSetRunMode``),
parameter (drive parameters ``#18.11``, the APC definitions such as ``APC_FB_POS`` and the PLC registers
``_P01%``), number, operator and string. Words are matched case-insensitively (DPL ignores case).

Block states: ``0`` normal, ``1`` inside a ``/* */`` comment, ``3`` inside the Notes prose.
"""

from __future__ import annotations

import re

from motiontool.dpl.check import register_parameter
from motiontool.ui.editor.dpl_lang import vocabulary
from motiontool.ui.editor.highlighter import IN_COMMENT, NORMAL, AposHighlighter

IN_NOTES = 3
_TOKEN = re.compile(r"""
 (?P<lc>//)
|(?P<bc>/\*)
|(?P<notes>\bNotes\s*\{)
|(?P<param>\#\d{1,3}\.\d{1,3})
|(?P<str>"[^"]*"?)
|(?P<num>(?:0[xX][0-9A-Fa-f]+|\d+\.\d+|\d+)(?![A-Za-z0-9_]))
|(?P<word>[A-Za-z_][A-Za-z0-9_]*%?)
|(?P<op><>|<=|>=|[-+*/&|<>=])
""", re.VERBOSE | re.IGNORECASE)


class DplHighlighter(AposHighlighter):
    """Colours a DPL program; colours and formats come from the APOSS highlighter."""

    def __init__(self, document=None, colors=None) -> None:
        super().__init__(document, colors)
        self._dpl = vocabulary()

    def highlightBlock(self, text: str) -> None:  # noqa: N802 (Qt override)
        self.setCurrentBlockState(NORMAL)
        fmt = self._formats
        pos = 0
        previous = self.previousBlockState()
        if previous == IN_NOTES:
            pos = self._notes(text, 0)
        elif previous == IN_COMMENT:
            pos = self._comment(text, 0)
        vocab = self._dpl
        n = len(text)
        while 0 <= pos < n:
            m = _TOKEN.search(text, pos)
            if m is None:
                break
            kind, s, e = m.lastgroup, m.start(), m.end()
            if kind == "word":
                word = m.group().upper()
                if word in vocab.keywords or word in vocab.functions:
                    self.setFormat(s, e - s, fmt["keyword"])
                elif word in vocab.definitions or register_parameter(word) is not None:
                    self.setFormat(s, e - s, fmt["parameter"])
            elif kind == "param":
                self.setFormat(s, e - s, fmt["parameter"])
            elif kind == "num":
                self.setFormat(s, e - s, fmt["number"])
            elif kind == "op":
                self.setFormat(s, e - s, fmt["operator"])
            elif kind == "str":
                self.setFormat(s, e - s, fmt["string"])
            elif kind == "lc":
                self.setFormat(s, n - s, fmt["comment"])
                return
            elif kind == "bc":
                e = self._comment(text, s)
            elif kind == "notes":
                brace = e - 1
                self.setFormat(s, brace - s, fmt["keyword"])
                e = self._notes(text, e)
            pos = e

    def _notes(self, text: str, start: int) -> int:
        """Notes prose from `start` in comment colour; the index after its '}' or -1 if it goes on."""
        close = text.find("}", start)
        end = len(text) if close < 0 else close
        self.setFormat(start, end - start, self._formats["comment"])
        if close < 0:
            self.setCurrentBlockState(IN_NOTES)
            return -1
        return close + 1
