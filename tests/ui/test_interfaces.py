"""The IDE on a live FC link (ide-spec 2.2-2.13, 2.36; DG 2011, 2504-2552, 3087-3111), against `motiontool drive` in
its own process: Settings → Interface, Select Controller with Open Interface, two APOSS windows on two controllers
of one bus, Break all / Start all / Delete Programs all, Close Interface, a lost connection and Reconnect. Every
step is fired as a user fires it (menu actions, clicks, keys)."""

from __future__ import annotations

import re
import time

import pytest
from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import QApplication, QDialogButtonBox

from tests.comms.drive_process import DriveProcess, drive_process

pytestmark = pytest.mark.wire


def answer_dialog(qtbot, handle):
    """Run `handle(dialog)` on the next modal dialog, once it is shown (the action's exec() blocks until then). When
    `handle` fails the dialog is rejected, so the test fails instead of waiting for a user forever."""
    def attempt():
        dialog = QApplication.activeModalWidget()
        if dialog is None:
            QTimer.singleShot(20, attempt)
            return
        try:
            handle(dialog)
        except BaseException:
            dialog.reject()
            raise
    QTimer.singleShot(0, attempt)


def click_ok(qtbot, dialog):
    qtbot.mouseClick(dialog.buttons.button(QDialogButtonBox.StandardButton.Ok), Qt.MouseButton.LeftButton)


def type_into(qtbot, widget, text):
    widget.setFocus()
    qtbot.keyClick(widget, Qt.Key.Key_A, Qt.KeyboardModifier.ControlModifier)
    qtbot.keyClick(widget, Qt.Key.Key_Delete)
    qtbot.keyClicks(widget, text)


def set_fc_interface(qtbot, window, url, first=1, last=3, baud="115200"):
    """Settings → Interface: FC protocol, the drive's URL, the baud rate (115200), IDs first..last, the default."""
    def handle(dialog):
        dialog.kind.setFocus()
        qtbot.keyClicks(dialog.kind, "FC")
        type_into(qtbot, dialog.port.lineEdit(), url)
        dialog.baud.setFocus()
        qtbot.keyClicks(dialog.baud, baud)
        type_into(qtbot, dialog.first, str(first))
        type_into(qtbot, dialog.last, str(last))
        if not dialog.default.isChecked():
            qtbot.mouseClick(dialog.default, Qt.MouseButton.LeftButton)
        click_ok(qtbot, dialog)
    answer_dialog(qtbot, handle)
    window.actions_by_text["Interface..."].trigger()


