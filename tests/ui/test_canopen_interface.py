"""The IDE on a CANopen interface (issue 15): Settings → Interface → CANopen with the virtual drive's slcan URL,
Select Controller scans the node ids and connects, a program runs and prints, the lost heartbeat of a stopped drive
is shown and the connection comes back by itself. Fired as a user fires it."""

from __future__ import annotations

import os
import signal

import pytest
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QMessageBox

from tests.comms.drive_process import drive_process
from tests.ui.test_interfaces import answer_dialog, click_ok, execute, type_into

pytestmark = pytest.mark.wire


def set_canopen_interface(qtbot, window, port, first=1, last=3):
    def handle(dialog):
        dialog.kind.setFocus()
        qtbot.keyClicks(dialog.kind, "CANopen")
        assert not dialog.baud.isEnabled()
        type_into(qtbot, dialog.port.lineEdit(), port)
        type_into(qtbot, dialog.first, str(first))
        type_into(qtbot, dialog.last, str(last))
        if not dialog.default.isChecked():
            qtbot.mouseClick(dialog.default, Qt.MouseButton.LeftButton)
        click_ok(qtbot, dialog)
    answer_dialog(qtbot, handle)
    window.actions_by_text["Interface..."].trigger()


def select_controller(qtbot, window, label):
    def handle(dialog):
        qtbot.mouseClick(dialog.open_button, Qt.MouseButton.LeftButton)
        tree = dialog.tree
        items = [tree.topLevelItem(i).child(j) for i in range(tree.topLevelItemCount())
                 for j in range(tree.topLevelItem(i).childCount())]
        item = next(i for i in items if i.text(0) == label and "canopen" in i.parent().text(0))
        qtbot.mouseClick(tree.viewport(), Qt.MouseButton.LeftButton, pos=tree.visualItemRect(item).center())
        click_ok(qtbot, dialog)
    answer_dialog(qtbot, handle)
    window.actions_by_text["Select Controller..."].trigger()


def test_canopen_interface_scan_run_and_a_stopped_drive(window, qtbot):
    with drive_process("--node", "1", "--node", "2", listen="canopen:slcan:socket://127.0.0.1:0") as drive:
        port = drive.url.removeprefix("canopen:")
        set_canopen_interface(qtbot, window, port)
        assert window.settings.value("interface/default") == "canopen"
        select_controller(qtbot, window, "Controller 2")
        assert window.controllers.interfaces[f"canopen:{port}"].found == [1, 2]      # the node scan of 1..3
        assert "Controller: 2" in window.windowTitle() and port in window.windowTitle()
        execute(qtbot, window, 'PRINT "over CAN"\nmain:\nDELAY 10\nGOTO main\n')
        qtbot.waitUntil(lambda: "[02] over CAN" in window.messages.toPlainText(), timeout=15000)
        os.kill(drive.proc.pid, signal.SIGSTOP)
        try:
            qtbot.waitUntil(lambda: "Lost connection" in window.controller_label.text(), timeout=5000)
        finally:
            os.kill(drive.proc.pid, signal.SIGCONT)
        assert window.connection.reconnect_button.isVisible()     # decision F23: the user reconnects
        qtbot.waitUntil(lambda: window.controllers.open_links(interface=f"canopen:{port}")
                        and all(link.alive for _, link in window.controllers.open_links(interface=f"canopen:{port}")),
                        timeout=5000)                              # the link is back by itself (heartbeats)
        qtbot.mouseClick(window.connection.reconnect_button, Qt.MouseButton.LeftButton)
        assert window.bridge.connected and window.bridge.controller_id == 2
        answer_dialog(qtbot, lambda box: qtbot.mouseClick(box.button(QMessageBox.StandardButton.Yes),
                                                          Qt.MouseButton.LeftButton))   # "Stop it?" — yes
        execute(qtbot, window, 'PRINT "again"\n')
        qtbot.waitUntil(lambda: "[02] again" in window.messages.toPlainText(), timeout=15000)
        window.actions_by_text["Close Interface"].trigger()


def test_the_interface_dialog_chooses_the_canopen_sdo_channel(window, qtbot):
    """Issue 24 item 4 / decision N52: the IDE beside another master on one node takes the node's second SDO server.
    Settings → Interface has the field (`,sdo=2` in the link); before, the IDE always used channel 1."""
    with drive_process("--node", "1", listen="canopen:slcan:socket://127.0.0.1:0") as drive:
        port = drive.url.removeprefix("canopen:")

        def handle(dialog):
            dialog.kind.setFocus()
            qtbot.keyClicks(dialog.kind, "CANopen")
            assert dialog.sdo.isEnabled() and dialog.sdo.currentData() == 1
            type_into(qtbot, dialog.port.lineEdit(), port)
            type_into(qtbot, dialog.first, "1")
            type_into(qtbot, dialog.last, "1")
            dialog.sdo.setFocus()
            qtbot.keyClick(dialog.sdo, Qt.Key.Key_Down)
            assert dialog.sdo.currentData() == 2
            if not dialog.default.isChecked():
                qtbot.mouseClick(dialog.default, Qt.MouseButton.LeftButton)
            click_ok(qtbot, dialog)
        answer_dialog(qtbot, handle)
        window.actions_by_text["Interface..."].trigger()
        assert int(window.settings.value("interface/canopen/sdo")) == 2
        select_controller(qtbot, window, "Controller 1")
        links = [link for _, link in window.controllers.open_links(interface=f"canopen:{port}")]
        assert links and links[0].sdo_channel == 2
        execute(qtbot, window, 'PRINT "over SDO 2"\n')
        qtbot.waitUntil(lambda: "[01] over SDO 2" in window.messages.toPlainText(), timeout=15000)
        window.actions_by_text["Close Interface"].trigger()
