"""The rule of issue 27 item 2 (test_link_off_gui_thread.py) for the tools' windows and the commands that connect
first: the CAM editor's and the Array Editor's transfers, Clear Error and Restart on a window whose controller is
not connected yet, the scope's TESTSETP list and upload and Tune's run. Each case drives the action as a user does
and names the link requests it made on the GUI thread; one still made there is xfail(strict)."""

from __future__ import annotations

import threading

import pytest
from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QContextMenuEvent
from PySide6.QtWidgets import QApplication, QLineEdit, QMenu, QMessageBox

from tests.modal import answering, button_reply
from tests.ui.gui_thread_check import (
    HOLD,
    RECORD,
    Case,
    checking,
    click,
    connect,
    no_request_on_the_gui_thread,
    params,
    said,
)


@pytest.fixture
def checked(window):
    yield from checking(window)


# --- CAM editor (DG L3579, ide-spec 4.3) --------------------------------------------------------------------------
def cam_editor(qtbot, w):
    connect(qtbot, w)
    w.actions_by_text["CAM-Editor"].trigger()
    editor = w.cam_editor
    qtbot.waitExposed(editor)
    RECORD.clear()
    return editor


def cam_read(qtbot, w, tmp_path) -> None:
    editor = cam_editor(qtbot, w)
    editor.actions_by_name["read"].trigger()
    assert editor.parameters, editor.message_line.text()     # the controller's parameters are the editor's now


def cam_write(qtbot, w, tmp_path) -> None:
    """Read first: a new editor holds no parameters and would send nothing."""
    editor = cam_editor(qtbot, w)
    editor.actions_by_name["read"].trigger()
    assert editor.parameters
    RECORD.clear()
    with answering(qtbot, button_reply(QMessageBox.StandardButton.Yes), timeout=20_000):
        editor.actions_by_name["write"].trigger()
    assert editor.message_line.text() == "Parameters and arrays written to the controller"


# --- Array Editor (DG L4088-4253) ---------------------------------------------------------------------------------
def array_editor(qtbot, w, tmp_path) -> None:
    """Tools ▸ Array Editor reads the window's controller at once (DG L4088-4109)."""
    connect(qtbot, w)
    RECORD.clear()
    w.actions_by_text["Array Editor"].trigger()
    assert w._array_editor.data_list.rows


def array_write(qtbot, w, tmp_path) -> None:
    """KPROP typed into its Value cell, then Write to controller (DG L4193-4253)."""
    from motiontool.arrayeditor.ui.editor import VALUE

    connect(qtbot, w)
    w.actions_by_text["Array Editor"].trigger()
    editor = w._array_editor
    qtbot.waitExposed(editor)
    editor.selection_box.setCurrentText("Axis 1")
    model = editor.model
    r = next(r for r in range(model.rowCount()) if editor.data_list.label(model.row_at(r)).startswith("Axis 1 3260"))
    index = model.index(r, VALUE)
    editor.table.scrollTo(index)
    cell = editor.table.visualRect(index).center()
    qtbot.mouseClick(editor.table.viewport(), Qt.MouseButton.LeftButton, pos=cell)
    qtbot.mouseDClick(editor.table.viewport(), Qt.MouseButton.LeftButton, pos=cell)
    qtbot.waitUntil(lambda: cell_editor(editor.table) is not None, timeout=20_000)
    field = cell_editor(editor.table)
    field.selectAll()
    qtbot.keyClicks(field, "45", delay=20)
    qtbot.keyClick(field, Qt.Key.Key_Return)
    qtbot.waitUntil(lambda: model.row_at(r).pending == 45, timeout=20_000)
    RECORD.clear()
    editor.actions_by_text["Write to controller"].trigger()
    assert any(op == "write_parameter" for op, _ in RECORD.taken())


def cell_editor(table) -> QLineEdit | None:
    return next((e for e in table.viewport().findChildren(QLineEdit) if e.isVisible()), None)


# --- commands that connect first (DG 2054-2066) --------------------------------------------------------------------
def clear_error(qtbot, w, tmp_path) -> None:
    w.actions_by_text["Clear Error"].trigger()
    said(qtbot, w, "Controller 1: error cleared")


def restart(qtbot, w, tmp_path) -> None:
    with answering(qtbot, button_reply(QMessageBox.StandardButton.Yes), timeout=20_000):
        w.actions_by_text["Restart..."].trigger()
    said(qtbot, w, "Controller 1: restarted (switched off and on)")


# --- the scope ---------------------------------------------------------------------------------------------------
def scope_opens(qtbot, w, tmp_path) -> None:
    """Tools ▸ Oscilloscope: the curve list shows the controller's state (connected) from the start."""
    connect(qtbot, w)
    qtbot.waitUntil(lambda: w.bridge.last_status is not None, timeout=20_000)
    RECORD.clear()
    w.actions_by_text["Oscilloscope"].trigger()
    scope = w._scopes[-1]
    scope.ask = False
    qtbot.waitUntil(lambda: scope.list.controller_state == "connected", timeout=20_000)
    qtbot.waitUntil(lambda: bool(RECORD.taken()), timeout=20_000)     # the IDE's status poll, at least
    scope.close()


# --- the scope's TESTSETP (DG 5326-5347) ---------------------------------------------------------------------------
RECORDS = ("DIM test[3000]\nTESTSETP 1 4097 4098 0x01270001 test\nTESTSTART 0\nPOSA 2000\nDELAY 1500\nTESTSTOP 0\n"
           "PRINT \"recorded\"\n")