def select_controller(qtbot, window, label):
    """Development → Select Controller: Open Interface (the default FC one), click the controller, OK."""
    def handle(dialog):
        qtbot.mouseClick(dialog.open_button, Qt.MouseButton.LeftButton)
        tree = dialog.tree
        items = [tree.topLevelItem(i).child(j) for i in range(tree.topLevelItemCount())
                 for j in range(tree.topLevelItem(i).childCount())]
        matching = [i for i in items if i.text(0) == label and "FC" in i.parent().text(0)]
        assert matching, f"{label} is not listed: {[(i.parent().text(0), i.text(0)) for i in items]}"
        item = matching[0]
        rect = tree.visualItemRect(item)
        qtbot.mouseClick(tree.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
        click_ok(qtbot, dialog)
    answer_dialog(qtbot, handle)
    window.actions_by_text["Select Controller..."].trigger()


def execute(qtbot, window, source):
    editor = window.current_editor() or window.new_file()
    editor.setPlainText(source)
    window.actions_by_text["Execute"].trigger()


@pytest.fixture
def drive():
    with drive_process("--node", "1", "--node", "2", "--node", "3") as process:
        yield process


def test_fc_interface_two_windows_break_start_delete_and_close(window, qtbot, drive):
    url = drive.url.removeprefix("fc:")
    set_fc_interface(qtbot, window, url)
    assert window.settings.value("interface/default") == "fc"
    assert window.controllers.default.port == url
    select_controller(qtbot, window, "Controller 2")
    assert window.controllers.interfaces[f"fc:{url}"].found == [1, 2, 3]       # the scan of 1..3
    assert f"[Controller: 2 FC: {url}]" in window.windowTitle()                 # DG 2011
    assert "Connected to controller 2 [FC: " in window.messages.toPlainText()
    execute(qtbot, window, 'PRINT "two"\nmain:\nDELAY 10\nGOTO main\n')
    qtbot.waitUntil(lambda: "[02] two" in window.messages.toPlainText(), timeout=10000)
    qtbot.waitUntil(lambda: "running" in window.controller_label.text(), timeout=5000)

    # a second APOSS window on controller 1 of the same bus
    window.actions_by_text["New APOSS Window"].trigger()
    other = window.other_windows[-1]
    qtbot.addWidget(other)
    select_controller(qtbot, other, "Controller 1")
    assert f"[Controller: 1 FC: {url}]" in other.windowTitle()
    execute(qtbot, other, 'PRINT "one"\nmain:\nDELAY 10\nGOTO main\n')
    qtbot.waitUntil(lambda: "[01] one" in other.messages.toPlainText(), timeout=10000)

    links = dict(window.controllers.open_links(interface=f"fc:{url}"))
    window.actions_by_text["Break all"].trigger()                               # both stop, from window 1
    assert {links[1].status().program_state, links[2].status().program_state} == {"break"}
    assert "Break all: stopped the programs of controllers 1, 2" in window.messages.toPlainText()
    other.actions_by_text["Start all"].trigger()
    assert {links[1].status().program_state, links[2].status().program_state} == {"running"}
    window.actions_by_text["Break all"].trigger()
    links[1].call("download", image=_image_b64(), number=3, name="kept")       # a saved program on controller 1
    window.actions_by_text["Delete Programs all"].trigger()
    assert links[1].call("list_programs") == []
    assert "Delete Programs all: deleted the programs of controllers 1" in window.messages.toPlainText()

    # the status bar says what the window is connected to; Close Interface closes both windows' controllers
    assert url in window.controller_label.text()
    window.actions_by_text["Close Interface"].trigger()
    assert "closing the connections to controllers 1, 2" in window.messages.toPlainText()
    assert not window.bridge.connected and not other.bridge.connected
    assert other.controller_label.text() == "Controller: not connected"
    other.close()


def _image_b64():
    import base64

    from motiontool.aposs.driver import compile_source

    return base64.b64encode(compile_source('PRINT "x"\n', "x.m").image.to_bytes()).decode()


def test_a_lost_drive_is_reported_and_reconnect_offered(window, qtbot):
    first = DriveProcess("--node", "1")
    url = first.url.removeprefix("fc:")
    port = int(url.rsplit(":", 1)[1])
    set_fc_interface(qtbot, window, url, 1, 1)
    select_controller(qtbot, window, "Controller 1")
    assert window.bridge.connected
    first.stop()                                                                 # the drive goes away
    qtbot.waitUntil(lambda: not window.bridge.connected, timeout=10000)
    assert "Lost connection" in window.controller_label.text()
    assert "Lost connection" in window.windowTitle()                             # ide-spec 2.3
    assert re.search(r"Lost connection to controller 1 \(FC: .*\)! Press Esc or Reconnect",
                     window.messages.toPlainText())
    assert window.connection.reconnect_button.isVisible()
    with drive_process("--node", "1", listen=f"fc:socket://127.0.0.1:{port}"):
        qtbot.mouseClick(window.connection.reconnect_button, Qt.MouseButton.LeftButton)
        assert window.bridge.connected and window.bridge.controller_id == 1
        assert not window.connection.reconnect_button.isVisible()
        assert f"[Controller: 1 FC: {url}]" in window.windowTitle()
        window.bridge.detach(close=False)
        window.controllers.close()


def test_a_link_timeout_stops_the_program_on_the_drive_and_the_ide_says_so(window, qtbot):
    """Issue 14 "Faults": on link loss the drive reacts as configured (--timeout, --timeout-reaction stop) and the
    tool says so when the line is back."""
    from tests.comms.drive_process import PausableProxy

    with drive_process("--node", "1", "--timeout", "0.5", "--timeout-reaction", "stop") as drive:
        proxy = PausableProxy(int(drive.url.rsplit(":", 1)[1]))
        try:
            url = f"socket://127.0.0.1:{proxy.port}"
            set_fc_interface(qtbot, window, url, 1, 1)
            select_controller(qtbot, window, "Controller 1")
            execute(qtbot, window, 'PRINT "up"\nmain:\nDELAY 10\nGOTO main\n')
            qtbot.waitUntil(lambda: "[01] up" in window.messages.toPlainText(), timeout=10000)
            proxy.paused.set()                                   # the cable is pulled
            qtbot.waitUntil(lambda: not window.bridge.connected, timeout=10000)
            qtbot.wait(600)
            proxy.paused.clear()                                 # and plugged in again
            qtbot.mouseClick(window.connection.reconnect_button, Qt.MouseButton.LeftButton)
            assert window.bridge.connected
            qtbot.waitUntil(lambda: "program was stopped (timeout reaction: stop)" in window.messages.toPlainText(),
                            timeout=10000)
            assert "[01] link timeout: no request from the master for 0.5 s" in window.messages.toPlainText()
            assert window.bridge.link.status().program_state == "break"
        finally:
            window.bridge.detach(close=False)
            window.controllers.close()
            proxy.close()


@pytest.mark.slow
def test_the_window_stays_responsive_while_a_slow_line_answers(window, qtbot):
    """A drive on a 2400-baud line needs about a second to answer a status request: the window keeps handling its
    events meanwhile (a 20 ms timer keeps firing), and the status still arrives (the status bar follows the
    program). The status is asked for on a worker thread; the UI still talks only through the Link. (Asked on the
    GUI thread, as before, the window stood still 1.9 s.)"""
    with drive_process("--node", "1", listen="fc:pty,baud=2400") as drive:
        path = drive.url.removeprefix("fc:")
        set_fc_interface(qtbot, window, path, 1, 1, baud="2400")
        assert window.controllers.default.baud == 2400
        select_controller(qtbot, window, "Controller 1")
        qtbot.waitUntil(lambda: "idle" in window.controller_label.text(), timeout=20000)
        ticks = []
        timer = QTimer(window, interval=20, timeout=lambda: ticks.append(time.monotonic()))
        try:
            execute(qtbot, window, 'PRINT "slow line"\n')                # blocks while it downloads: a command
            timer.start()
            qtbot.waitUntil(lambda: "[01] slow line" in window.messages.toPlainText(), timeout=20000)
            qtbot.waitUntil(lambda: "program ended" in window.controller_label.text(), timeout=20000)
            qtbot.wait(300)
        finally:
            timer.stop()
            window.bridge.detach(close=False)
            window.controllers.close()
        gaps = [b - a for a, b in zip(ticks, ticks[1:], strict=False)]
        assert len(ticks) > 20 and max(gaps) < 0.5, f"the window stood still {max(gaps):.2f} s"


@pytest.mark.slow
def test_close_interface_while_the_status_is_on_a_slow_line(window, qtbot):
    """Close Interface (DG 2548-2550) while the window's first status request is still on a 2400-baud line: the
    status thread ends, the answer of the closed link never reaches the window, and closing is not reported as a
    lost connection. Then the window connects again and closes: its status thread ends with it."""
    with drive_process("--node", "1", listen="fc:pty,baud=2400") as drive:
        set_fc_interface(qtbot, window, drive.url.removeprefix("fc:"), 1, 1, baud="2400")
        select_controller(qtbot, window, "Controller 1")          # asks for the status at once (about 1 s)
        thread = window.bridge.status_worker.worker
        assert thread is not None and thread.is_alive()
        answers = []
        window.bridge.status_changed.connect(answers.append)
        window.actions_by_text["Close Interface"].trigger()
        assert not window.bridge.connected
        qtbot.waitUntil(lambda: not thread.is_alive(), timeout=10000)
        qtbot.wait(200)                                           # anything queued would arrive now
        assert answers == []
        assert window.controller_label.text() == "Controller: not connected"
        assert "Lost connection" not in window.messages.toPlainText()
        assert not window.connection.reconnect_button.isVisible()

        window.actions_by_text["New APOSS Window"].trigger()         # the last window closes the interfaces
        other = window.other_windows[-1]
        qtbot.addWidget(other)
        select_controller(qtbot, other, "Controller 1")
        qtbot.waitUntil(lambda: "idle" in other.controller_label.text(), timeout=20000)
        thread = other.bridge.status_worker.worker
        other.close()
        qtbot.waitUntil(lambda: not thread.is_alive(), timeout=10000)
        window.controllers.close()
