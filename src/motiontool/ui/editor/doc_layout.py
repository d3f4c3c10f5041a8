"""The CodeEditor's document layout: QPlainTextDocumentLayout that repaints one line for a one-line edit.

QPlainTextDocumentLayout takes the blocks from ``from`` to ``from + charsRemoved + charsAdded`` as changed.
When a QSyntaxHighlighter re-colours the edited line it widens the reported change to the whole line
(removed and added both about the line length), so that sum reaches into the next line: Qt then drops
the layout of both lines and repaints the whole view for every keystroke (about 1.5 ms of a 4 ms keystroke
on a 5 000-line program, measured with benchmarks/editor_latency.py).

This layout remembers the edit itself (``contentsChange``, emitted just before the layout is told). When
that edit stays inside one line (no line break typed or deleted) and the widened change covers only that
line, it reports just that line, so Qt lays out and repaints only it. Everything else (Return, pasting
several lines, a ``/*`` that re-colours the lines below, a colour change) keeps Qt's own handling.
"""

from __future__ import annotations

from PySide6.QtGui import QTextDocument
from PySide6.QtWidgets import QPlainTextDocumentLayout, QPlainTextEdit


def install_line_layout(editor: QPlainTextEdit) -> LineLayout:
    """Give `editor` an empty document laid out by a LineLayout; the caller keeps the returned layout
    (PySide deletes a layout made in Python together with its Python object)."""
    document = QTextDocument(editor)
    layout = LineLayout(document)
    document.setDocumentLayout(layout)
    editor.setDocument(document)
    return layout


class LineLayout(QPlainTextDocumentLayout):
    def __init__(self, document: QTextDocument) -> None:
        super().__init__(document)
        self._blocks = document.blockCount()
        self._edit: tuple[int, int] | None = None  # (position, characters added) of the last edit
        document.contentsChange.connect(self._edited)

    def _edited(self, position: int, _removed: int, added: int) -> None:
        self._edit = (position, added)

    def documentChanged(self, start: int, removed: int, added: int) -> None:  # noqa: N802 (Qt override)
        edit, self._edit = self._edit, None
        doc = self.document()
        count = doc.blockCount()
        same_count, self._blocks = count == self._blocks, count
        if edit is not None and same_count and removed and added:
            block = doc.findBlock(edit[0])
            first, end = block.position(), block.position() + block.length()
            if edit[0] + edit[1] < end and first <= start and start + added <= end:
                removed = 0  # one line changed: from + removed + added now ends inside it
        super().documentChanged(start, removed, added)
