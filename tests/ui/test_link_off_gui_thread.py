"""The rule of issue 27 item 2: no link request from the IDE runs on the GUI thread. On a 9600-baud line one
exchange takes a quarter of a second or more, and a request asked on the GUI thread stops the window that long.

The IDE's default interface here is a link scheme (gui_thread_check.py) whose every request notes whether it ran on
the GUI thread. Each case drives one user action as a user does (menu actions, clicks, dialogs answered) and then
names the requests that action made on the GUI thread. An action not yet moved off the GUI thread is marked
xfail(strict): the list of marks is what remains of the item. The tools' windows (CAM and Array editors, the
scope's TESTSETP and Tune, Restart) have their cases in test_link_off_gui_thread_tools.py.
"""

from __future__ import annotations

import threading
import time

import pytest
from PySide6.QtCore import QPoint, Qt, QTimer
from PySide6.QtGui import QContextMenuEvent
from PySide6.QtWidgets import QApplication, QMenu, QMessageBox, QToolButton

from tests.modal import answering, button_reply, cancel_reply, file_reply, ok_reply, text_reply
from tests.ui.gui_thread_check import (
    HOLD,
    RECORD,
    Case,
    checking,
    click,
    connect,
    no_request_on_the_gui_thread,
    params,
    program,
    said,
)


@pytest.fixture
def checked(window):
    yield from checking(window)


# --- the actions --------------------------------------------------------------------------------------------------
def select_controller(qtbot, w, tmp_path) -> None:
    def choose(dialog) -> None:
        tree = dialog.tree
        item = next(tree.topLevelItem(0).child(j) for j in range(tree.topLevelItem(0).childCount())
                    if tree.topLevelItem(0).child(j).text(0) == "Controller 2")
        qtbot.mouseClick(tree.viewport(), Qt.MouseButton.LeftButton, pos=tree.visualItemRect(item).center())
        click(qtbot, dialog.buttons.button(dialog.buttons.StandardButton.Ok))

    with answering(qtbot, choose, timeout=20_000):
        w.actions_by_text["Select Controller..."].trigger()
    qtbot.waitUntil(lambda: w.bridge.connected and w.bridge.controller_id == 2, timeout=20_000)


