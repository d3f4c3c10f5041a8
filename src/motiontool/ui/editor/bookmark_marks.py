"""Bookmarks in the program editor (ide-spec 1.37): kept in the text blocks' data, so they move with their lines;
saved outside the program file by bookmarks.BookmarkStore.  A part of the CodeEditor, ``editor.bookmarks``."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING

from PySide6.QtGui import QTextBlock

from motiontool.ui.editor.bookmarks import BookmarkStore, next_bookmark
from motiontool.ui.editor.debug_marks import BlockData

if TYPE_CHECKING:
    from motiontool.ui.editor.code_editor import CodeEditor


class Bookmarks:
    """The bookmarks of one CodeEditor; it reaches the editor only through ``self.editor``."""

    def __init__(self, editor: CodeEditor) -> None:
        self.editor = editor

    @staticmethod
    def has_bookmark(block: QTextBlock) -> bool:
        data = block.userData()
        return isinstance(data, BlockData) and data.bookmark

    def set_bookmark(self, block: QTextBlock, on: bool) -> None:
        data = block.userData()
        if not isinstance(data, BlockData):
            if not on:
                return
            data = BlockData()
            block.setUserData(data)
        data.bookmark = on

    def lines(self) -> list[int]:
        """The bookmarked lines, 1-based, ascending."""
        lines, block = [], self.editor.document().begin()
        while block.isValid():
            if self.has_bookmark(block):
                lines.append(block.blockNumber() + 1)
            block = block.next()
        return lines

    def set_bookmarks(self, lines: Iterable[int]) -> None:
        """Replace all bookmarks by `lines` (1-based; lines past the end are ignored)."""
        wanted = set(lines)
        block = self.editor.document().begin()
        while block.isValid():
            self.set_bookmark(block, block.blockNumber() + 1 in wanted)
            block = block.next()
        self.changed()

    def changed(self) -> None:
        self.editor.gutter.update()
        self.editor.bookmarksChanged.emit()

    def toggle_bookmark(self, *, line: int | None = None) -> bool:
        """Ctrl-F2: toggle the bookmark on `line` (default: the caret line); True if it is now set."""
        block = (self.editor.textCursor().block() if line is None
                 else self.editor.document().findBlockByNumber(line - 1))
        on = not self.has_bookmark(block)
        self.set_bookmark(block, on)
        self.changed()
        return on

    def clear_bookmarks(self) -> None:
        """Edit → Clear All Bookmarks."""
        self.set_bookmarks(())

    def _goto_bookmark(self, backward: bool) -> int | None:
        target = next_bookmark(self.lines(), self.editor.caret_line_col()[0], backward)
        if target is not None:
            self.editor.goto_line(target)
        return target

    def next_bookmark(self) -> int | None:
        """F2: the caret to the next bookmarked line, wrapping; returns that line (or None)."""
        return self._goto_bookmark(False)

    def previous_bookmark(self) -> int | None:
        """Shift-F2: the caret to the previous bookmarked line, wrapping."""
        return self._goto_bookmark(True)

    def load_bookmarks(self, store: BookmarkStore, *, path: str | Path | None = None) -> None:
        """Restore the bookmarks of `path` (default: file_path) from `store`."""
        path = path or self.editor.file_path
        if path is not None:
            self.editor.file_path = Path(path)
            self.set_bookmarks(store.load(path))

    def save_bookmarks(self, store: BookmarkStore, *, path: str | Path | None = None) -> None:
        path = path or self.editor.file_path
        if path is not None:
            store.save(path, self.lines())
