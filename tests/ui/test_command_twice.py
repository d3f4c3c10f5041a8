"""A command's button clicked again, or its shortcut pressed again, while the command waits for the controller does
not run it a second time (decision I34; found under Xvfb on a 9600-baud line: Prepare Singlestep clicked again
during its debug download was compiled, downloaded and prepared again once the first had ended). The download is
held on the line (tests/ui/gui_thread_check.py) while the user clicks or presses the key, 120 ms apart."""

from __future__ import annotations

import threading

import pytest
from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import QToolBar, QToolButton

from tests.modal import answering
from tests.ui.gui_thread_check import HOLD, RECORD, checking, click, connect, program, said

PACE_MS = 120


@pytest.fixture
def checked(window):
    yield from checking(window)


def toolbar_button(w, text: str):
    action = w.actions_by_text[text]
    for bar in w.findChildren(QToolBar):
        if (button := bar.widgetForAction(action)) is not None:
            return button
    raise AssertionError(f"no toolbar button for {text}")


def held_download(qtbot, again, op: str = "download"):
    """Holds the next `op` request until `again()` was done twice at a human pace, then lets it through."""
    arrived, through = threading.Event(), threading.Event()
    HOLD[op] = (arrived, through)
    presses = [0]

    def look() -> None:
        if not arrived.is_set():
            QTimer.singleShot(20, look)
            return
        if presses[0] < 2:
            presses[0] += 1
            again()
            QTimer.singleShot(PACE_MS, look)
            return
        through.set()

    QTimer.singleShot(0, look)
    return through, presses


def downloads(kind: str = "download") -> int:
    return sum(op == kind for op, _ in RECORD.taken())


def test_prepare_singlestep_clicked_again_while_it_downloads_runs_once(checked, qtbot, tmp_path):
    connect(qtbot, checked)
    program(checked, tmp_path)
    button = toolbar_button(checked, "Prepare Singlestep")
    RECORD.clear()
    through, presses = held_download(qtbot, lambda: qtbot.mouseClick(button, Qt.MouseButton.LeftButton))
    try:
        qtbot.mouseClick(button, Qt.MouseButton.LeftButton)
    finally:
        through.set()
    said(qtbot, checked, "Prepare stepping ok")
    qtbot.wait(3 * PACE_MS)        # a click that was kept would run now
    assert presses[0] == 2
    assert downloads() == 1, RECORD.taken()


def test_execute_pressed_again_while_it_downloads_runs_once(checked, qtbot, tmp_path):
    connect(qtbot, checked)
    program(checked, tmp_path)
    editor = checked.current_editor()
    editor.setFocus()
    RECORD.clear()
    through, presses = held_download(qtbot, lambda: qtbot.keyClick(editor, Qt.Key.Key_F5))
    try:
        qtbot.keyClick(editor, Qt.Key.Key_F5)
    finally:
        through.set()
    said(qtbot, checked, "ran 1")
    qtbot.wait(3 * PACE_MS)
    assert presses[0] == 2
    assert downloads() == 1, RECORD.taken()
    assert checked.messages.toPlainText().count("ran 1") == 1


def test_programs_start_clicked_again_while_it_starts_runs_once(checked, qtbot, tmp_path):
    """Controller > Programs is a dialog of its own: its Start clicked again while the start waits."""
    connect(qtbot, checked)
    program(checked, tmp_path)
    outcome = checked.development.compile_current()       # set-up: program 0 stored on the controller
    checked.bridge.link.download(outcome.result.image.to_bytes(), number=0, name="ran")
    RECORD.clear()
    held: list = []

    def start_twice(dialog) -> None:
        qtbot.waitUntil(lambda: dialog.table.rowCount() == 1, timeout=20_000)
        rect = dialog.table.visualItemRect(dialog.table.item(0, 0))
        qtbot.mouseClick(dialog.table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
        start = dialog.buttons["Start"]
        held.extend(held_download(qtbot, lambda: click(qtbot, start), op="start"))
        try:
            click(qtbot, start)
        finally:
            held[0].set()
        click(qtbot, dialog.buttons["Close"])

    with answering(qtbot, start_twice, timeout=20_000):
        checked.actions_by_text["Programs..."].trigger()
    said(qtbot, checked, "ran 1")
    qtbot.wait(3 * PACE_MS)
    assert held[1][0] == 2
    assert downloads("start") == 1, RECORD.taken()


def test_scope_start_clicked_again_while_it_starts_runs_once(checked, qtbot):
    """The oscilloscope's Start (DG 4620-4627) waits for the controller's answer to the stream request like the
    IDE's commands (scope/ui/poll_job.wait is link_jobs.waiting since motiontool.qtjobs): Start clicked again
    meanwhile is dropped. On 9b7b607 (the scope's wait without the guard) the stream was asked 3 times."""
    connect(qtbot, checked)
    checked.actions_by_text["Oscilloscope"].trigger()
    scope = checked._scopes[-1]
    scope.ask = False
    scope.add_signal_curve("APOS", group="Test Group (Free Run)")   # set-up: a curve to record
    start = next(b for b in scope.findChildren(QToolButton) if b.defaultAction() is scope.start_action)
    RECORD.clear()
    through, presses = held_download(qtbot, lambda: click(qtbot, start), op="stream")
    try:
        click(qtbot, start)
    finally:
        through.set()
    qtbot.waitUntil(lambda: scope.run.running, timeout=20_000)
    qtbot.wait(3 * PACE_MS)        # a click that was kept would run now
    assert presses[0] == 2
    assert downloads("stream") == 1, RECORD.taken()
    scope.stop_action.trigger()
    scope.close()
