"""Keyboard editing functions of the CodeEditor that QPlainTextEdit lacks (ide-spec 1.14-1.19, 1.38).

A part of the CodeEditor, ``editor.edit``: it reaches the editor only through ``self.editor``. The pure text
logic lives in ``textops`` so it is testable without widgets.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from PySide6.QtGui import QTextCursor

from motiontool.ui.editor import textops

if TYPE_CHECKING:
    from motiontool.ui.editor.code_editor import CodeEditor

_Move = QTextCursor.MoveOperation
_Keep = QTextCursor.MoveMode.KeepAnchor


class Editing:
    """The keyboard editing functions of one CodeEditor, and the count of Repeat (Ctrl-Alt-R)."""

    def __init__(self, editor: CodeEditor) -> None:
        self.editor = editor
        self.repeat_count = 0  # the next key command runs this many times (0: once)

    # --- navigation ------------------------------------------------------------------------------------
    def goto_line(self, line: int, *, col: int = 1) -> None:
        """Put the caret on 1-based `line`, before 1-based column `col` (clamped), and show it."""
        doc = self.editor.document()
        block = doc.findBlockByNumber(max(0, min(line, doc.blockCount()) - 1))
        cursor = QTextCursor(block)
        cursor.setPosition(block.position() + max(0, min(col - 1, block.length() - 1)))
        self.editor.setTextCursor(cursor)
        self.editor.centerCursor()

    def caret_line_col(self) -> tuple[int, int]:
        """The caret as the status bar shows it: 1-based line and column ("13:1") [DG L2196]."""
        cursor = self.editor.textCursor()
        return cursor.blockNumber() + 1, cursor.positionInBlock() + 1

    def goto_line_dialog(self) -> None:
        """Ctrl-G: ask for a line number and go there [DG L2111]."""
        line = self.editor.prompts.integer("Go to Line", f"Line number (1-{self.editor.blockCount()}):",
                                           self.caret_line_col()[0], 1, self.editor.blockCount())
        if line is not None:
            self.goto_line(line)

    def goto_matching_bracket(self) -> bool:
        """Ctrl-B: jump to the bracket matching the one at (or just before) the caret [DG L2112]."""
        cursor = self.editor.textCursor()
        text = self.editor.toPlainText()
        umap = textops.Utf16Map(text)
        target = textops.matching_bracket(text, umap.from_qt(cursor.position()))
        if target is None:
            return False
        cursor.setPosition(umap.to_qt(target))
        self.editor.setTextCursor(cursor)
        return True

    def _goto_block(self, number: int, at_end: bool, *, select: bool = False) -> None:
        block = self.editor.document().findBlockByNumber(number)
        cursor = self.editor.textCursor()
        pos = block.position() + (block.length() - 1 if at_end else 0)
        cursor.setPosition(pos, _Keep if select else QTextCursor.MoveMode.MoveAnchor)
        self.editor.setTextCursor(cursor)

    def goto_next_blank_line(self) -> None:
        """Ctrl-Alt-Down: start of the next blank line (ide-spec 1.14 DECISION for the lost arrow glyph)."""
        lines = self.editor.toPlainText().split("\n")
        self._goto_block(textops.next_blank_line(lines, self.editor.textCursor().blockNumber()), at_end=False)

    def goto_previous_blank_line(self) -> None:
        """Ctrl-Alt-Up: end of the previous blank line."""
        lines = self.editor.toPlainText().split("\n")
        self._goto_block(textops.previous_blank_line(lines, self.editor.textCursor().blockNumber()), at_end=True)

    def move_word_end(self, *, select: bool = False) -> None:
        """Ctrl-Right: end of the word; at a word's end, the end of the next word [DG L2108]."""
        cursor = self.editor.textCursor()
        mode = _Keep if select else QTextCursor.MoveMode.MoveAnchor
        start = cursor.position()
        cursor.movePosition(_Move.EndOfWord, mode)
        if cursor.position() == start:
            cursor.movePosition(_Move.NextWord, mode)
            cursor.movePosition(_Move.EndOfWord, mode)
        self.editor.setTextCursor(cursor)

    def scroll_lines(self, lines: int) -> None:
        """Ctrl-Up/Down: scroll the view without moving the caret [DG L2166-2170]."""
        bar = self.editor.verticalScrollBar()
        bar.setValue(bar.value() + lines)

    def scroll_columns(self, steps: int) -> None:
        """Ctrl-PgUp/PgDn: scroll left/right by a quarter of the view."""
        bar = self.editor.horizontalScrollBar()
        bar.setValue(bar.value() + steps * max(bar.pageStep() // 4, 1))

    # --- selection and clipboard -----------------------------------------------------------------------
    def _select_blocks(self, first: int, last: int) -> QTextCursor:
        """A cursor over whole lines first..last (0-based) including the line break after `last`."""
        doc = self.editor.document()
        cursor = QTextCursor(doc.findBlockByNumber(first))
        end = doc.findBlockByNumber(last)
        if end.next().isValid():
            cursor.setPosition(end.next().position(), _Keep)
        else:
            cursor.setPosition(end.position() + end.length() - 1, _Keep)
            if first > 0:  # the last line: take the break before it instead
                cursor.setPosition(cursor.position())
                cursor.setPosition(doc.findBlockByNumber(first).position() - 1, _Keep)
        return cursor

    def select_line(self) -> None:
        """Ctrl-Alt-F8: select the line under the caret [DG L2135]."""
        block = self.editor.textCursor().block()
        cursor = QTextCursor(block)
        cursor.movePosition(_Move.EndOfBlock, _Keep)
        self.editor.setTextCursor(cursor)

    def cut_line(self) -> None:
        """Ctrl-Y: cut the current line to the clipboard [DG L2141]."""
        number = self.editor.textCursor().blockNumber()
        self.editor.setTextCursor(self._select_blocks(number, number))
        self.editor.cut()

    def cut_paragraph(self) -> None:
        """Ctrl-Alt-K: cut from the previous blank line to the next blank line [DG L2144]."""
        lines = self.editor.toPlainText().split("\n")
        first, last = textops.paragraph_range(lines, self.editor.textCursor().blockNumber())
        self.editor.setTextCursor(self._select_blocks(first, last))
        self.editor.cut()

    # --- modify ----------------------------------------------------------------------------------------
    def _change_case(self, upper: bool) -> None:
        cursor = self.editor.textCursor()
        if not cursor.hasSelection():
            return
        start, end = cursor.selectionStart(), cursor.selectionEnd()
        text = cursor.selectedText()
        cursor.insertText(text.upper() if upper else text.lower())
        cursor.setPosition(start)
        cursor.setPosition(end, _Keep)
        self.editor.setTextCursor(cursor)

    def lowercase_selection(self) -> None:
        """Ctrl-U [DG L2160]."""
        self._change_case(False)

    def uppercase_selection(self) -> None:
        """Ctrl-Shift-U [DG L2161]."""
        self._change_case(True)

    def delete_word_end(self) -> None:
        """Ctrl-Delete: delete to the end of the word; between words, the blanks up to the next word
        [DG L2159]."""
        cursor = self.editor.textCursor()
        if not cursor.hasSelection():
            start = cursor.position()
            cursor.movePosition(_Move.EndOfWord, _Keep)
            if cursor.position() == start:
                cursor.movePosition(_Move.NextWord, _Keep)
        cursor.removeSelectedText()
        self.editor.setTextCursor(cursor)

    def insert_line_above(self) -> None:
        """Ctrl-Shift-N: a new line above the current one, with its indentation [DG L2162]."""
        cursor = self.editor.textCursor()
        text = cursor.block().text()
        indent = text[: len(text) - len(text.lstrip(" \t"))]
        cursor.movePosition(_Move.StartOfBlock)
        cursor.insertText(indent + "\n")
        cursor.movePosition(_Move.PreviousBlock)
        cursor.movePosition(_Move.EndOfBlock)
        self.editor.setTextCursor(cursor)

    def toggle_overwrite(self) -> None:
        """Insert: switch between insert and overwrite typing [DG L2154]."""
        self.editor.setOverwriteMode(not self.editor.overwriteMode())

    def indent_string(self) -> str:
        return " " * self.editor.settings.tab_size if self.editor.settings.convert_tabs_while_typing else "\t"

    def insert_tab(self) -> None:
        """Tab without a selection: a tab, or spaces to the next tab stop when converting [DG L3148]."""
        cursor = self.editor.textCursor()
        if self.editor.settings.convert_tabs_while_typing:
            block_text = cursor.block().text()
            column = textops.display_column(block_text, cursor.positionInBlock(), self.editor.settings.tab_size)
            cursor.insertText(" " * textops.spaces_to_next_stop(column, self.editor.settings.tab_size))
        else:
            cursor.insertText("\t")
        self.editor.setTextCursor(cursor)

    def selected_block_range(self) -> tuple[int, int]:
        cursor = self.editor.textCursor()
        doc = self.editor.document()
        first = doc.findBlock(cursor.selectionStart())
        last = doc.findBlock(cursor.selectionEnd())
        if last.blockNumber() > first.blockNumber() and cursor.selectionEnd() == last.position():
            last = last.previous()  # a selection ending at a line start does not include that line
        return first.blockNumber(), last.blockNumber()

    def _reselect_blocks(self, first: int, last: int) -> None:
        doc = self.editor.document()
        cursor = QTextCursor(doc.findBlockByNumber(first))
        end = doc.findBlockByNumber(last)
        cursor.setPosition(end.position() + end.length() - 1, _Keep)
        self.editor.setTextCursor(cursor)

    def indent_selection(self) -> None:
        """Tab with a selection: indent the selected lines by one level [DG L2156]."""
        first, last = self.selected_block_range()
        indent = self.indent_string()
        cursor = self.editor.textCursor()
        cursor.beginEditBlock()
        for number in range(first, last + 1):
            block = self.editor.document().findBlockByNumber(number)
            if block.text():
                cursor.setPosition(block.position())
                cursor.insertText(indent)
        cursor.endEditBlock()
        self._reselect_blocks(first, last)

    def unindent_selection(self) -> None:
        """Shift-Tab: remove one indentation level from the selected lines (or the caret line) [DG L2157]."""
        first, last = self.selected_block_range()
        had_selection = self.editor.textCursor().hasSelection()
        cursor = self.editor.textCursor()
        cursor.beginEditBlock()
        for number in range(first, last + 1):
            block = self.editor.document().findBlockByNumber(number)
            text = block.text()
            drop = len(text) - len(textops.unindent(text, self.editor.settings.tab_size))
            if drop:
                cursor.setPosition(block.position())
                cursor.setPosition(block.position() + drop, _Keep)
                cursor.removeSelectedText()
        cursor.endEditBlock()
        if had_selection:
            self._reselect_blocks(first, last)

    def convert_tabs(self) -> int:
        """Edit → Convert Tabs: every tab of the buffer to spaces with the tab size [DG L2354-2358].

        One undo step; lines are edited in place, so bookmarks stay. Returns the number of changed lines.
        """
        changed = 0
        cursor = QTextCursor(self.editor.document())
        cursor.beginEditBlock()
        block = self.editor.document().begin()
        while block.isValid():
            text = block.text()
            if "\t" in text:
                cursor.setPosition(block.position())
                cursor.setPosition(block.position() + block.length() - 1, _Keep)
                cursor.insertText(textops.expand_tabs(text, self.editor.settings.tab_size))
                changed += 1
            block = block.next()
        cursor.endEditBlock()
        return changed

    # --- repeat ----------------------------------------------------------------------------------------
    def repeat_next(self, count: int) -> None:
        """Execute the next key command `count` times (Ctrl-Alt-R) [DG L2163]."""
        self.repeat_count = max(0, int(count))

    def repeat_dialog(self) -> None:
        count = self.editor.prompts.integer("Repeat", "Repeat the next command this many times:", 2, 1, 9999)
        if count is not None:
            self.repeat_next(count)