def recorded(qtbot, w, tmp_path) -> None:
    connect(qtbot, w)
    editor = w.current_editor() or w.new_file()
    editor.setPlainText(RECORDS)
    w.save(editor=editor, path=tmp_path / "records.m")
    w.actions_by_text["Execute"].trigger()
    said(qtbot, w, "recorded")
    w.actions_by_text["Oscilloscope"].trigger()
    scope = w._scopes[-1]
    scope.ask = False
    return scope


def scope_testsetp(qtbot, w, tmp_path) -> None:
    """A program records with TESTSETP; the scope's TESTSETP variant lists the recordings and uploads the newest."""
    scope = recorded(qtbot, w, tmp_path)
    RECORD.clear()
    scope.mode_actions["testsetp"].trigger()
    qtbot.waitUntil(lambda: len(scope.scope.curves) == 3, timeout=20_000)   # REG_ACTPOS, REG_COMPOS, the SYSVAR
    scope.close()


def scope_reload(qtbot, w, tmp_path) -> None:
    """The curve list's Reload & Redisplay on a TESTSETP curve reads its recording again (DG 4850-4876)."""
    scope = recorded(qtbot, w, tmp_path)
    scope.mode_actions["testsetp"].trigger()
    qtbot.waitUntil(lambda: len(scope.scope.curves) == 3, timeout=20_000)
    tree = scope.list
    item = next(tree.topLevelItem(g).child(k) for g in range(tree.topLevelItemCount())
                for k in range(tree.topLevelItem(g).childCount()))
    pos = tree.visualItemRect(item).center()
    RECORD.clear()
    QApplication.sendEvent(tree.viewport(), QContextMenuEvent(QContextMenuEvent.Reason.Mouse, pos,
                                                              tree.viewport().mapToGlobal(pos)))
    qtbot.waitUntil(lambda: isinstance(QApplication.activePopupWidget(), QMenu), timeout=20_000)
    menu = QApplication.activePopupWidget()
    action = next(a for a in menu.actions() if a.text() == "Reload & Redisplay")
    qtbot.mouseClick(menu, Qt.MouseButton.LeftButton, pos=menu.actionGeometry(action).center())
    qtbot.waitUntil(lambda: any(op == "upload_recording" for op, _ in RECORD.taken()), timeout=20_000)
    QApplication.processEvents()
    scope.close()


# --- the scope's Tune (DG 4704-4712, decision S9) -------------------------------------------------------------------
def scope_tune(qtbot, w, tmp_path) -> None:
    """Tune's Run: the gains written, the test move downloaded and started, its end awaited, the recording
    uploaded; the run's result appears and Run is enabled again."""
    connect(qtbot, w)
    w.actions_by_text["Oscilloscope"].trigger()
    scope = w._scopes[-1]
    scope.ask = False
    scope.mode_actions["tune"].trigger()
    panel = scope.tune_panel
    qtbot.waitUntil(lambda: panel.run.isEnabled(), timeout=20_000)
    RECORD.clear()
    click(qtbot, panel.run)
    qtbot.waitUntil(lambda: scope.run.tune is not None and len(scope.run.tune.results) == 1 and panel.run.isEnabled(),
                    timeout=30_000)
    scope.close()


CASES = {
    "CAM-Editor Read from controller": Case(cam_read),
    "CAM-Editor Write to controller": Case(cam_write),
    "Array Editor opens and reads": Case(array_editor),
    "Array Editor Write to controller": Case(array_write),
    "Clear Error connects first": Case(clear_error),
    "Restart connects first": Case(restart),
    "Oscilloscope opens": Case(scope_opens),
    "Oscilloscope TESTSETP": Case(scope_testsetp),
    "Oscilloscope TESTSETP Reload": Case(scope_reload),
    "Oscilloscope Tune Run": Case(scope_tune),
}


@pytest.mark.parametrize("name", list(params(CASES)))
def test_no_link_request_of_the_action_runs_on_the_gui_thread(checked, qtbot, tmp_path, name):
    CASES[name].action(qtbot, checked, tmp_path)
    no_request_on_the_gui_thread(name)


def test_while_the_cam_editor_reads_its_window_says_so(checked, qtbot, tmp_path):
    """Read from controller with its array list held on the line: the CAM editor's own status bar names what it
    waits for and the cursor is busy; both are gone once the controller's parameters are the editor's."""
    editor = cam_editor(qtbot, checked)
    arrived, through = threading.Event(), threading.Event()
    HOLD["list_arrays"] = (arrived, through)
    seen: dict[str, object] = {}

    def look() -> None:
        if not arrived.is_set():
            QTimer.singleShot(20, look)
            return
        seen["message"] = editor.statusBar().currentMessage()
        cursor = QApplication.overrideCursor()
        seen["cursor"] = cursor.shape() if cursor is not None else None
        through.set()

    QTimer.singleShot(0, look)
    try:
        editor.actions_by_name["read"].trigger()
    finally:
        through.set()
    assert editor.parameters
    assert seen == {"message": "Controller 1: reading parameters and arrays …", "cursor": Qt.CursorShape.BusyCursor}
    assert QApplication.overrideCursor() is None
    assert editor.statusBar().currentMessage() != seen["message"]
