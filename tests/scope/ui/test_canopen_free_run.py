"""The oscilloscope's Free Run over a CANopen link (issue 15 item 3): the group is streamed as TxPDOs of the
drive's controller and the window title shows the values the link lost (decision S31)."""

import itertools

import pytest
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QToolButton

from motiontool.aposs.driver import compile_source
from motiontool.comms.canopen.link import CanopenLink
from motiontool.controller.canopen.server import CanopenDrive
from motiontool.controller.drive.simulator import VirtualDrive
from motiontool.scope.ui import ScopeWindow

_names = itertools.count(1)


@pytest.fixture
def link():
    drive = VirtualDrive([1])
    channel = f"scope-canopen-{next(_names)}"
    nodes = CanopenDrive(drive, channel)
    drive.start()
    link = CanopenLink("virtual", channel, 1)
    yield link
    link.close()
    nodes.close()
    drive.stop()


def click(qtbot, window, action):
    button = next(b for b in window.findChildren(QToolButton) if b.defaultAction() is action)
    qtbot.mouseClick(button, Qt.LeftButton)


def test_free_run_over_canopen_draws_pdo_data_and_shows_the_lost_count(qtbot, link):
    window = ScopeWindow(link, "free_run", ask=False)
    qtbot.addWidget(window)
    window.show()
    group = "Test Group (Free Run)"
    for signal in ("APOS", "CPOS", "4119"):
        window.add_signal_curve(signal, group=group)
    link.download(compile_source("VEL 20\nACC 50\nDEC 50\nPOSA 100000\n", "p.m").image.to_bytes())
    link.start()
    click(qtbot, window, window.start_action)
    qtbot.waitUntil(lambda: len(window.scope.curve("1: sys_clock [4119]").raw()[0]) > 500, timeout=15000)
    qtbot.waitUntil(lambda: "[PDO: 0 lost]" in window.windowTitle(), timeout=5000)
    t, clock = window.scope.curve("1: sys_clock [4119]").raw()
    assert (clock == t).all() and (t[1:] - t[:-1] == 1).all()    # the controller's clock, every ms
    x, _ = window.chart.items["1: CPOS"].getData()
    assert x is not None and x.size > 10                          # drawn live
    click(qtbot, window, window.stop_action)
    assert "[PDO" not in window.windowTitle()
    assert not link.pdo_stream.running
