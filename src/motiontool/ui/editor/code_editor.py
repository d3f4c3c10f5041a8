"""The APOSS program editor widget (ide-spec 1.5-1.8, 1.11-1.24, 1.31-1.38, 1.44).

QPlainTextEdit plus: AposHighlighter colours, a left margin with line numbers, bookmark triangles and
error/warning marks, current-line highlight, bookmarks kept on the text blocks (they move with edits),
diagnostics as wavy underlines with tooltips, completion (Ctrl-Space and after 3 typed letters; Enter takes a
row only once one is chosen with the arrow keys, else it ends the line: I17), hover help for commands and
parameters, the manual's context menu and keyboard functions, and key macros.

The editor handles its own keys (it accepts ShortcutOverride for them), so the keys work the same whether
or not the main window binds its Edit-menu entries; the window may connect the entries to the same methods.
Parts it owns (issue 27 item 7), each reaching it through one typed reference: ``edit``, ``search``, ``recorder``
(macros), ``debug`` (debug_marks), ``bookmarks`` (bookmark_marks). Signals and Qt event handlers stay here.
"""

from __future__ import annotations

import operator
import re
from collections.abc import Iterable
from pathlib import Path
from typing import NamedTuple

from PySide6.QtCore import QEvent, QModelIndex, QObject, QPoint, QRect, Qt, QTimer, Signal
from PySide6.QtGui import (
    QColor,
    QContextMenuEvent,
    QFont,
    QFontDatabase,
    QHelpEvent,
    QKeyEvent,
    QKeySequence,
    QMouseEvent,
    QPalette,
    QResizeEvent,
    QTextBlock,
    QTextCharFormat,
    QTextCursor,
    QTextFormat,
)
from PySide6.QtWidgets import QCompleter, QMenu, QPlainTextEdit, QTextEdit, QToolTip, QWidget

from motiontool.qtjobs.prompts import QtPrompts
from motiontool.ui.editor import dpl_lang, lang, outline
from motiontool.ui.editor.bookmark_marks import Bookmarks
from motiontool.ui.editor.completion import CompletionModel, HintDelegate
from motiontool.ui.editor.debug_marks import DebugMarks
from motiontool.ui.editor.doc_layout import install_line_layout
from motiontool.ui.editor.editing import Editing
from motiontool.ui.editor.gutter import LineNumberArea
from motiontool.ui.editor.highlighter import AposHighlighter
from motiontool.ui.editor.keymap import EDITING, KEYMAP
from motiontool.ui.editor.macros import MacroRecorder, MacroSlots, combination
from motiontool.ui.editor.searching import Searching
from motiontool.ui.editor.settings import EditorSettings

AUTO_COMPLETE_LETTERS = 3
_CHOOSING_KEYS = frozenset({Qt.Key.Key_Up, Qt.Key.Key_Down, Qt.Key.Key_PageUp, Qt.Key.Key_PageDown})
_LINEFEED = 0x0A  # the key code of X11's Linefeed keysym (Qt names none)
_MODIFIER_KEYS = frozenset({Qt.Key.Key_Shift, Qt.Key.Key_Control, Qt.Key.Key_Alt, Qt.Key.Key_Meta,
                            Qt.Key.Key_AltGr})
_DIAG_TOKEN_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*|\d[A-Za-z0-9_.]*|\"[^\"]*\"?|\S")



class _Diagnostic(NamedTuple):
    cursor: QTextCursor  # selects the token; Qt keeps it in place while the text is edited
    severity: str        # "error" | "warning"
    message: str