def connect_with_esc(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    said(qtbot, w, "Connected to controller 1")


def execute(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    program(w, tmp_path)
    RECORD.clear()
    w.actions_by_text["Execute"].trigger()
    said(qtbot, w, "ran 1")


def download_all(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    program(w, tmp_path)
    RECORD.clear()

    def start(dialog) -> None:
        click(qtbot, dialog.buttons["Start"])
        qtbot.waitUntil(lambda: "Done for controllers: 1" in dialog.log.toPlainText(), timeout=20_000)
        click(qtbot, dialog.buttons["Close"])

    with answering(qtbot, start, timeout=20_000):
        w.actions_by_text["Download all"].trigger()


def programs(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    RECORD.clear()

    def close(dialog) -> None:
        qtbot.waitUntil(lambda: dialog.table.rowCount() >= 0 and dialog.isVisible(), timeout=20_000)
        click(qtbot, dialog.buttons["Close"])

    with answering(qtbot, close, timeout=20_000):
        w.actions_by_text["Programs..."].trigger()


def reset_arrays(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    RECORD.clear()
    with answering(qtbot, button_reply(QMessageBox.StandardButton.Yes), timeout=20_000):
        w.actions_by_text["Arrays..."].trigger()
    said(qtbot, w, "reset arrays done")


def save_ram(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    RECORD.clear()
    with answering(qtbot, button_reply(QMessageBox.StandardButton.Yes), timeout=20_000):
        w.actions_by_text["Save RAM"].trigger()
    said(qtbot, w, "Save RAM done")


def diagnostic_report(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    RECORD.clear()
    with answering(qtbot, file_reply(tmp_path / "report.txt"), timeout=20_000):
        w.actions_by_text["Diagnostic Report..."].trigger()
    said(qtbot, w, "diagnostic report written")


def save_parameters(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    RECORD.clear()
    with answering(qtbot, file_reply(tmp_path / "backup.zbc"), timeout=20_000):
        w.actions_by_text["Save to file..."].trigger()
    qtbot.waitUntil(lambda: (tmp_path / "backup.zbc").exists(), timeout=20_000)


def axis_parameters(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    RECORD.clear()

    def read_then_cancel(dialog) -> None:
        qtbot.waitUntil(lambda: dialog.waiting == 0 and dialog.ok.isEnabled(), timeout=20_000)
        cancel_reply(dialog)

    with answering(qtbot, read_then_cancel, timeout=20_000):
        w.actions_by_text["Axis..."].trigger()


def watch(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)

    def choose(dialog) -> None:
        group = dialog.system.topLevelItem(1)
        next(group.child(k) for k in range(group.childCount()) if group.child(k).text(0) == "KPROP").setSelected(True)
        click(qtbot, dialog.add_button)

    with answering(qtbot, ok_reply(choose), timeout=20_000):
        w.actions_by_text["Watch Add"].trigger()
    pane = w.debugger.watch
    RECORD.clear()
    w.actions_by_text["Watch Start"].trigger()
    qtbot.waitUntil(lambda: pane.values()[0] == "30", timeout=20_000)
    w.actions_by_text["Watch Stop"].trigger()
    qtbot.waitUntil(lambda: pane.jobs.pending == 0, timeout=20_000)


def error_history(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    RECORD.clear()

    def close(dialog) -> None:
        qtbot.waitUntil(lambda: any(op == "error_history" for op, _ in RECORD.taken()), timeout=20_000)
        cancel_reply(dialog)

    with answering(qtbot, close, timeout=20_000):
        w.actions_by_text["Error History..."].trigger()


def scope_start_stop(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    w.actions_by_text["Oscilloscope"].trigger()
    scope = w._scopes[-1]
    scope.add_signal_curve("4119", group="Test Group (Free Run)")
    RECORD.clear()
    start = next(b for b in scope.findChildren(QToolButton) if b.defaultAction() is scope.start_action)
    stop = next(b for b in scope.findChildren(QToolButton) if b.defaultAction() is scope.stop_action)
    click(qtbot, start)
    qtbot.waitUntil(lambda: len(scope.scope.curves[0].buffer) > 5, timeout=20_000)
    click(qtbot, stop)
    qtbot.waitUntil(lambda: not scope.run.running, timeout=20_000)
    scope.ask = False
    scope.close()


def scope_single_shot(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    w.actions_by_text["Oscilloscope"].trigger()
    scope = w._scopes[-1]
    with answering(qtbot, ok_reply(), timeout=20_000):   # the recording dialog, as it is
        scope.mode_actions["single_shot"].trigger()
    scope.add_signal_curve("4119", group="Test Group (Single Shot)")
    RECORD.clear()
    start = next(b for b in scope.findChildren(QToolButton) if b.defaultAction() is scope.start_action)
    stop = next(b for b in scope.findChildren(QToolButton) if b.defaultAction() is scope.stop_action)
    click(qtbot, start)
    qtbot.waitUntil(lambda: scope.run.single_shot is not None and scope.run.single_shot.running, timeout=20_000)
    click(qtbot, stop)
    qtbot.waitUntil(lambda: not scope.run.running and len(scope.scope.curves[0].buffer) > 0, timeout=20_000)
    scope.ask = False
    scope.close()


# --- the debugger (DG L3364-3459) --------------------------------------------------------------------------------
def debugging(qtbot, w, tmp_path):
    """Prepare Singlestep on PROGRAM: stopped before line 1 (`x = 1`); the requests so far are forgotten."""
    connect(qtbot, w)
    program(w, tmp_path)
    editor = w.current_editor()
    w.actions_by_text["Prepare Singlestep"].trigger()
    qtbot.waitUntil(lambda: editor.debug.debug_current == 1, timeout=20_000)
    RECORD.clear()
    return editor


def at(editor, line: int, col: int) -> QPoint:
    cursor = editor.textCursor()
    cursor.setPosition(editor.document().findBlockByNumber(line - 1).position() + col - 1)
    return editor.cursorRect(cursor).center() + QPoint(1, 0)


def step_to_print(qtbot, w, editor) -> None:
    editor.setFocus()
    qtbot.keyClick(editor, Qt.Key.Key_F9)
    qtbot.waitUntil(lambda: editor.debug.debug_current == 2, timeout=20_000)


def prepare_singlestep(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    program(w, tmp_path)
    RECORD.clear()
    w.actions_by_text["Prepare Singlestep"].trigger()
    said(qtbot, w, "Prepare stepping ok")


def breakpoint_go(qtbot, w, tmp_path) -> None:
    """Double-click line 2 (a breakpoint, sent at once), then Go stops there (DG L3408-3418, L2436-2438)."""
    editor = debugging(qtbot, w, tmp_path)
    qtbot.mouseClick(editor.viewport(), Qt.MouseButton.LeftButton, pos=at(editor, 2, 2))
    qtbot.mouseDClick(editor.viewport(), Qt.MouseButton.LeftButton, pos=at(editor, 2, 2))
    assert editor.debug.breakpoints() == [2]
    w.actions_by_text["Go"].trigger()
    qtbot.waitUntil(lambda: editor.debug.debug_current == 2, timeout=20_000)


def singlestep(qtbot, w, tmp_path) -> None:
    step_to_print(qtbot, w, debugging(qtbot, w, tmp_path))


def variable_value(qtbot, w, tmp_path) -> None:
    """A left click on `x` shows its value in the yellow popup (DG L3440-3444)."""
    editor = debugging(qtbot, w, tmp_path)
    step_to_print(qtbot, w, editor)
    RECORD.clear()
    qtbot.mouseClick(editor.viewport(), Qt.MouseButton.LeftButton, pos=at(editor, 2, 15))
    qtbot.waitUntil(lambda: editor.debug.value_popup is not None and editor.debug.value_popup.text() == "x = 1",
                    timeout=20_000)


def change_value(qtbot, w, tmp_path) -> None:
    """Right-click `x`, Change value of x..., type 5: the program prints it (DG L3457-3459)."""
    editor = debugging(qtbot, w, tmp_path)
    step_to_print(qtbot, w, editor)
    RECORD.clear()

    def choose() -> None:
        menu = QApplication.activePopupWidget()
        if not isinstance(menu, QMenu):       # the menu asks the value before it opens
            QTimer.singleShot(50, choose)
            return
        action = next(a for a in menu.actions() if a.text().startswith("Change value of x"))
        qtbot.mouseClick(menu, Qt.MouseButton.LeftButton, pos=menu.actionGeometry(action).center())

    pos = at(editor, 2, 15)
    with answering(qtbot, text_reply("5"), timeout=20_000):
        QTimer.singleShot(150, choose)
        QApplication.sendEvent(editor.viewport(), QContextMenuEvent(QContextMenuEvent.Reason.Mouse, pos,
                                                                    editor.viewport().mapToGlobal(pos)))
    w.actions_by_text["Singlestep"].trigger()      # the dialog took the focus: the menu's entry, not F9
    said(qtbot, w, "ran 5")


def end_debug(qtbot, w, tmp_path) -> None:
    debugging(qtbot, w, tmp_path)
    w.actions_by_text["End Debug"].trigger()
    said(qtbot, w, "Debug ended")


def every_controller(entry: str, says: str):
    """Development ▸ Break all / Start all / Delete Programs all: Break all and Delete Programs all reach 1 and 2
    (the scan found both), Start all the open one (F24)."""
    def act(qtbot, w, tmp_path) -> None:
        connect(qtbot, w)
        RECORD.clear()
        w.actions_by_text[entry].trigger()
        said(qtbot, w, says)
    return act


CASES = {
    "Select Controller": Case(select_controller),
    "connect (Esc)": Case(connect_with_esc),
    "Execute": Case(execute),
    "Download all": Case(download_all),
    "Programs": Case(programs),
    "Break all": Case(every_controller("Break all", "Break all: ")),
    "Start all": Case(every_controller("Start all", "Start all: ")),
    "Delete Programs all": Case(every_controller("Delete Programs all", "Delete Programs all: ")),
    "Reset > Arrays": Case(reset_arrays),
    "Memory > Save RAM": Case(save_ram),
    "Diagnostic Report": Case(diagnostic_report),
    "Parameters > Save to file": Case(save_parameters),
    "Parameters > Axis": Case(axis_parameters),
    "Watch": Case(watch),
    "Error History": Case(error_history),
    "Oscilloscope Start/Stop": Case(scope_start_stop),
    "Oscilloscope Single Shot Start/Stop": Case(scope_single_shot),
    "Prepare Singlestep": Case(prepare_singlestep),
    "Breakpoint and Go": Case(breakpoint_go),
    "Singlestep": Case(singlestep),
    "Variable value": Case(variable_value),
    "Change value": Case(change_value),
    "End Debug": Case(end_debug),
}


@pytest.mark.parametrize("name", list(params(CASES)))
def test_no_link_request_of_the_action_runs_on_the_gui_thread(checked, qtbot, tmp_path, name):
    CASES[name].action(qtbot, checked, tmp_path)
    no_request_on_the_gui_thread(name)


def test_the_recorder_sees_a_request_on_the_gui_thread(checked):
    """The rule can fail: a request asked directly from the test (the GUI thread) is noted as such."""
    link = checked.controllers.link(1)
    link.status()
    assert ("status", True) in RECORD.taken()


def test_while_execute_waits_for_its_download_the_window_paints_and_says_so(checked, qtbot, tmp_path):
    """Execute with its download held on the line: a 20 ms timer of the window keeps firing, the status bar says
    what it waits for and the cursor is busy; when the answer comes, the program runs and both are gone."""
    connect(qtbot, checked)
    program(checked, tmp_path)
    arrived, through = threading.Event(), threading.Event()
    HOLD["download"] = (arrived, through)
    ticks: list[float] = []
    seen: dict[str, object] = {}
    timer = QTimer(checked, interval=20, timeout=lambda: ticks.append(time.monotonic()))

    def look() -> None:
        if not arrived.is_set():
            QTimer.singleShot(20, look)
            return
        if "message" not in seen:
            seen["message"] = checked.statusBar().currentMessage()
            cursor = QApplication.overrideCursor()
            seen["cursor"] = cursor.shape() if cursor is not None else None
            seen["ticks"] = len(ticks)
            seen["held_at"] = time.monotonic()
        if time.monotonic() - seen["held_at"] < 0.5:    # the download stays on the line half a second
            QTimer.singleShot(20, look)
            return
        seen["ticks while held"] = len(ticks) - seen["ticks"]
        through.set()

    timer.start()
    QTimer.singleShot(0, look)
    try:
        checked.actions_by_text["Execute"].trigger()
    finally:
        through.set()
        timer.stop()
    said(qtbot, checked, "ran 1")
    assert seen["message"] == "Controller 1: downloading ran …"
    assert seen["cursor"] == Qt.CursorShape.BusyCursor
    assert seen["ticks while held"] >= 5, seen     # 25 at 20 ms; a window that stood still has none
    assert QApplication.overrideCursor() is None and checked.statusBar().currentMessage() == ""


def test_while_prepare_singlestep_downloads_the_window_says_so(checked, qtbot, tmp_path):
    """Prepare Singlestep with its debug download held on the line: the status bar names it, the cursor is busy;
    both are gone once the program stands before its first statement."""
    connect(qtbot, checked)
    program(checked, tmp_path)
    arrived, through = threading.Event(), threading.Event()
    HOLD["download"] = (arrived, through)
    seen: dict[str, object] = {}

    def look() -> None:
        if not arrived.is_set():
            QTimer.singleShot(20, look)
            return
        seen["message"] = checked.statusBar().currentMessage()
        cursor = QApplication.overrideCursor()
        seen["cursor"] = cursor.shape() if cursor is not None else None
        through.set()

    QTimer.singleShot(0, look)
    try:
        checked.actions_by_text["Prepare Singlestep"].trigger()
    finally:
        through.set()
    said(qtbot, checked, "Prepare stepping ok")
    assert seen == {"message": "Controller 1: downloading ran for debugging …", "cursor": Qt.CursorShape.BusyCursor}
    assert QApplication.overrideCursor() is None and checked.statusBar().currentMessage() == ""
