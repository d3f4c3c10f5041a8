"""FindReplaceDialog and FindInFilesDialog on a real CodeEditor; F3 / Ctrl-F3 keys (ide-spec 1.17, 1.32-1.36)."""

from __future__ import annotations

import pytest
from PySide6.QtCore import Qt

from motiontool.ui.editor import FindInFilesDialog, FindReplaceDialog
from motiontool.ui.editor.search import SearchOptions

PROGRAM = "vel1 = 10\nvel2 = 100\nacc = 1000\nvel3 \t= 5\nvelocity = 7\n"
CTRL, SHIFT = Qt.KeyboardModifier.ControlModifier, Qt.KeyboardModifier.ShiftModifier


@pytest.fixture
def dialog(qtbot, editor):
    editor.setPlainText(PROGRAM)
    editor.goto_line(1)
    press(qtbot, editor, Qt.Key.Key_R, CTRL)  # Ctrl-R: Find and Replace [DG L2152]
    dlg = editor.search.find_dialog
    assert isinstance(dlg, FindReplaceDialog) and dlg.isVisible() and dlg.replace_edit.isVisible()
    return dlg


def press(qtbot, widget, key, modifiers=Qt.KeyboardModifier.NoModifier):
    qtbot.keyClick(widget, key, modifiers)


def use_syntax(dlg: FindReplaceDialog, mode: str) -> None:
    dlg.options_box.set_mode(mode)
    assert dlg.options().mode == mode


def selected(editor) -> tuple[int, str]:
    cursor = editor.textCursor()
    return cursor.blockNumber() + 1, cursor.selectedText()


def test_ctrl_f_opens_find_without_replace(qtbot, editor):
    editor.setPlainText(PROGRAM)
    press(qtbot, editor, Qt.Key.Key_F, CTRL)
    dlg = editor.search.find_dialog
    assert dlg.isVisible() and dlg.windowTitle() == "Find" and not dlg.replace_edit.isVisible()


def test_find_next_plain_then_f3_and_shift_f3(qtbot, editor, dialog):
    qtbot.keyClicks(dialog.find_edit, "vel")
    dialog.whole_word = dialog.options_box.whole_word
    assert dialog.find_next() and selected(editor) == (1, "vel")
    press(qtbot, editor, Qt.Key.Key_F3)  # F3: next [DG L2148]
    assert selected(editor) == (2, "vel")
    press(qtbot, editor, Qt.Key.Key_F3, SHIFT)  # Shift-F3: previous
    assert selected(editor) == (1, "vel")


def test_manual_pattern_syntax_in_the_dialog(qtbot, editor, dialog):
    """DG L2324: 'vel[ \\t]*= Search for "vel", followed by any number of spaces or tabs, followed by "="'."""
    use_syntax(dialog, "pattern")
    dialog.find_edit.setText(r"vel[1-3][ \t]*=")
    hits = []
    for _ in range(4):
        assert dialog.find_next()
        hits.append(selected(editor))
    assert hits == [(1, "vel1 ="), (2, "vel2 ="), (4, "vel3 \t="), (1, "vel1 =")]
    assert "continued" in dialog.status.text()  # wrapped around


def test_manual_pattern_plus_and_or(qtbot, editor, dialog):
    """DG L2319 '10+ ... (e.g. 10, 100, 1000, etc.)' and L2323 '(vel) (acc) Search for "vel" or "acc"'."""
    use_syntax(dialog, "pattern")
    dialog.find_edit.setText("10+")
    found = []
    for _ in range(3):
        dialog.find_next()
        found.append(selected(editor)[1])
    assert found == ["10", "100", "1000"]
    dialog.find_edit.setText("(vel)|(acc)")
    dialog.options_box.whole_word.setChecked(True)
    editor.goto_line(1)
    dialog.find_next()
    assert selected(editor) == (3, "acc")  # whole word: vel1, vel2, velocity do not count


def test_match_case_direction_and_no_wrap(qtbot, editor, dialog):
    dialog.find_edit.setText("VEL")
    dialog.options_box.match_case.setChecked(True)
    assert not dialog.find_next() and "Cannot find" in dialog.status.text()
    dialog.options_box.match_case.setChecked(False)
    editor.goto_line(3)
    dialog.up.setChecked(True)
    assert dialog.find_next() and selected(editor) == (2, "vel")
    dialog.wrap.setChecked(False)
    editor.goto_line(1)
    assert not dialog.find_next()


def test_invalid_pattern_shows_an_error(qtbot, editor, dialog):
    use_syntax(dialog, "pattern")
    dialog.find_edit.setText("vel[1-")
    assert not dialog.find_next()
    assert "missing ']'" in dialog.status.text()