class CodeEditor(QPlainTextEdit):
    cursorLineColChanged = Signal(int, int)  # 1-based line and column for the status bar (ide-spec 1.5)
    bookmarksChanged = Signal()
    macroRecordingChanged = Signal(bool)
    openLocationRequested = Signal(str, int, int)  # a Find in Files hit in another file: path, line, column
    breakpointsChanged = Signal()
    variableEditRequested = Signal(str)  # right-click on a variable while debugging (ide-spec 3.9)

    def __init__(self, parent: QWidget | None = None, settings: EditorSettings | None = None) -> None:
        super().__init__(parent)
        self.settings = settings or EditorSettings()
        self.file_path: Path | None = None
        self._diagnostics: list[_Diagnostic] = []
        self.macros = MacroSlots()  # the saved macros: the application keeps them across restarts
        self.prompts = QtPrompts(self)  # what its commands ask through; a main window gives its own (issue 27.5)
        self.edit = Editing(self)
        self.search = Searching(self)
        self.recorder = MacroRecorder(self)
        self.debug = DebugMarks(self)
        self.bookmarks = Bookmarks(self)
        self._layout = install_line_layout(self)  # a keystroke repaints its line, not the whole view
        self.setLineWrapMode(QPlainTextEdit.LineWrapMode.NoWrap)
        self.setMouseTracking(True)
        self.highlighter = AposHighlighter(self.document(), self.settings.colors)
        self.lang = lang  # the words the editor knows: APOSS (lang) or DPL (dpl_lang), see set_language
        self.gutter = LineNumberArea(self)
        self._keymap = {QKeySequence(k).toString(QKeySequence.SequenceFormat.PortableText): v
                        for k, v in KEYMAP.items()}
        self._completion_model = CompletionModel(self)
        self._completer = QCompleter(self._completion_model, self)
        self._completer.setWidget(self)
        self._completer.setCompletionMode(QCompleter.CompletionMode.PopupCompletion)
        self._completer.setCaseSensitivity(Qt.CaseSensitivity.CaseInsensitive)
        self._completer.setMaxVisibleItems(12)
        self._completer.popup().setItemDelegate(HintDelegate(self._completer.popup()))
        self._completer.activated[str].connect(self.insert_completion)
        self._completion_chosen = False  # a row picked with the arrow keys: only then does Enter take it
        self._completer.popup().installEventFilter(self)  # after the completer's own filter, so it runs first
        self._symbols_revision = -1
        self._popup_width = 360
        self._symbol_timer = QTimer(self, singleShot=True, interval=400, timeout=self._refresh_symbols)
        self.document().contentsChanged.connect(self._symbol_timer.start)
        self._extra_line = -1
        self._gutter_state: tuple = ()
        self.blockCountChanged.connect(self._update_gutter_width)
        self.updateRequest.connect(self._update_gutter)
        self.cursorPositionChanged.connect(self._caret_moved)
        self.apply_settings(self.settings)
        self._caret_moved()

    # --- settings --------------------------------------------------------------------------------------
    def apply_settings(self, settings: EditorSettings) -> None:
        """Use `settings`: font, tab size, colours (Settings → Editor, ide-spec 1.44)."""
        self.settings = settings
        c = settings.colors
        self._quiet_colors = {QColor(x).rgb() for x in (c.comment, c.string, c.preprocessor)}
        if settings.font_family:
            font = QFont(settings.font_family)
        else:
            font = QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont)
        font.setStyleHint(QFont.StyleHint.Monospace)
        font.setFixedPitch(True)
        font.setPointSize(settings.font_size)
        self.setFont(font)
        self.setTabStopDistance(self.fontMetrics().horizontalAdvance(" ") * settings.tab_size)
        palette = self.palette()
        palette.setColor(QPalette.ColorRole.Base, QColor(settings.colors.window))
        palette.setColor(QPalette.ColorRole.Text, QColor(settings.colors.text))
        self.setPalette(palette)
        if self.highlighter.colors != settings.colors:
            self.highlighter.set_colors(settings.colors)
        self._update_gutter_width()
        self.update_extra_selections()
        self.gutter.update()

    # --- margin ----------------------------------------------------------------------------------------
    def _update_gutter_width(self, *_args) -> None:
        self.setViewportMargins(self.gutter.area_width(), 0, 0, 0)

    def _update_gutter(self, rect: QRect, dy: int) -> None:
        """Follow the view. The margin is only repainted where what it shows (first line, scroll offset, line
        count, caret line) changed: not for a repaint of the whole view in the same state, nor for one inside
        the caret line (typing in it, the caret blinking): its number and marks stay as they are."""
        if dy:
            self.gutter.scroll(0, dy)
            return
        cursor = self.textCursor()
        state = (self.firstVisibleBlock().blockNumber(), self.contentOffset().y(), self.blockCount(),
                 cursor.blockNumber())
        if state != self._gutter_state:
            # first line, line count or caret line changed: line numbers change beyond this request (setTextCursor
            # asks for the old and the new caret line before it reports the move)
            self._gutter_state = state
            self.gutter.update()
            return
        if rect.contains(self.viewport().rect()):
            return
        line = self.blockBoundingGeometry(cursor.block()).translated(self.contentOffset()).toAlignedRect()
        if line.adjusted(0, -2, 0, 2).contains(rect):  # Qt adds 1 px
            return
        self.gutter.update(0, rect.y(), self.gutter.width(), rect.height())

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 (Qt override)
        super().resizeEvent(event)
        cr = self.contentsRect()
        self.gutter.setGeometry(QRect(cr.left(), cr.top(), self.gutter.area_width(), cr.height()))

    def goto_line(self, line: int, *, col: int = 1) -> None:
        self.edit.goto_line(line, col=col)  # kept here: the window, the parts and many tests go to lines

    def caret_line_col(self) -> tuple[int, int]:
        return self.edit.caret_line_col()

    def _caret_moved(self) -> None:
        self.update_extra_selections(force=False)
        line, col = self.caret_line_col()
        self.cursorLineColChanged.emit(line, col)

    def mark_saved(self) -> None:
        """After File → Save / Save As: the undo (and redo) history is cleared (ide-spec 1.21)."""
        self.document().clearUndoRedoStacks()
        self.document().setModified(False)

    # --- diagnostics -----------------------------------------------------------------------------------
    def set_diagnostics(self, diagnostics: Iterable, *, file: str | None = None, goto_first: bool = False) -> None:
        """Show compiler diagnostics (``.severity``, ``.message``, ``.loc.line/.col``) as wavy underlines.

        With `file`, only diagnostics whose ``loc.file`` equals it are shown (others are in include files).
        Errors are red, warnings orange; notes are ignored. The message is the tooltip of the underline.
        With `goto_first` the caret jumps to the first error, as after Syntax Check (ide-spec 1.23).
        """
        self._diagnostics = []
        doc = self.document()
        for d in diagnostics:
            if d.severity not in ("error", "warning") or (file is not None and d.loc.file != file):
                continue
            block = doc.findBlockByNumber(max(1, d.loc.line) - 1)
            if not block.isValid():
                block = doc.lastBlock()
            text = block.text()
            col = max(0, min(d.loc.col - 1, len(text)))
            m = _DIAG_TOKEN_RE.match(text, col) if col < len(text) else None
            start, end = (m.start(), m.end()) if m else (max(0, len(text) - 1), len(text))
            cursor = QTextCursor(doc)
            cursor.setPosition(block.position() + start)
            cursor.setPosition(block.position() + end, QTextCursor.MoveMode.KeepAnchor)
            self._diagnostics.append(_Diagnostic(cursor, d.severity, d.message))
        self.update_extra_selections()
        self.gutter.update()
        errors = [(line, col) for line, col, severity, _ in self.diagnostics() if severity == "error"]
        if goto_first and errors:
            self.goto_line(errors[0][0], col=errors[0][1])

    def clear_diagnostics(self) -> None:
        self.set_diagnostics(())

    def diagnostics(self) -> list[tuple[int, int, str, str]]:
        """The shown diagnostics at their current places: (line, col, severity, message), 1-based, in text order."""
        return sorted((d.cursor.block().blockNumber() + 1,
                       d.cursor.selectionStart() - d.cursor.block().position() + 1, d.severity, d.message)
                      for d in self._diagnostics)

    def diagnostic_marks(self) -> dict[int, str]:
        """0-based block number → "error" or "warning" (errors win) for the margin."""
        marks: dict[int, str] = {}
        for d in self._diagnostics:
            number = d.cursor.block().blockNumber()
            if marks.get(number) != "error":
                marks[number] = d.severity
        return marks

    def update_extra_selections(self, *, force: bool = True) -> None:
        """Current-line band and diagnostic squiggles. Setting them repaints the whole view, so a caret move
        within the same line (typing) skips it unless `force`."""
        block_number = self.textCursor().blockNumber()
        if not force and block_number == self._extra_line:
            return
        self._extra_line = block_number
        selections = []
        line = QTextEdit.ExtraSelection()
        line.format.setBackground(QColor(self.settings.colors.current_line))
        line.format.setProperty(QTextFormat.Property.FullWidthSelection, True)
        line.cursor = QTextCursor(self.textCursor().block())
        selections.append(line)
        debug = self.debug.debug_selection()
        if debug is not None:
            selections.append(debug)
        for d in self._diagnostics:
            sel = QTextEdit.ExtraSelection()
            sel.format.setUnderlineStyle(QTextCharFormat.UnderlineStyle.SpellCheckUnderline)
            sel.format.setUnderlineColor(QColor(getattr(self.settings.colors, d.severity)))
            sel.format.setToolTip(d.message)
            sel.cursor = d.cursor
            selections.append(sel)
        self.setExtraSelections(selections)

    # --- hover help ------------------------------------------------------------------------------------
    def tooltip_at(self, pos: QPoint) -> str | None:
        """Tooltip for viewport point `pos`: a diagnostic's message, else the help of a command/parameter."""
        block = self.cursorForPosition(pos).block()
        text = block.text()
        index = self.cursorForPosition(pos).positionInBlock()
        probe = QTextCursor(block)

        def x_at(i: int) -> int:
            probe.setPosition(block.position() + i)
            return self.cursorRect(probe).left()

        if index > 0 and x_at(index) > pos.x():
            index -= 1  # the caret position is right of the character under the mouse
        if index >= len(text):
            return None
        rect = self.cursorRect(probe)
        if not (x_at(index) <= pos.x() <= x_at(index + 1) and rect.top() <= pos.y() <= rect.bottom()):
            return None  # beside the text, not on it
        doc_pos = block.position() + index
        messages = [d.message for d in self._diagnostics
                    if d.cursor.selectionStart() <= doc_pos < max(d.cursor.selectionEnd(), doc_pos + 1)
                    and d.cursor.block() == block]
        if messages:
            return "\n".join(messages)
        return None if self.in_comment_or_string(block, index) else self.lang.hover_text(text, index)

    def viewportEvent(self, event: QEvent) -> bool:  # noqa: N802 (Qt override)
        if event.type() == QEvent.Type.ToolTip and isinstance(event, QHelpEvent):
            text = self.tooltip_at(event.pos())
            if text:
                QToolTip.showText(event.globalPos(), text, self.viewport())
            else:
                QToolTip.hideText()
                event.ignore()
            return True
        return super().viewportEvent(event)

    # --- language --------------------------------------------------------------------------------------
    @property
    def language(self) -> str:
        return "dpl" if self.lang is dpl_lang else "aposs"

    def print_(self, printer) -> None:
        from motiontool.ui.editor.printing import print_editor

        print_editor(self, printer)  # wrapped lines, a header on each page

    def set_language(self, language: str) -> None:
        """"dpl" for the APC's DPL (.dpl files), "aposs" otherwise: colours, hover help and completion follow."""
        if language == self.language:
            return
        from motiontool.ui.editor.dpl_highlighter import DplHighlighter

        self.highlighter.setDocument(None)
        kind = DplHighlighter if language == "dpl" else AposHighlighter
        self.highlighter = kind(self.document(), self.settings.colors)
        self.highlighter.rehighlight()  # now, not on Qt's next event-loop pass: the text is already there
        self.lang = dpl_lang if language == "dpl" else lang
        self._symbols_revision = -1

    # --- completion ------------------------------------------------------------------------------------
    @property
    def completer(self) -> QCompleter:
        return self._completer

    def _word_prefix(self) -> str:
        cursor = self.textCursor()
        text = cursor.block().text()[: cursor.positionInBlock()]
        i = len(text)
        while i > 0 and (text[i - 1].isalnum() or text[i - 1] == "_"):
            i -= 1
        return text[i:] if not text[i:i + 1].isdigit() else ""

    def in_comment_or_string(self, block: QTextBlock, index: int) -> bool:
        """True if character `index` of `block` is coloured as a comment, string or preprocessor line."""
        plain = self._quiet_colors
        ranges = block.layout().formats()
        return any(r.start <= index < r.start + r.length and r.format.foreground().color().rgb() in plain
                   for r in ranges)

    def _refresh_symbols(self) -> None:
        """Rebuild the completion list from the program (runs when typing pauses, and for Ctrl-Space)."""
        revision = self.document().revision()
        if revision == self._symbols_revision or self._completer.popup().isVisible():
            return
        self._symbols_revision = revision
        items = self.lang.completion_items(self.toPlainText())
        if self._completion_model.set_items(items):
            fm = self._completer.popup().fontMetrics()
            longest = sorted(items, key=lambda i: -len(i.name) - len(i.hint))[:40]
            self._popup_width = min(720, max((fm.horizontalAdvance(i.name) + fm.horizontalAdvance(i.hint[:60])
                                              for i in longest), default=0) + 64)

    def complete(self, *, force: bool = True) -> bool:
        """Ctrl-Space: open the completion popup for the word left of the caret; True if it is shown.

        Typing opens it (``force=False``) after AUTO_COMPLETE_LETTERS letters outside comments and strings,
        using the symbol list of the last typing pause, so a keystroke never waits for a rescan."""
        prefix = self._word_prefix()
        popup = self._completer.popup()
        cursor = self.textCursor()
        if not force and (len(prefix) < AUTO_COMPLETE_LETTERS
                          or self.in_comment_or_string(cursor.block(), cursor.positionInBlock() - 1)):
            popup.hide()
            return False
        if not popup.isVisible() and (force or self._symbols_revision < 0):
            self._refresh_symbols()
        self._completer.setCompletionPrefix(prefix)
        count = self._completer.completionCount()
        if count == 0 or count == 1 and self._completer.currentCompletion().upper() == prefix.upper():
            popup.hide()  # nothing to offer, or the word is already complete
            return False
        # no row is chosen until the user picks one: Enter typed at speed must end the line (issue 23)
        popup.setCurrentIndex(QModelIndex())
        self._completion_chosen = False
        rect = self.cursorRect()
        rect.translate(self.viewport().pos())
        rect.setWidth(max(360, self._popup_width))
        self._completer.complete(rect)
        return True

    def insert_completion(self, name: str) -> None:
        cursor = self.textCursor()
        cursor.movePosition(QTextCursor.MoveOperation.Left, QTextCursor.MoveMode.KeepAnchor,
                            len(self._word_prefix()))
        cursor.insertText(name)
        self.setTextCursor(cursor)

    # --- outline ---------------------------------------------------------------------------------------
    def outline(self) -> list[outline.OutlineItem]:
        """Labels, SUBPROGs and function definitions of the program (tasks and labels of DPL), in line order."""
        if self.lang is dpl_lang:
            return dpl_lang.outline(self.toPlainText())
        return outline.outline(self.toPlainText())

    # --- keys ------------------------------------------------------------------------------------------
    def key_bindings(self) -> dict[str, str]:
        """The editor's own keys: shortcut (portable text) → what it does ("F2" → "next bookmark")."""
        return {k: (v if isinstance(v, str) else v[0]).rsplit(".", 1)[-1].replace("_", " ")
                for k, v in self._keymap.items()}

    def event(self, event: QEvent) -> bool:
        if event.type() == QEvent.Type.ShortcutOverride and isinstance(event, QKeyEvent):
            combo = combination(event)
            if combo in self._keymap or combo in self.macros.first_keys() or self.recorder.pending_chord:
                event.accept()
                return True
        return super().event(event)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 (Qt override)
        if (watched is self._completer.popup() and event.type() == QEvent.Type.KeyPress
                and isinstance(event, QKeyEvent) and event.key() in _CHOOSING_KEYS):
            self._completion_chosen = True
        return super().eventFilter(watched, event)

    def keyPressEvent(self, event: QKeyEvent) -> None:  # noqa: N802 (Qt override)
        if event.key() == _LINEFEED:  # X11 Linefeed (xdotool type, some input tools): Qt drops it, it is a Return
            event.accept()
            event = QKeyEvent(QEvent.Type.KeyPress, Qt.Key.Key_Return, event.modifiers(), "\r")
        popup = self._completer.popup()
        key = event.key()
        if popup.isVisible() and key in (Qt.Key.Key_Enter, Qt.Key.Key_Return):
            popup.hide()
            event.accept()  # (it came through the popup: accepted, the completer leaves it alone)
            if self._completion_chosen and popup.currentIndex().isValid():
                self.insert_completion(popup.currentIndex().data())  # the chosen row, no new line
                return
            # nothing chosen: Enter ends the line as if the popup were not there
        elif popup.isVisible() and key == Qt.Key.Key_Tab and not popup.currentIndex().isValid():
            self.insert_completion(self._completer.completionModel().index(0, 0).data())  # Tab takes the first
            popup.hide()
            event.accept()
            return
        elif popup.isVisible() and key in (Qt.Key.Key_Enter, Qt.Key.Key_Return, Qt.Key.Key_Escape,
                                           Qt.Key.Key_Tab, Qt.Key.Key_Backtab):
            event.ignore()  # the completer's popup takes these
            return
        if event.key() in _MODIFIER_KEYS:  # a modifier alone neither records nor breaks a two-key shortcut
            super().keyPressEvent(event)
            return
        combo = combination(event)
        self.recorder.note(event, combo)
        if self.recorder.take_shortcut(combo):
            return
        count, self.edit.repeat_count = max(1, self.edit.repeat_count), 0
        for _ in range(count):
            self._handle_key(event, combo)

    def _handle_key(self, event: QKeyEvent, combo: str) -> None:
        key = event.key()
        action = self._keymap.get(combo)
        name, *args = (action,) if isinstance(action, str | None) else action
        options = args.pop() if args and isinstance(args[-1], dict) else {}
        if self.isReadOnly():  # only moving, selecting, copying, finding and bookmarks
            if name is not None and name not in EDITING:
                operator.attrgetter(name)(self)(*args, **options)
            elif name is None:
                super().keyPressEvent(event)
            return
        if name is not None:
            operator.attrgetter(name)(self)(*args, **options)  # "edit.cut_line": the part's method
            return
        cursor = self.textCursor()
        if key == Qt.Key.Key_Tab and not event.modifiers() & ~Qt.KeyboardModifier.KeypadModifier:
            first, last = self.edit.selected_block_range()
            self.edit.indent_selection() if cursor.hasSelection() and first != last else self.edit.insert_tab()
            return
        if key == Qt.Key.Key_Backtab:
            self.edit.unindent_selection()
            return
        if key in (Qt.Key.Key_Return, Qt.Key.Key_Enter) and not event.modifiers() & ~(
                Qt.KeyboardModifier.KeypadModifier | Qt.KeyboardModifier.ShiftModifier):
            self._new_line()
            return
        super().keyPressEvent(event)
        if self.recorder.playing:
            return
        text = event.text()
        if text and (text.isalnum() or text == "_") or (key == Qt.Key.Key_Backspace and self._completer.popup()
                                                         .isVisible()):
            self.complete(force=self._completer.popup().isVisible() and bool(self._word_prefix()))
        elif text or key in (Qt.Key.Key_Left, Qt.Key.Key_Right, Qt.Key.Key_Home, Qt.Key.Key_End):
            self._completer.popup().hide()

    def _new_line(self) -> None:
        """Return keeps the indentation of the line; at a line start the line's bookmark moves down with it."""
        cursor = self.textCursor()
        block = cursor.block()
        text = block.text()
        at_start = cursor.positionInBlock() == 0 and not cursor.hasSelection()
        indent = "" if at_start else text[: len(text) - len(text.lstrip(" \t"))][: cursor.positionInBlock()]
        moved = at_start and self.bookmarks.has_bookmark(block)
        cursor.beginEditBlock()
        cursor.insertBlock()
        cursor.insertText(indent)
        cursor.endEditBlock()
        if moved:
            self.bookmarks.set_bookmark(block, False)
            self.bookmarks.set_bookmark(cursor.block(), True)
            self.bookmarks.changed()
        self.setTextCursor(cursor)
        self.ensureCursorVisible()

    # --- mouse (ide-spec 1.8, 1.12) --------------------------------------------------------------------
    def mousePressEvent(self, event: QMouseEvent) -> None:  # noqa: N802 (Qt override)
        if event.button() == Qt.MouseButton.MiddleButton:  # wheel click selects the word
            cursor = self.cursorForPosition(event.position().toPoint())
            cursor.select(QTextCursor.SelectionType.WordUnderCursor)
            self.setTextCursor(cursor)
            return
        self._completer.popup().hide()
        super().mousePressEvent(event)
        self.debug.debug_mouse_press(event)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:  # noqa: N802 (Qt override)
        super().mouseMoveEvent(event)
        self.debug.debug_mouse_move(event)

    def mouseDoubleClickEvent(self, event: QMouseEvent) -> None:  # noqa: N802 (Qt override)
        if event.button() == Qt.MouseButton.MiddleButton:  # wheel double-click selects the line
            cursor = self.cursorForPosition(event.position().toPoint())
            cursor.movePosition(QTextCursor.MoveOperation.StartOfBlock)
            cursor.movePosition(QTextCursor.MoveOperation.EndOfBlock, QTextCursor.MoveMode.KeepAnchor)
            self.setTextCursor(cursor)
            return
        if self.debug.debug_double_click(event):
            return
        super().mouseDoubleClickEvent(event)

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:  # noqa: N802 (Qt override)
        if event.button() == Qt.MouseButton.MiddleButton:
            return  # no X11 selection paste: the wheel click selects instead
        super().mouseReleaseEvent(event)

    # --- context menu (ide-spec 1.7) -------------------------------------------------------------------
    def build_context_menu(self) -> QMenu:
        menu = QMenu(self)
        doc, has_sel = self.document(), self.textCursor().hasSelection()
        entries = [
            ("Undo", "Ctrl+Z", self.undo, doc.isUndoAvailable()), ("Cut", "Ctrl+X", self.cut, has_sel),
            ("Copy", "Ctrl+C", self.copy, has_sel), ("Paste", "Ctrl+V", self.paste, self.canPaste()), None,
            ("Find...", "Ctrl+F", self.search.show_find_dialog, True),
            ("Replace...", "Ctrl+R", self.search.show_replace_dialog, True),
            ("Find in Files...", "", self.search.show_find_in_files, True), None,
            ("Next Bookmark", "F2", self.bookmarks.next_bookmark, True),
            ("Previous Bookmark", "Shift+F2", self.bookmarks.previous_bookmark, True),
            ("Toggle Bookmark", "Ctrl+F2", self.bookmarks.toggle_bookmark, True),
            ("Clear All Bookmarks", "", self.bookmarks.clear_bookmarks, True),
        ]
        for entry in entries:
            if entry is None:
                menu.addSeparator()
                continue
            text, keys, slot, enabled = entry
            action = menu.addAction(f"{text}\t{keys}" if keys else text)
            action.triggered.connect(lambda *_, s=slot: s())
            action.setEnabled(enabled)
        return menu

    def contextMenuEvent(self, event: QContextMenuEvent) -> None:  # noqa: N802 (Qt override)
        menu = self.build_context_menu()
        value = self.debug.variable_value
        name = self.debug.variable_at(event.pos()) if value is not None else None
        if name and value is not None and value(name) is not None:
            menu.insertSeparator(menu.actions()[0])
            action = menu.addAction(f"Change value of {name}...")
            menu.insertAction(menu.actions()[0], action)
            action.triggered.connect(lambda *_, n=name: self.variableEditRequested.emit(n))
        menu.exec(event.globalPos())
