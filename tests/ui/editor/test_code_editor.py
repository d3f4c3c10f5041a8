"""CodeEditor driven through real key and mouse events (pytest-qt, offscreen)."""

from __future__ import annotations

import operator

import pytest
from PySide6.QtCore import QEvent, QPoint, Qt
from PySide6.QtGui import QAction, QHelpEvent, QKeySequence, QTextCharFormat, QTextCursor
from PySide6.QtWidgets import QApplication, QMainWindow, QToolTip

from motiontool.aposs.driver import compile_source
from motiontool.ui.editor import BookmarkStore, CodeEditor, EditorSettings, OutlineItem
from motiontool.ui.editor.keymap import EDITING, KEYMAP
from motiontool.ui.editor.macros import MacroSlots

CTRL, SHIFT, ALT = (Qt.KeyboardModifier.ControlModifier, Qt.KeyboardModifier.ShiftModifier,
                    Qt.KeyboardModifier.AltModifier)
TEN_LINES = "\n".join(f"line {i}" for i in range(1, 11))


def press(qtbot, widget, key, modifiers=Qt.KeyboardModifier.NoModifier, times=1):
    for _ in range(times):
        qtbot.keyClick(widget, key, modifiers)


def point_at(editor: CodeEditor, line: int, col: int) -> QPoint:
    """Viewport point in the middle of the character at 1-based line/col."""
    cursor = QTextCursor(editor.document().findBlockByNumber(line - 1))
    cursor.setPosition(cursor.position() + col - 1)
    left = editor.cursorRect(cursor)
    cursor.setPosition(cursor.position() + 1)
    return QPoint((left.left() + editor.cursorRect(cursor).left()) // 2, left.center().y())


# --- bookmarks (ide-spec 1.37) ------------------------------------------------------------------------------

def test_bookmarks_move_with_inserted_lines_and_f2_cycles(qtbot, editor):
    editor.setPlainText(TEN_LINES)
    editor.goto_line(4)
    press(qtbot, editor, Qt.Key.Key_F2, CTRL)  # Ctrl-F2 toggles [DG L2118]
    editor.goto_line(8)
    press(qtbot, editor, Qt.Key.Key_F2, CTRL)
    assert editor.bookmarks.lines() == [4, 8]
    editor.goto_line(1)
    qtbot.keyClicks(editor, "new")
    press(qtbot, editor, Qt.Key.Key_Return, times=2)  # two lines inserted above the marks
    assert editor.bookmarks.lines() == [6, 10]
    editor.goto_line(6)
    press(qtbot, editor, Qt.Key.Key_Return)  # Return at the start of a marked line: the mark moves down with it
    assert editor.bookmarks.lines() == [7, 11]
    editor.goto_line(1)
    visited = []
    for _ in range(3):
        press(qtbot, editor, Qt.Key.Key_F2)
        visited.append(editor.caret_line_col()[0])
    assert visited == [7, 11, 7]  # wraps around
    press(qtbot, editor, Qt.Key.Key_F2, SHIFT)
    assert editor.caret_line_col()[0] == 11
    press(qtbot, editor, Qt.Key.Key_F2, CTRL)  # toggle off on line 11
    assert editor.bookmarks.lines() == [7]
    editor.bookmarks.clear_bookmarks()
    assert editor.bookmarks.lines() == [] and editor.bookmarks.next_bookmark() is None


def test_editor_keys_win_over_window_shortcuts(qtbot):
    """The main window binds F2 in its Edit menu; in the editor F2 still goes to the next bookmark."""
    window = QMainWindow()
    qtbot.addWidget(window)
    fired = []
    action = QAction("Next Bookmark", window, shortcut="F2", triggered=lambda: fired.append(1))
    window.addAction(action)
    editor = CodeEditor()
    window.setCentralWidget(editor)
    window.show()
    qtbot.waitExposed(window)
    editor.setFocus()
    editor.setPlainText(TEN_LINES)
    editor.bookmarks.set_bookmarks([5])
    editor.goto_line(1)
    press(qtbot, editor, Qt.Key.Key_F2)
    assert editor.caret_line_col()[0] == 5 and not fired


def test_bookmarks_saved_outside_the_program(qtbot, editor, tmp_path):
    program = tmp_path / "demo.m"
    program.write_text(TEN_LINES, encoding="utf-8")
    store = BookmarkStore(tmp_path / "cfg" / "bookmarks.json")
    editor.setPlainText(TEN_LINES)
    editor.file_path = program
    editor.bookmarks.set_bookmarks([2, 9])
    editor.bookmarks.save_bookmarks(store)
    again = CodeEditor()
    qtbot.addWidget(again)
    again.setPlainText(program.read_text(encoding="utf-8"))
    again.bookmarks.load_bookmarks(store, path=program)
    assert again.bookmarks.lines() == [2, 9]
    assert program.read_text(encoding="utf-8") == TEN_LINES


# --- tabs (ide-spec 1.22, 1.38, 1.44) -----------------------------------------------------------------------

def test_convert_tabs_is_one_undo_step_and_keeps_bookmarks(qtbot, editor):
    editor.setPlainText("\tPOSA 1\nab\tcd\nno tabs")
    editor.bookmarks.set_bookmarks([2])
    assert editor.edit.convert_tabs() == 2
    assert editor.toPlainText() == "    POSA 1\nab  cd\nno tabs"
    assert editor.bookmarks.lines() == [2]
    press(qtbot, editor, Qt.Key.Key_Z, CTRL)
    assert editor.toPlainText() == "\tPOSA 1\nab\tcd\nno tabs"


def test_tab_key_with_and_without_conversion(qtbot, editor):
    editor.setPlainText("ab")
    editor.moveCursor(QTextCursor.MoveOperation.End)
    press(qtbot, editor, Qt.Key.Key_Tab)
    assert editor.toPlainText() == "ab\t"
    editor.apply_settings(EditorSettings(tab_size=4, convert_tabs_while_typing=True))
    editor.setPlainText("ab\tx")  # existing tabs stay [DG L3150]
    editor.moveCursor(QTextCursor.MoveOperation.End)
    press(qtbot, editor, Qt.Key.Key_Tab)
    assert editor.toPlainText() == "ab\tx   "  # "ab\tx" ends at column 5 → 3 spaces to the stop at 8
    assert editor.tabStopDistance() == editor.fontMetrics().horizontalAdvance(" ") * 4


def test_tab_and_shift_tab_indent_a_selection(qtbot, editor):
    editor.setPlainText("a\nb\nc")
    cursor = editor.textCursor()
    cursor.setPosition(0)
    cursor.setPosition(3, QTextCursor.MoveMode.KeepAnchor)  # lines 1-2
    editor.setTextCursor(cursor)
    press(qtbot, editor, Qt.Key.Key_Tab)
    assert editor.toPlainText() == "\ta\n\tb\nc"
    press(qtbot, editor, Qt.Key.Key_Backtab, SHIFT)
    assert editor.toPlainText() == "a\nb\nc"


# --- keyboard functions (ide-spec 1.14-1.19) ----------------------------------------------------------------

def test_line_and_paragraph_keys(qtbot, editor):
    editor.setPlainText("one\ntwo\n\nthree\nfour\n\nfive")
    editor.goto_line(2)
    press(qtbot, editor, Qt.Key.Key_Y, CTRL)  # cut line [DG L2141]
    assert editor.toPlainText() == "one\n\nthree\nfour\n\nfive"
    assert QApplication.clipboard().text() == "two\n"
    editor.goto_line(4)
    press(qtbot, editor, Qt.Key.Key_K, CTRL | ALT)  # cut paragraph [DG L2144]
    assert editor.toPlainText() == "one\n\n\nfive"
    editor.goto_line(1)
    press(qtbot, editor, Qt.Key.Key_Down, CTRL | ALT)  # next blank line
    assert editor.caret_line_col() == (2, 1)
    press(qtbot, editor, Qt.Key.Key_N, CTRL | SHIFT)  # new line above
    assert editor.toPlainText() == "one\n\n\n\nfive" and editor.caret_line_col() == (2, 1)


def test_case_bracket_select_overwrite_and_undo_keys(qtbot, editor):
    editor.setPlainText("posa (a[1] + b)")
    press(qtbot, editor, Qt.Key.Key_F8, CTRL | ALT)  # select line
    assert editor.textCursor().selectedText() == "posa (a[1] + b)"
    press(qtbot, editor, Qt.Key.Key_U, CTRL | SHIFT)
    assert editor.toPlainText() == "POSA (A[1] + B)"
    press(qtbot, editor, Qt.Key.Key_U, CTRL)
    assert editor.toPlainText() == "posa (a[1] + b)"
    editor.goto_line(1, col=6)
    press(qtbot, editor, Qt.Key.Key_B, CTRL)  # matching bracket
    assert editor.textCursor().position() == 14
    press(qtbot, editor, Qt.Key.Key_Insert)
    assert editor.overwriteMode()
    editor.goto_line(1)
    qtbot.keyClicks(editor, "MOVE")
    assert editor.toPlainText() == "MOVE (a[1] + b)"
    press(qtbot, editor, Qt.Key.Key_Insert)
    assert not editor.overwriteMode()
    editor.moveCursor(QTextCursor.MoveOperation.End)
    qtbot.keyClicks(editor, " xy")
    assert editor.toPlainText() == "MOVE (a[1] + b) xy"
    press(qtbot, editor, Qt.Key.Key_Backspace, ALT)  # undo [DG L2155]
    assert editor.toPlainText() == "MOVE (a[1] + b)"
    editor.goto_line(1)
    press(qtbot, editor, Qt.Key.Key_Right, CTRL)  # end of the word [DG L2108]
    assert editor.textCursor().position() == 4


def test_repeat_next_command(qtbot, editor):
    editor.setPlainText("")
    editor.edit.repeat_next(5)
    qtbot.keyClicks(editor, "x")
    assert editor.toPlainText() == "xxxxx"


def test_return_keeps_indentation(qtbot, editor):
    editor.setPlainText("  IF a THEN")
    editor.moveCursor(QTextCursor.MoveOperation.End)
    press(qtbot, editor, Qt.Key.Key_Return)
    qtbot.keyClicks(editor, "b")
    assert editor.toPlainText() == "  IF a THEN\n  b"


def test_save_clears_undo(editor):
    editor.setPlainText("a")
    editor.textCursor().insertText("b")
    assert editor.document().isUndoAvailable()
    editor.mark_saved()
    assert not editor.document().isUndoAvailable() and not editor.document().isModified()


# --- mouse (ide-spec 1.8, 1.11, 1.12) -----------------------------------------------------------------------

def test_mouse_word_and_line_selection(qtbot, editor):
    editor.setPlainText("POSA target_pos\nline two")
    viewport = editor.viewport()
    qtbot.mouseDClick(viewport, Qt.MouseButton.LeftButton, pos=point_at(editor, 1, 8))
    assert editor.textCursor().selectedText() == "target_pos"
    qtbot.mouseClick(viewport, Qt.MouseButton.MiddleButton, pos=point_at(editor, 2, 2))
    assert editor.textCursor().selectedText() == "line"
    y = point_at(editor, 2, 1).y()
    qtbot.mouseClick(editor.gutter, Qt.MouseButton.LeftButton, pos=QPoint(10, y))  # margin click: the line
    assert editor.textCursor().selectedText() == "line two"


# --- macros (ide-spec 1.24) ---------------------------------------------------------------------------------

def test_macro_record_and_replay(qtbot, editor):
    editor.setPlainText("")
    press(qtbot, editor, Qt.Key.Key_R, CTRL | SHIFT)  # start recording [DG L2206]
    assert editor.recorder.is_recording
    qtbot.keyClicks(editor, "ab")
    press(qtbot, editor, Qt.Key.Key_Return)
    press(qtbot, editor, Qt.Key.Key_R, CTRL | SHIFT)  # stop
    assert not editor.recorder.is_recording
    assert editor.toPlainText() == "ab\n"
    assert editor.recorder.play_macro()
    assert editor.toPlainText() == "ab\nab\n"
    editor.macros.assign("Alt+M", editor.recorder.last_macro)
    press(qtbot, editor, Qt.Key.Key_M, ALT)  # the saved shortcut plays it
    assert editor.toPlainText() == "ab\nab\nab\n"
    editor.recorder.clear_macros()
    assert not editor.recorder.play_macro()


def test_stopping_with_the_key_opens_save_macro(qtbot, editor):
    """DG L2208: 'Press the keyboard shortcut that you want to assign to the macro (e.g. [Ctrl]-[Shift]-[M]).
    Each shortcut can be up to two characters in length. Then select one of the available "Save As"
    alternatives.'"""
    editor.setPlainText("")
    press(qtbot, editor, Qt.Key.Key_R, CTRL | SHIFT)
    qtbot.keyClicks(editor, "q")
    press(qtbot, editor, Qt.Key.Key_R, CTRL | SHIFT)
    dialog = editor.recorder.macro_dialog
    assert dialog.isVisible() and dialog.slot_list.count() == 10
    assert dialog.slot_list.item(0).text() == "1 : <unassigned>" and not dialog.ok_button.isEnabled()
    dialog.shortcut_edit.setKeySequence(QKeySequence("F3"))
    assert dialog.assigned.text() == "Currently assigned to: find next"  # the warning of DG L2218
    dialog.shortcut_edit.setKeySequence(QKeySequence("Alt+Q, Alt+W"))  # two keystrokes
    assert dialog.assigned.text() == "Currently assigned to: <unassigned>"
    dialog.slot_list.setCurrentRow(3)
    dialog.accept()
    assert editor.macros.slots()[3] == "Alt+Q, Alt+W"
    press(qtbot, editor, Qt.Key.Key_Q, ALT)
    press(qtbot, editor, Qt.Key.Key_W, ALT)
    assert editor.toPlainText() == "qq"
    restored = MacroSlots.from_json(editor.macros.to_json())  # the application persists them
    assert restored.slots() == editor.macros.slots() and restored.get("Alt+Q, Alt+W") == editor.macros.get(
        "Alt+Q, Alt+W")


def test_at_most_ten_macros():
    slots = MacroSlots()
    for i in range(10):
        slots.assign(f"Alt+{i}", [])
    with pytest.raises(ValueError):
        slots.assign("Alt+A", [])
    assert slots.assign("Alt+A", [], slot=2) == 2 and slots.get("Alt+2") is None
    slots.clear()
    assert len(slots) == 0


def test_macro_records_editor_commands(qtbot, editor):
    editor.setPlainText("x = 1\ny = 2\nz = 3")
    editor.recorder.start_recording()
    press(qtbot, editor, Qt.Key.Key_F2, CTRL)  # toggle bookmark
    press(qtbot, editor, Qt.Key.Key_Down)
    keys = editor.recorder.stop_recording(shortcut="Ctrl+Shift+M")
    assert len(keys) == 2 and editor.macros.shortcuts() == ["Ctrl+Shift+M"]
    editor.recorder.play_macro(shortcut="Ctrl+Shift+M")
    assert editor.bookmarks.lines() == [1, 2] and editor.caret_line_col()[0] == 3


# --- completion and hover help ------------------------------------------------------------------------------

def test_completion_popup_after_three_letters(qtbot, editor):
    editor.setPlainText("")
    qtbot.keyClicks(editor, "PO")
    assert not editor.completer.popup().isVisible()
    qtbot.keyClicks(editor, "S")
    popup = editor.completer.popup()
    qtbot.waitUntil(popup.isVisible)
    shown = [popup.model().index(i, 0).data() for i in range(popup.model().rowCount())]
    assert "POSA" in shown and all(name.upper().startswith("POS") for name in shown)
    assert not popup.currentIndex().isValid()  # nothing chosen yet: Enter would end the line (issue 23)
    press(qtbot, popup, Qt.Key.Key_Down)
    assert popup.currentIndex().data() == "POSA"
    press(qtbot, popup, Qt.Key.Key_Return)
    assert editor.toPlainText() == "POSA"
    assert not popup.isVisible()


def test_ctrl_space_completes_program_symbols(qtbot, editor):
    editor.setPlainText("my_speed = 10\nmy_label:\n")
    editor.moveCursor(QTextCursor.MoveOperation.End)
    qtbot.keyClicks(editor, "my")
    press(qtbot, editor, Qt.Key.Key_Space, CTRL)
    popup = editor.completer.popup()
    qtbot.waitUntil(popup.isVisible)
    shown = {popup.model().index(i, 0).data() for i in range(popup.model().rowCount())}
    assert shown == {"my_label", "my_speed"}
    press(qtbot, popup, Qt.Key.Key_Escape)
    assert not popup.isVisible()


def test_hover_tooltip_shows_command_syntax_and_help(qtbot, editor):
    editor.setPlainText("x = 1\nPOSA 3000\n")
    pos = point_at(editor, 2, 2)
    QApplication.sendEvent(editor.viewport(),
                           QHelpEvent(QEvent.Type.ToolTip, pos, editor.viewport().mapToGlobal(pos)))
    qtbot.waitUntil(QToolTip.isVisible)
    assert "POSA p" in QToolTip.text() and "absolute position" in QToolTip.text()
    assert editor.tooltip_at(point_at(editor, 1, 1)) is None
    QToolTip.hideText()


# --- diagnostics (ide-spec 1.23, 1.39) ----------------------------------------------------------------------

def test_diagnostics_draw_wavy_underlines_at_the_token(qtbot, editor):
    text = "x = 1\nPOSA\ny = 010\n"
    editor.setPlainText(text)
    result = compile_source(text, "prog.m")
    editor.set_diagnostics(result.diagnostics, file="prog.m")
    squiggles = [s for s in editor.extraSelections()
                 if s.format.underlineStyle() == QTextCharFormat.UnderlineStyle.SpellCheckUnderline]
    found = {(s.cursor.blockNumber() + 1, s.cursor.selectedText(), s.format.underlineColor().name())
             for s in squiggles}
    colors = editor.settings.colors
    assert (2, "POSA", colors.error) in found
    assert (3, "010", colors.warning) in found
    assert editor.diagnostic_marks() == {1: "error", 2: "warning"}
    assert "POSA needs more arguments" in editor.tooltip_at(point_at(editor, 2, 2))
    editor.goto_line(1)
    press(qtbot, editor, Qt.Key.Key_Return)  # the squiggles move with the text
    assert [(line, col, sev) for line, col, sev, _ in editor.diagnostics()] == [(3, 1, "error"), (4, 5, "warning")]
    editor.clear_diagnostics()
    assert editor.diagnostic_marks() == {}


def test_goto_line_and_caret_signal(qtbot, editor):
    editor.setPlainText(TEN_LINES)
    with qtbot.waitSignal(editor.cursorLineColChanged) as blocker:
        editor.goto_line(7, col=3)
    assert blocker.args == [7, 3] and editor.caret_line_col() == (7, 3)


# --- outline, context menu, margin ----------------------------------------------------------------------------

def test_outline(editor):
    editor.setPlainText("start:\nGOSUB s1\nGOTO start\nlong twice(long v)\n{\n return(v*2)\n}\n"
                        "SUBMAINPROG\nSUBPROG s1\nRETURN\nENDPROG\n")
    assert editor.outline() == [OutlineItem("label", "start", 1), OutlineItem("function", "twice", 4),
                                OutlineItem("subprog", "s1", 9)]


def test_context_menu_entries(editor):
    menu = editor.build_context_menu()
    entries = [a.text().split("\t") for a in menu.actions() if not a.isSeparator()]
    assert entries == [["Undo", "Ctrl+Z"], ["Cut", "Ctrl+X"], ["Copy", "Ctrl+C"], ["Paste", "Ctrl+V"],
                       ["Find...", "Ctrl+F"], ["Replace...", "Ctrl+R"], ["Find in Files..."],
                       ["Next Bookmark", "F2"], ["Previous Bookmark", "Shift+F2"], ["Toggle Bookmark", "Ctrl+F2"],
                       ["Clear All Bookmarks"]]
    toggle = next(a for a in menu.actions() if a.text().startswith("Toggle"))
    toggle.trigger()
    assert editor.bookmarks.lines() == [1]


def test_margin_grows_with_line_count(editor):
    editor.setPlainText("x")
    narrow = editor.gutter.area_width()
    editor.setPlainText("\n" * 20000)
    assert editor.gutter.area_width() > narrow
    assert editor.viewportMargins().left() == editor.gutter.area_width()


def test_keys_qt_already_provides(qtbot, editor):
    """ide-spec 1.14/1.15/1.18 keys that come with QPlainTextEdit still work inside the CodeEditor."""
    editor.setPlainText("alpha beta\ngamma delta")
    editor.goto_line(1, col=3)
    press(qtbot, editor, Qt.Key.Key_End, CTRL)
    assert editor.textCursor().position() == len(editor.toPlainText())
    press(qtbot, editor, Qt.Key.Key_Backspace, CTRL)  # delete to the start of the word
    assert editor.toPlainText() == "alpha beta\ngamma "
    press(qtbot, editor, Qt.Key.Key_Home, CTRL | SHIFT)  # select to the start of the program
    assert editor.textCursor().selectedText() == "alpha beta\u2029gamma "
    press(qtbot, editor, Qt.Key.Key_Home, CTRL)
    press(qtbot, editor, Qt.Key.Key_Delete, CTRL)  # delete to the end of the word
    assert editor.toPlainText() == " beta\ngamma "
    press(qtbot, editor, Qt.Key.Key_End, SHIFT)
    assert editor.textCursor().selectedText() == " beta"


def test_syntax_check_result_puts_the_caret_on_the_first_error(editor):
    text = "x = 010\ny = 1\nPOSA\nGOTO nowhere\n"
    editor.setPlainText(text)
    editor.set_diagnostics(compile_source(text, "p.m").diagnostics, goto_first=True)
    assert editor.caret_line_col()[0] == 3


def test_no_help_or_completion_inside_comments_and_strings(qtbot, editor):
    editor.setPlainText('// POSA here\nPRINT "POSA"\n')
    assert editor.tooltip_at(point_at(editor, 1, 5)) is None
    assert editor.tooltip_at(point_at(editor, 2, 9)) is None
    assert "PRINT" in editor.tooltip_at(point_at(editor, 2, 2))
    editor.goto_line(1)
    editor.moveCursor(QTextCursor.MoveOperation.EndOfLine)
    qtbot.keyClicks(editor, " POS")
    assert not editor.completer.popup().isVisible()


def test_editor_settings_dialog(qtbot, editor):
    from motiontool.ui.editor import EditorSettingsDialog

    dialog = EditorSettingsDialog(editor.settings)
    qtbot.addWidget(dialog)
    names = [dialog.elements.item(i).text() for i in range(7)]
    assert names == ["Comment", "Keyword", "Number", "Operator", "String", "Text", "Window"]  # [DG L3124-3131]
    assert dialog.tab_size.minimum() == 2
    dialog.set_color("keyword", "#aa0000")
    dialog.tab_size.setValue(2)
    dialog.convert.setChecked(True)
    chosen = dialog.settings()
    assert chosen.colors.keyword == "#aa0000" and chosen.tab_size == 2 and chosen.convert_tabs_while_typing
    assert dialog.preview.highlighter.colors.keyword == "#aa0000"
    editor.apply_settings(chosen)
    editor.setPlainText("POSA 1")
    ranges = editor.document().firstBlock().layout().formats()
    assert ranges[0].format.foreground().color().name() == "#aa0000"


def test_read_only_editor_moves_but_does_not_edit(qtbot, editor):
    editor.setPlainText(TEN_LINES)
    editor.setReadOnly(True)
    editor.goto_line(2)
    none = Qt.KeyboardModifier.NoModifier
    for key, mods in ((Qt.Key.Key_Return, none), (Qt.Key.Key_Tab, none), (Qt.Key.Key_Y, CTRL),
                      (Qt.Key.Key_N, CTRL | SHIFT), (Qt.Key.Key_Delete, CTRL)):
        press(qtbot, editor, key, mods)
    assert editor.toPlainText() == TEN_LINES
    press(qtbot, editor, Qt.Key.Key_F2, CTRL)
    assert editor.bookmarks.lines() == [2]


def test_scroll_keys_move_the_view_not_the_caret(qtbot, editor):
    editor.setPlainText("\n".join("x" * 300 for _ in range(200)))
    editor.goto_line(1)
    press(qtbot, editor, Qt.Key.Key_Down, CTRL, times=3)
    assert editor.verticalScrollBar().value() == 3 and editor.caret_line_col() == (1, 1)
    press(qtbot, editor, Qt.Key.Key_PageDown, CTRL)
    assert editor.horizontalScrollBar().value() > 0 and editor.caret_line_col() == (1, 1)


def test_every_editor_key_names_a_function_of_the_editor_or_its_parts(editor):
    """DG L2107-2170 list the editor's keys; each KEYMAP entry ("edit.cut_line", "undo") must name a callable on
    the editor or one of its parts (issue 27 item 7), or the key would fail only when pressed."""

    def resolves(name: str) -> bool:
        try:
            return callable(operator.attrgetter(name)(editor))
        except AttributeError:
            return False

    names = {v if isinstance(v, str) else v[0] for v in KEYMAP.values()}
    assert EDITING - names == set()  # a name the keymap no longer has
    assert [n for n in sorted(names) if not resolves(n)] == []
