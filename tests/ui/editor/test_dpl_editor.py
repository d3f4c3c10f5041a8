"""The program editor with a DPL program (.dpl): DPL colours, hover help for the APC calls, completion,
live diagnostics and F4 syntax check in the APOSS form (issue 20)."""

from __future__ import annotations

from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QColor

from tests.dpl.manual import PROGRAMS

SOURCE = "\n".join([
    "Notes{",
    "free prose: IF #18.11 = 3",
    "} //Notes",
    "Initial {",
    "Status% = APCSetRunMode(APC_DISABLE) // disable",
    "}",
    "Pos0{",
    "Pos% = APCReadPar(APC_FB_POS) + #18.11",
    "}",
]) + "\n"


def colour_at(editor, line: int, column: int) -> str:
    block = editor.document().findBlockByNumber(line - 1)
    for r in block.layout().formats():
        if r.start <= column - 1 < r.start + r.length:
            return r.format.foreground().color().name()
    return ""


def test_a_dpl_file_opens_with_dpl_colours_and_help(window, tmp_path, qtbot):
    path = tmp_path / "prog.dpl"
    path.write_text(SOURCE, encoding="utf-8")
    editor = window.open_file(path)
    assert editor.language == "dpl"
    colors = editor.settings.colors
    assert colour_at(editor, 2, 14) == QColor(colors.comment).name()        # Notes prose, even "IF #18.11"
    assert colour_at(editor, 5, 11) == QColor(colors.keyword).name()        # APCSetRunMode
    assert colour_at(editor, 5, 25) == QColor(colors.parameter).name()      # APC_DISABLE
    assert colour_at(editor, 8, 33) == QColor(colors.parameter).name()      # #18.11
    assert colour_at(editor, 4, 1) == QColor(colors.keyword).name()         # the task name
    editor.goto_line(8, col=10)
    rect = editor.cursorRect()
    tip = editor.tooltip_at(QPoint(rect.left() + 2, rect.center().y()))
    assert tip and "(Value%, Status%) = APCReadPar(Par%)" in tip and "L2529" in tip
    names = [i.name for i in editor.lang.completion_items(editor.toPlainText())]
    assert {"APCReadPar", "APC_FB_POS", "Pos%", "ELSEIF"} <= set(names)


def test_f4_checks_a_dpl_program_with_gcc_style_messages(window, tmp_path, qtbot):
    path = tmp_path / "bad.dpl"
    path.write_text("Pos0{\nx% = APCSetRunMode(APC_DI SABLE)\n}\n", encoding="utf-8")
    editor = window.open_file(path)
    qtbot.keyClick(editor, Qt.Key.Key_F4)
    assert f"{path}:2:27: error: expected ')' closing the arguments of APCSetRunMode, found 'SABLE'" \
        in window.messages.toPlainText()
    assert editor.caret_line_col() == (2, 27)
    assert [(d[0], d[2]) for d in editor.diagnostics()] == [(2, "error")]


def test_the_manuals_programs_check_clean_in_the_editor(window, qtbot):
    editor = window.open_file(PROGRAMS / "s7_5_ctsync_master.dpl")
    qtbot.keyClick(editor, Qt.Key.Key_F4)
    assert "Syntax check: no errors" in window.messages.toPlainText()


def test_saving_as_dpl_switches_the_language(window, tmp_path):
    editor = window.new_file()
    editor.setPlainText(SOURCE)
    assert editor.language == "aposs"
    window.save(editor=editor, path=tmp_path / "renamed.dpl")
    assert editor.language == "dpl"
    window.live_check()
    assert editor.diagnostics() == []


def test_the_outline_lists_tasks_and_labels(window, tmp_path):
    path = tmp_path / "o.dpl"
    path.write_text(SOURCE.replace("Pos0{\n", "Pos0{\nloop:\n") + "Background{\ntop:\ngoto top:\n}\n",
                    encoding="utf-8")
    editor = window.open_file(path)
    assert [(i.kind, i.name, i.line) for i in editor.outline()] == [
        ("task", "Notes", 1), ("task", "Initial", 4), ("task", "Pos0", 7), ("label", "loop", 8),
        ("task", "Background", 11), ("label", "top", 12)]
    window.live_check()
    assert window.outline.item(0).text() == "task: Notes  (1)"
