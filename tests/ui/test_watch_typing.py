"""A value typed into the Watch while the answer to the previous one is still on its way (DG L2452-2467: "the
value can be changed" in the Watch). The answer used to reset the open editor to the controller's old value, so
Enter wrote nothing and the typed text was lost (a clean-clone run at load 10 failed the Watch test this way)."""

from __future__ import annotations

import threading

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QAbstractItemView, QLineEdit

from motiontool.ui.watch import WatchAddDialog
from tests.modal import answering, ok_reply


def open_editor(qtbot, table, row: int) -> QLineEdit:
    rect = table.visualItemRect(table.item(row, 1))
    qtbot.mouseClick(table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
    qtbot.mouseDClick(table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
    return next(w for w in table.findChildren(QLineEdit) if w.isVisible())


def enter(qtbot, table, line: QLineEdit) -> None:
    qtbot.keyClick(line, Qt.Key.Key_Return)
    qtbot.waitUntil(lambda: table.state() != QAbstractItemView.State.EditingState, timeout=3000)  # Qt closes later


def test_a_value_typed_while_the_previous_write_is_answered_is_written_and_the_refusal_shows(window, qtbot):
    editor = window.new_file()
    editor.setPlainText("i = 0\nagain:\ni = i + 1\nDELAY 10\nGOTO again\n")
    window.actions_by_text["Prepare Singlestep"].trigger()

    def choose(dialog):
        assert isinstance(dialog, WatchAddDialog)
        group = dialog.system.topLevelItem(1)
        next(group.child(k) for k in range(group.childCount()) if group.child(k).text(0) == "KPROP").setSelected(True)
        dialog.add_button.click()

    with answering(qtbot, ok_reply(choose)):
        window.actions_by_text["Watch Add"].trigger()
    pane = window.debugger.watch
    window.actions_by_text["Watch Start"].trigger()
    qtbot.waitUntil(lambda: pane.values()[0] != "", timeout=3000)
    window.actions_by_text["Watch Stop"].trigger()     # no poll in flight: pending 0 = every answer delivered
    qtbot.waitUntil(lambda: pane.jobs.pending == 0, timeout=3000)
    gate, answered = threading.Event(), threading.Event()
    written = window.debugger.write_watch

    def slow_line(kind, key, text):
        gate.wait(10)
        try:
            return written(kind, key, text)
        finally:
            answered.set()

    pane.set_writer(slow_line)

    line = open_editor(qtbot, pane.table, 0)
    line.selectAll()
    qtbot.keyClicks(line, "55")
    enter(qtbot, pane.table, line)
    line = open_editor(qtbot, pane.table, 0)          # the next value, typed before 55 is answered
    line.selectAll()
    qtbot.keyClicks(line, "-4")
    gate.set()
    qtbot.waitUntil(lambda: answered.is_set() and pane.jobs.pending == 0, timeout=3000)  # 55's answer is in
    assert window.bridge.link.read_parameter("KPROP") == 55
    assert line.isVisible() and line.text() == "-4"
    enter(qtbot, pane.table, line)
    qtbot.waitUntil(lambda: "outside" in pane.table.item(0, 1).toolTip(), timeout=3000)
    assert window.bridge.link.read_parameter("KPROP") == 55
    window.debugger.end()
