"""Find, Replace and Mark All in a CodeEditor (ide-spec 1.17, 1.32-1.35), on top of the Qt-free ``search``.

A part of the CodeEditor, ``editor.search``: it reaches the editor only through ``self.editor``. The last
search is remembered so F3 / Shift-F3 repeat it.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from pathlib import Path
from typing import TYPE_CHECKING

from PySide6.QtGui import QTextCursor

from motiontool.ui.editor import search
from motiontool.ui.editor.find_dialog import FindInFilesDialog, FindReplaceDialog
from motiontool.ui.editor.search import Hit, SearchOptions
from motiontool.ui.editor.textops import Utf16Map

if TYPE_CHECKING:
    from motiontool.ui.editor.code_editor import CodeEditor

_Keep = QTextCursor.MoveMode.KeepAnchor


class Searching:
    """Find, Replace, Mark All and the Find dialogs of one CodeEditor."""

    def __init__(self, editor: CodeEditor) -> None:
        self.editor = editor
        self.search_text = ""
        self.search_options = SearchOptions()
        self.last_hit: Hit | None = None  # the last find result (``wrapped`` tells the search passed an end)
        self.find_dialog: FindReplaceDialog | None = None
        self.files_dialog: FindInFilesDialog | None = None

    def _select_range(self, umap: Utf16Map, start: int, end: int) -> None:
        cursor = self.editor.textCursor()
        cursor.setPosition(umap.to_qt(start))
        cursor.setPosition(umap.to_qt(end), _Keep)
        self.editor.setTextCursor(cursor)
        self.editor.ensureCursorVisible()

    def find(self, *, text: str | None = None, options: SearchOptions | None = None) -> bool:
        """Select the next hit of `text` (default: the last search) from the caret; PatternError if invalid.

        Forward searches start at the end of the selection, backward ones before its start.
        """
        if text is not None:
            self.search_text = text
        if options is not None:
            self.search_options = options
        if not self.search_text:
            return False
        rx = search.compile_search(self.search_text, self.search_options)
        doc_text = self.editor.toPlainText()
        umap = Utf16Map(doc_text)
        cursor = self.editor.textCursor()
        qt_pos = cursor.selectionStart() if self.search_options.backward else cursor.selectionEnd()
        hit = search.find(doc_text, rx, umap.from_qt(qt_pos), self.search_options)
        self.last_hit = hit
        if hit is None:
            return False
        self._select_range(umap, hit.start, hit.end)
        return True

    def _find_directed(self, backward: bool) -> bool:
        if not self.search_text:
            self.show_find_dialog()
            return False
        opts = self.search_options
        return self.find(options=SearchOptions(opts.mode, opts.match_case, opts.whole_word, backward, opts.wrap))

    def find_next(self) -> bool:
        """F3: the next hit of the last search [DG L2148]."""
        return self._find_directed(False)

    def find_previous(self) -> bool:
        """Shift-F3: the previous hit of the last search [DG L2149]."""
        return self._find_directed(True)

    def word_under_caret(self) -> str:
        cursor = self.editor.textCursor()
        if cursor.hasSelection():
            return cursor.selectedText()
        cursor.select(QTextCursor.SelectionType.WordUnderCursor)
        return cursor.selectedText()

    def find_word(self, *, backward: bool = False) -> bool:
        """Ctrl-F3 / Ctrl-Shift-F3: next/previous occurrence of the word under the caret [DG L2150-2151]."""
        word = self.word_under_caret().strip()
        if not word:
            return False
        if not self.editor.textCursor().hasSelection():  # start from the word itself, so it is skipped
            cursor = self.editor.textCursor()
            cursor.select(QTextCursor.SelectionType.WordUnderCursor)
            self.editor.setTextCursor(cursor)
        return self.find(text=word, options=SearchOptions("plain", False, True, backward, True))

    def _match_at_selection(self, rx: re.Pattern[str], doc_text: str, umap: Utf16Map) -> re.Match[str] | None:
        cursor = self.editor.textCursor()
        if not cursor.hasSelection():
            return None
        start, end = umap.from_qt(cursor.selectionStart()), umap.from_qt(cursor.selectionEnd())
        m = rx.match(doc_text, start)
        return m if m is not None and m.end() == end else None

    def replace(self, text: str, replacement: str, *, options: SearchOptions | None = None) -> bool:
        """Replace: if the selection is a hit, replace it; then select the next hit. True if one was replaced."""
        self.search_text, self.search_options = text, options or self.search_options
        rx = search.compile_search(text, self.search_options)
        doc_text = self.editor.toPlainText()
        umap = Utf16Map(doc_text)
        m = self._match_at_selection(rx, doc_text, umap)
        replaced = False
        if m is not None:
            self.editor.textCursor().insertText(search.expand_replacement(m, replacement, self.search_options.mode))
            replaced = True
        self.find()
        return replaced

    def replace_all(self, text: str, replacement: str, *, options: SearchOptions | None = None,
                    in_selection: bool = False) -> int:
        """Replace every hit (in the whole text, or in the selection) as ONE undo step; the count."""
        opts = options or self.search_options
        self.search_text, self.search_options = text, opts
        doc_text = self.editor.toPlainText()
        umap = Utf16Map(doc_text)
        lo, hi = 0, len(doc_text)
        cursor = self.editor.textCursor()
        if in_selection and cursor.hasSelection():
            lo, hi = umap.from_qt(cursor.selectionStart()), umap.from_qt(cursor.selectionEnd())
        edits = [e for e in search.replacements(doc_text, text, replacement, opts) if lo <= e[0] and e[1] <= hi]
        if not edits:
            return 0
        edit = QTextCursor(self.editor.document())
        edit.beginEditBlock()
        for start, end, new in reversed(edits):  # from the end, so earlier positions stay valid
            edit.setPosition(umap.to_qt(start))
            edit.setPosition(umap.to_qt(end), _Keep)
            edit.insertText(new)
        edit.endEditBlock()
        return len(edits)

    def mark_all(self, text: str, *, options: SearchOptions | None = None) -> int:
        """Mark All: a bookmark on every line with a hit; F2 then walks through them [DG L2306]."""
        opts = options or self.search_options
        self.search_text, self.search_options = text, opts
        doc_text = self.editor.toPlainText()
        hits = search.find_all(doc_text, text, opts)
        starts = [0] + [m.end() for m in re.finditer("\n", doc_text)]
        lines = sorted({bisect_right(starts, h.start) for h in hits})
        marks = self.editor.bookmarks
        marks.set_bookmarks(sorted(set(marks.lines()) | set(lines)))
        return len(lines)

    def show_find_dialog(self, *, replace: bool = False) -> FindReplaceDialog:
        """Ctrl-F / Alt-F3 (Find), Ctrl-R (Replace): the non-modal FindReplaceDialog, with the selection."""
        if self.find_dialog is None:
            self.find_dialog = FindReplaceDialog(self.editor)
        self.find_dialog.open_for(replace=replace)
        return self.find_dialog

    def show_replace_dialog(self) -> FindReplaceDialog:
        return self.show_find_dialog(replace=True)

    def show_find_in_files(self) -> FindInFilesDialog:
        """Edit → Find in Files: search the saved files beside the program (ide-spec 1.36)."""
        if self.files_dialog is None:
            root = self.editor.file_path.parent if self.editor.file_path else Path.cwd()
            self.files_dialog = FindInFilesDialog(root, self.editor, prompts=self.editor.prompts)
            self.files_dialog.locationActivated.connect(self._open_location)
        self.files_dialog.open_for(text=self.word_under_caret())
        return self.files_dialog

    def _open_location(self, path: str, line: int, col: int) -> None:
        if self.editor.file_path is not None and Path(path).resolve() == self.editor.file_path.resolve():
            self.editor.goto_line(line, col=col)
            self.editor.setFocus()
        else:
            self.editor.openLocationRequested.emit(path, line, col)