def test_replace_steps_through_hits(qtbot, editor, dialog):
    use_syntax(dialog, "pattern")
    dialog.find_edit.setText("vel[0-9]")
    dialog.replace_edit.setText("speed")
    dialog.find_next()
    assert dialog.replace() and editor.toPlainText().startswith("speed = 10\nvel2")
    assert selected(editor) == (2, "vel2")  # the next hit is selected
    assert dialog.replace()
    assert editor.toPlainText().startswith("speed = 10\nspeed = 100")


def test_replace_all_is_one_undo_step(qtbot, editor, dialog):
    editor.bookmarks.set_bookmarks([4])
    use_syntax(dialog, "pattern")
    dialog.find_edit.setText(r"vel[ \t]*[0-9]")
    dialog.replace_edit.setText(r"v\t")
    qtbot.mouseClick(dialog.replace_all_button, Qt.MouseButton.LeftButton)
    assert "3 replacement(s)" in dialog.status.text()
    assert editor.toPlainText() == "v\t = 10\nv\t = 100\nacc = 1000\nv\t \t= 5\nvelocity = 7\n"
    assert editor.bookmarks.lines() == [4]  # edits in place keep the line marks
    press(qtbot, editor, Qt.Key.Key_Z, CTRL)  # ONE undo brings back the whole text ...
    assert editor.toPlainText() == PROGRAM
    assert not editor.document().isUndoAvailable()  # ... and it was the only step


def test_replace_all_in_regex_mode_with_groups(editor):
    editor.setPlainText(PROGRAM)
    count = editor.search.replace_all(r"vel(\d)", r"axis\1_vel", options=SearchOptions(mode="regex"))
    assert count == 3 and editor.toPlainText().startswith("axis1_vel = 10\naxis2_vel = 100")


def test_mark_all_bookmarks_every_hit_line(qtbot, editor, dialog):
    """DG L2306: 'Mark All ... all instances found are immediately "bookmarked" ... [F2] can then be used'."""
    dialog.find_edit.setText("vel")
    qtbot.mouseClick(dialog.mark_button, Qt.MouseButton.LeftButton)
    assert editor.bookmarks.lines() == [1, 2, 4, 5]
    editor.goto_line(2)
    press(qtbot, editor, Qt.Key.Key_F2)
    assert editor.caret_line_col()[0] == 4


def test_ctrl_f3_finds_the_word_under_the_caret(qtbot, editor):
    editor.setPlainText("POSA a\nx = a + aa\nPRINT a")
    editor.goto_line(1, col=6)
    press(qtbot, editor, Qt.Key.Key_F3, CTRL)
    assert selected(editor) == (2, "a")
    assert editor.textCursor().selectionStart() == 11
    press(qtbot, editor, Qt.Key.Key_F3, CTRL)
    assert selected(editor) == (3, "a")  # 'aa' is not the word 'a'
    press(qtbot, editor, Qt.Key.Key_F3, CTRL | SHIFT)
    assert selected(editor) == (2, "a") and editor.textCursor().selectionStart() == 11


def test_find_with_emoji_before_the_hit(editor):
    editor.setPlainText("// \U0001F600 comment\nPOSA 1")
    assert editor.search.find(text="POSA")
    assert editor.textCursor().selectedText() == "POSA"


def test_find_in_files_dialog(qtbot, editor, tmp_path):
    (tmp_path / "main.m").write_text("GOSUB home\n", encoding="utf-8")
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "home.m").write_text("// home position\nSUBPROG home\n", encoding="utf-8")
    editor.setPlainText("GOSUB home\n")
    editor.file_path = tmp_path / "main.m"
    editor.goto_line(1, col=8)
    dlg = editor.search.show_find_in_files()
    assert isinstance(dlg, FindInFilesDialog) and dlg.find_edit.text() == "home"
    hits = dlg.run_search()
    assert [(h.path.name, h.line) for h in hits] == [("home.m", 1), ("home.m", 2), ("main.m", 1)]
    assert dlg.results.topLevelItemCount() == 3
    with qtbot.waitSignal(editor.openLocationRequested) as blocker:
        dlg.results.itemDoubleClicked.emit(dlg.results.topLevelItem(1), 0)
    assert blocker.args == [str(tmp_path / "lib" / "home.m"), 2, 9]
    dlg.results.itemDoubleClicked.emit(dlg.results.topLevelItem(2), 0)  # the editor's own file: jump there
    assert editor.caret_line_col() == (1, 7)
