"""The Watch on a slow FC line (issue 27 item 2): every entry is a request, ~0.23 s at 2400 baud, and the poll every
250 ms asked them on the GUI thread: with 4 entries the window stood still ~1 s at each poll. The pane now polls on
its link-jobs thread and shows the values when they arrive; a 20 ms timer keeps firing meanwhile.

DG 11164: "32-60	KPROP	Proportional Factor	30"; DG L2452-2477: Watch Add, Watch Start."""

from __future__ import annotations

import time

import pytest
from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import QDialogButtonBox

from motiontool.ui.watch import WatchAddDialog
from tests.comms.drive_process import drive_process
from tests.modal import answering
from tests.ui.test_controller_dialogs import click
from tests.ui.test_interfaces import select_controller, set_fc_interface

pytestmark = [pytest.mark.wire, pytest.mark.slow]

WATCHED = ("APOS", "AVEL", "KPROP", "KDER")


def double_click(qtbot, view, pos) -> None:
    qtbot.mouseClick(view.viewport(), Qt.MouseButton.LeftButton, pos=pos)
    qtbot.mouseDClick(view.viewport(), Qt.MouseButton.LeftButton, pos=pos)


def test_the_watch_polls_a_2400_baud_line_while_the_window_keeps_handling_its_events(window, qtbot):
    with drive_process("--node", "1", listen="fc:pty,baud=2400") as drive:
        set_fc_interface(qtbot, window, drive.url.removeprefix("fc:"), 1, 1, baud="2400")
        select_controller(qtbot, window, "Controller 1")
        qtbot.waitUntil(lambda: "idle" in window.controller_label.text(), timeout=20000)

        def add(dialog):
            assert isinstance(dialog, WatchAddDialog)
            for top in range(dialog.system.topLevelItemCount()):
                group = dialog.system.topLevelItem(top)
                for j in range(group.childCount()):
                    if group.child(j).text(0) in WATCHED:
                        double_click(qtbot, dialog.system, dialog.system.visualItemRect(group.child(j)).center())
            click(qtbot, dialog.findChild(QDialogButtonBox).button(QDialogButtonBox.StandardButton.Close))

        with answering(qtbot, add):
            window.actions_by_text["Watch Add"].trigger()
        pane = window.debugger.watch
        assert sorted(e.key for e in pane.entries) == sorted(WATCHED)
        kprop = next(r for r, e in enumerate(pane.entries) if e.key == "KPROP")
        ticks: list[float] = []
        timer = QTimer(window, interval=20, timeout=lambda: ticks.append(time.monotonic()))
        try:
            timer.start()
            window.actions_by_text["Watch Start"].trigger()
            qtbot.waitUntil(lambda: pane.values()[kprop] == "30" and "" not in pane.values(), timeout=20000)
            qtbot.wait(1500)                                     # a few more polls
            window.actions_by_text["Watch Stop"].trigger()
        finally:
            timer.stop()
            window.bridge.detach(close=False)
            window.controllers.close()
    gaps = [b - a for a, b in zip(ticks, ticks[1:], strict=False)]
    # asked on the GUI thread each poll stood the window still ~1 s; 0.5 s leaves room for a loaded 2-core machine
    assert len(ticks) > 50 and max(gaps) < 0.5, f"the window stood still {max(gaps):.2f} s"
