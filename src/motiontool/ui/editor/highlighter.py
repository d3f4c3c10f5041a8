"""Syntax colouring of APOSS programs (ide-spec 1.6): a fast per-line regular-expression highlighter.

Element kinds: comment (``//`` and multi-line ``/* */``), keyword (every name of the command table; the
words of multi-word names such as ``MOTOR ON`` are matched together), parameter (code names of the
parameter database such as ``KPROP``), number (decimal, hex ``0x1F``, double ``1.5e3``), operator, string
(``"..."`` and character constants ``'A'``) and preprocessor lines (``#define``, ``#include``, continued with a
trailing backslash). Words are matched case-insensitively.

Block states: ``-1``/``0`` normal, ``1`` inside a ``/* */`` comment, ``2`` continuation of a directive line.
"""

from __future__ import annotations

import re

from PySide6.QtGui import QColor, QFont, QSyntaxHighlighter, QTextCharFormat, QTextDocument

from motiontool.ui.editor.lang import vocabulary
from motiontool.ui.editor.settings import EditorColors

__all__ = ["AposHighlighter", "EditorColors", "KINDS"]

NORMAL, IN_COMMENT, IN_DIRECTIVE = 0, 1, 2
KINDS = ("comment", "keyword", "number", "operator", "string", "parameter", "preprocessor")

_TOKEN = re.compile(r"""
 (?P<lc>//)
|(?P<bc>/\*)
|(?P<str>"[^"]*"?)
|(?P<chr>'[^'\\]?')
|(?P<term>[Xx]\d+/\d+)
|(?P<num>(?:0[xX][0-9A-Fa-f]+|(?:\d+\.\d*|\.\d+)(?:[eE][+-]?\d+)?|\d+[eE][+-]?\d+|\d+)(?![A-Za-z0-9_]))
|(?P<word>[A-Za-z_][A-Za-z0-9_]*)
|(?P<op><<|>>|==|!=|<=|>=|\+\+|--|[-+*/%^&|~<>=!])
""", re.VERBOSE)
_DIRECTIVE = re.compile(r"[ \t]*#")


class AposHighlighter(QSyntaxHighlighter):
    """Colours an APOSS program in `document` with `colors` (``set_colors`` changes them later)."""

    def __init__(self, document: QTextDocument | None = None, colors: EditorColors | None = None) -> None:
        super().__init__(document)
        self._vocab = vocabulary()
        self._formats: dict[str, QTextCharFormat] = {}
        self._colors = colors or EditorColors()
        self._build_formats()

    # --- colours ---------------------------------------------------------------------------------------
    @property
    def colors(self) -> EditorColors:
        return self._colors

    def set_colors(self, colors: EditorColors) -> None:
        self._colors = colors
        self._build_formats()
        self.rehighlight()

    def format_for(self, kind: str) -> QTextCharFormat:
        """The character format used for element `kind` (one of KINDS)."""
        return QTextCharFormat(self._formats[kind])

    def _build_formats(self) -> None:
        c = self._colors
        for kind in KINDS:
            fmt = QTextCharFormat()
            fmt.setForeground(QColor(getattr(c, kind)))
            self._formats[kind] = fmt
        self._formats["keyword"].setFontWeight(QFont.Weight.Bold)
        self._formats["comment"].setFontItalic(True)

    # --- highlighting ----------------------------------------------------------------------------------
    def highlightBlock(self, text: str) -> None:  # noqa: N802 (Qt override)
        self.setCurrentBlockState(NORMAL)
        fmt = self._formats
        start = 0
        previous = self.previousBlockState()
        if previous == IN_COMMENT:
            start = self._comment(text, 0)
            if start < 0:
                return
        elif previous == IN_DIRECTIVE or (start == 0 and _DIRECTIVE.match(text)):
            self._directive(text)
            return
        n = len(text)
        vocab = self._vocab
        single, multi_first, params = vocab.single, vocab.multi_first, vocab.params
        pos = start
        while pos < n:
            m = _TOKEN.search(text, pos)
            if m is None:
                break
            kind = m.lastgroup
            s, e = m.start(), m.end()
            if kind == "word":
                word = m.group().upper()
                if word in multi_first and (mm := vocab.multi_re.match(text, s)):
                    e = mm.end()
                    self.setFormat(s, e - s, fmt["keyword"])
                elif word in single:
                    self.setFormat(s, e - s, fmt["keyword"])
                elif word in params:
                    self.setFormat(s, e - s, fmt["parameter"])
            elif kind == "num":
                self.setFormat(s, e - s, fmt["number"])
            elif kind == "op":
                self.setFormat(s, e - s, fmt["operator"])
            elif kind == "str" or kind == "chr":
                self.setFormat(s, e - s, fmt["string"])
            elif kind == "lc":
                self.setFormat(s, n - s, fmt["comment"])
                return
            elif kind == "bc":
                e = self._comment(text, s)
                if e < 0:
                    return
            pos = e

    def _comment(self, text: str, start: int) -> int:
        """Colour a block comment from `start`; return the index after ``*/`` or -1 if it goes on."""
        close = text.find("*/", start + 2 if text.startswith("/*", start) else start)
        end = len(text) if close < 0 else close + 2
        self.setFormat(start, end - start, self._formats["comment"])
        if close < 0:
            self.setCurrentBlockState(IN_COMMENT)
            return -1
        return end

    def _directive(self, text: str) -> None:
        """A preprocessor line: directive colour, a trailing ``//`` comment in comment colour."""
        comment = text.find("//")
        body_end = len(text) if comment < 0 else comment
        self.setFormat(0, body_end, self._formats["preprocessor"])
        if comment >= 0:
            self.setFormat(comment, len(text) - comment, self._formats["comment"])
        elif text.endswith("\\"):
            self.setCurrentBlockState(IN_DIRECTIVE)
