"""The debugger and the watch on the manual's Hello.m (ide-spec 3.1-3.13, scenarios S12 and S13)."""

from PySide6.QtCore import QPoint, Qt

from motiontool.ui.editor.debug_marks import DOT_BLUE, DOT_RED

HELLO = """// Hello.m
DIM arr[100]
i = 1
while (i <= 5) do
  print "Hello: ",i
  delay 500
  i = i + 1
endwhile
print "Good bye."
"""


def _prepare(window, qtbot):
    editor = window.new_file()
    editor.setPlainText(HELLO)
    assert window.debugger.prepare()
    qtbot.waitUntil(lambda: editor.debug.debug_current == 3, timeout=5000)
    return editor


def _dots(editor):
    doc = editor.document()
    return {n + 1: editor.debug.debug_dot(doc.findBlockByNumber(n)) for n in range(doc.blockCount())
            if editor.debug.debug_dot(doc.findBlockByNumber(n))}


def _point_at(editor, line, col):
    cursor = editor.textCursor()
    cursor.setPosition(editor.document().findBlockByNumber(line - 1).position() + col - 1)
    return editor.cursorRect(cursor).center() + QPoint(1, 0)


def test_prepare_singlestep_marks_statements_and_stops_before_the_first(window, qtbot):
    """DG L3364-3382: "The program is compiled in debug mode and downloaded to the controller. However,
    program execution is not started"; "A blue dot is placed before each executable statement"; "The next
    statement to be executed … will be highlighted in yellow"; the pane shows "Compiling debug ok (N bytes)
    Loading N bytes ok Prepare stepping ok"."""
    editor = _prepare(window, qtbot)
    assert _dots(editor) == {3: DOT_BLUE, 4: DOT_BLUE, 5: DOT_BLUE, 6: DOT_BLUE, 7: DOT_BLUE, 9: DOT_BLUE}
    text = window.messages.toPlainText()
    assert "Compiling debug ok (" in text and "Prepare stepping ok" in text
    size = text.split("Compiling debug ok (")[1].split(" bytes")[0]
    assert f"Loading {size} bytes ok" in text
    assert window.bridge.link.status().program_state == "break"
    assert "Hello" not in text  # not started
    assert editor.isReadOnly()


def test_breakpoint_go_step_inspect_change_and_end(window, qtbot):
    """S12: a breakpoint on the print line, Go stops there, F9 moves to delay; clicking `i` shows 1; setting
    i to 50 ends the loop; an 11th breakpoint is refused; End Debug keeps the red dots (DG L3390-3430)."""
    editor = _prepare(window, qtbot)
    qtbot.mouseDClick(editor.viewport(), Qt.MouseButton.LeftButton, pos=_point_at(editor, 5, 4))
    assert editor.debug.breakpoints() == [5]
    assert _dots(editor)[5] == DOT_RED
    window.actions_by_text["Go"].trigger()
    qtbot.waitUntil(lambda: editor.debug.debug_current == 5, timeout=5000)
    qtbot.keyClick(editor, Qt.Key.Key_F9)
    qtbot.waitUntil(lambda: editor.debug.debug_current == 6, timeout=5000)
    qtbot.waitUntil(lambda: "Hello: 1" in window.messages.toPlainText(), timeout=5000)
    assert editor.debug.variable_at(_point_at(editor, 7, 3)) == "i"
    assert window.debugger.read_value("i") == "1"
    assert window.debugger.write_value("i", "50")
    window.actions_by_text["Go"].trigger()
    qtbot.waitUntil(lambda: "Good bye." in window.messages.toPlainText(), timeout=5000)
    assert "Hello: 2" not in window.messages.toPlainText()
    # at most 10 breakpoints (DG L3430): fill with the executable lines, then one more is refused
    for line in (3, 4, 6, 7, 9):
        assert editor.debug.toggle_breakpoint(line) is None
    assert len(editor.debug.breakpoints()) == 6
    assert editor.debug.toggle_breakpoint(2) is not None  # DIM: no blue dot, no breakpoint
    window.actions_by_text["End Debug"].trigger()
    assert not editor.isReadOnly()
    assert set(_dots(editor).values()) == {DOT_RED}
    assert editor.debug.breakpoints() == [3, 4, 5, 6, 7, 9]


def test_an_eleventh_breakpoint_is_refused(window, qtbot):
    editor = window.new_file()
    editor.setPlainText("".join(f"x{n} = {n}\n" for n in range(12)))
    assert window.debugger.prepare()
    refusals = [editor.debug.toggle_breakpoint(line) for line in range(1, 12)]
    assert refusals[:10] == [None] * 10
    assert "at most 10" in refusals[10]
    window.debugger.end()


def test_watch_variable_array_element_and_process_data(window, qtbot):
    """S13 / DG L2452-2477: Watch Add a variable, an array element (index limited to 250) and axis process
    data; Watch Start refreshes; Delete removes the selected entry."""
    from motiontool.ui.watch import WatchAddDialog

    editor = window.new_file()
    editor.setPlainText("DIM arr[300]\narr[3] = 7\ni = 0\nagain:\ni = i + 1\nDELAY 10\nGOTO again\n")
    assert window.debugger.prepare()
    pane = window.debugger.watch
    dialog = WatchAddDialog(pane)
    qtbot.addWidget(dialog)
    dialog.program.setCurrentRow(dialog.program.count() - 1)  # arr[300]
    assert dialog.index.isEnabled() and dialog.index.maximum() == 250
    dialog.index.setValue(3)
    dialog.add_button.click()
    dialog.program.setCurrentRow(0)
    assert dialog.program.currentItem().text() == "i" and not dialog.index.isEnabled()
    dialog.add_button.click()
    apos = dialog.system.topLevelItem(0).child(0)
    dialog.program.clearSelection()
    dialog.system.setCurrentItem(apos)
    dialog.add_button.click()
    assert [e.key for e in pane.entries] == ["arr[3]", "i", "APOS"]
    window.debugger.go()
    window.debugger.watch_start()
    qtbot.waitUntil(lambda: pane.values()[0] == "7" and int(pane.values()[1] or 0) > 3, timeout=5000)
    window.debugger.watch_stop()
    pane.table.selectRow(2)
    pane.table.setFocus()
    qtbot.keyClick(pane.table, Qt.Key.Key_Delete)
    assert [e.key for e in pane.entries] == ["arr[3]", "i"]
    window.debugger.end()
