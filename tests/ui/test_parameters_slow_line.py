"""Parameters ▸ Axis on a slow FC line (issue 27 item 2): ~115 reads take 6.6 s at 9600 baud, and asked on the GUI
thread the window stood still that long before the dialog appeared. The reads now run on the dialog's link-jobs
thread: the dialog appears at once, says it is reading, and its fields fill in while the window keeps handling its
events (a 20 ms timer keeps firing).

DG 11164: "32-60	KPROP	Proportional Factor	30" - the value the field shows once read."""

from __future__ import annotations

import time

import pytest
from PySide6.QtCore import QTimer

from motiontool.ui.parameter_dialogs import ParametersDialog
from tests.comms.drive_process import drive_process
from tests.modal import answering
from tests.ui.test_controller_dialogs import button, click, values_read
from tests.ui.test_interfaces import select_controller, set_fc_interface

pytestmark = [pytest.mark.wire, pytest.mark.slow]


def test_the_axis_dialog_appears_at_once_and_fills_in_while_a_9600_baud_line_answers(window, qtbot):
    with drive_process("--node", "1", listen="fc:pty,baud=9600") as drive:
        set_fc_interface(qtbot, window, drive.url.removeprefix("fc:"), 1, 1, baud="9600")
        select_controller(qtbot, window, "Controller 1")
        qtbot.waitUntil(lambda: "idle" in window.controller_label.text(), timeout=20000)
        ticks: list[float] = []
        seen = {}
        timer = QTimer(window, interval=20, timeout=lambda: ticks.append(time.monotonic()))

        def watch(dialog):
            assert isinstance(dialog, ParametersDialog)
            # the first field (Basic Settings) whose answer is still to come: on a busy machine the first answers
            # may arrive before the dialog is shown (a clean-clone run at load 8 saw the first field filled in)
            first = next(f for f in dialog.fields.values() if f.current is None)
            seen["at_first"] = (time.monotonic() - started, dialog.waiting, first.widget.isEnabled(),
                                first.widget.placeholderText(), dialog.ok.isEnabled(), dialog.message.text())
            values_read(qtbot, dialog, timeout_ms=60_000)
            field = dialog.fields["32-60"]
            seen["read"] = (time.monotonic() - started, field.widget.text(), field.widget.isEnabled(),
                            dialog.message.text())
            click(qtbot, button(dialog, "Cancel"))

        try:
            timer.start()
            started = time.monotonic()
            with answering(qtbot, watch):
                window.actions_by_text["Axis..."].trigger()
        finally:
            timer.stop()
            window.bridge.detach(close=False)
            window.controllers.close()
    shown_after, waiting, enabled, placeholder, ok, message = seen["at_first"]
    assert shown_after < 1.0 and waiting > 50, seen["at_first"]   # before most of the 115 answers could arrive
    assert (enabled, placeholder, ok) == (False, "reading …", False)
    assert message.startswith("Controller 1: reading ") and message.endswith(" parameters …")
    read_after, kprop, enabled, message = seen["read"]
    assert (kprop, enabled, message) == ("30", True, "")
    assert read_after > 2.0, "115 reads at 9600 baud: the values came over the line, not from elsewhere"
    gaps = [b - a for a, b in zip(ticks, ticks[1:], strict=False)]
    # the old dialog stopped the window for the whole 6.6 s; 0.5 s leaves room for a loaded 2-core machine
    assert len(ticks) > 50 and max(gaps) < 0.5, f"the window stood still {max(gaps):.2f} s"
