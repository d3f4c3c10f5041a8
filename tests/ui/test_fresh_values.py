"""Dialogs that show controller values write back only what the user changed (issue 23 item 2): a KPROP set in
Parameters ▸ Axis survived neither the Tune panel's "Apply and run test" (it wrote back the gains it had read
when it opened) nor a value the panel showed from before."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QAbstractSpinBox

from motiontool.ui.parameter_dialogs import ParametersDialog
from tests.modal import answering
from tests.ui.test_controller_dialogs import button, choose_group, click, retype, values_read


def set_kprop_in_the_axis_dialog(window, qtbot, value: str) -> None:
    def edit(dialog):
        assert isinstance(dialog, ParametersDialog)
        dialog.activateWindow()
        qtbot.waitUntil(dialog.isActiveWindow, timeout=2000)
        values_read(qtbot, dialog)
        choose_group(qtbot, dialog, "Position Regulation")
        retype(qtbot, dialog.fields["32-60"].widget, value, leave_to=dialog.fields["32-61"].widget)
        click(qtbot, button(dialog, "OK"))
        qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=10_000)   # once written (link-jobs thread)

    with answering(qtbot, edit):
        window.actions_by_text["Axis..."].trigger()


def type_into(qtbot, box: QAbstractSpinBox, text: str) -> None:
    click(qtbot, box)
    box.selectAll()
    qtbot.keyClicks(box, text)
    qtbot.keyClick(box, Qt.Key.Key_Tab)


def run_test_move(qtbot, scope) -> None:
    panel = scope.tune_panel
    runs = panel.results.rowCount()
    click(qtbot, panel.run)
    qtbot.waitUntil(lambda: panel.results.rowCount() == runs + 1, timeout=20_000)


def test_a_kprop_set_in_the_axis_dialog_survives_tunes_apply_and_run(window, qtbot):
    window.actions_by_text["Oscilloscope"].trigger()
    scope = window._scopes[-1]
    scope.mode_actions["tune"].trigger()
    panel = scope.tune_panel
    assert panel.pid["KPROP"].value() == 30          # what Tune read when it was chosen
    set_kprop_in_the_axis_dialog(window, qtbot, "45")
    link = window.bridge.link
    assert link.read_parameter("KPROP") == 45
    scope.activateWindow()                           # back to the scope: it reads the gains again
    qtbot.waitUntil(lambda: panel.pid["KPROP"].value() == 45, timeout=5000)
    link.write_parameter("KPROP", 46)                # changed once more while the panel shows 45
    type_into(qtbot, panel.distance, "2000")         # a short test move
    run_test_move(qtbot, scope)
    assert link.read_parameter("KPROP") == 46        # not the 30 (or 45) the panel had read
    assert panel.pid["KPROP"].value() == 46          # and the panel now shows the controller's value
    assert panel.results.item(0, 1).text() == "46"   # the run used it
    # a gain the user edits in the panel is written; the others stay as the controller has them
    link.write_parameter("KDER", 123)                # e.g. a program or another tool changed KDER meanwhile
    type_into(qtbot, panel.pid["KPROP"], "60")
    run_test_move(qtbot, scope)
    assert link.read_parameter("KPROP") == 60 and link.read_parameter("KDER") == 123
    assert panel.pid["KDER"].value() == 123
    scope.close()
