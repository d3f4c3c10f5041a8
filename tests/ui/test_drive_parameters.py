"""Parameters ▸ Drive (FC 300), from the Axis and Global dialogs (issue 25 item 2, decision I24): the drive's own
parameters by menu group beside the option's, read and written on the link-jobs thread; only what the user
changed is written (I22).

CR 1394-1396: "an LCP value of 50.0 Hz (par. 16-13 conversion index = –1) is equivalent to a return value of
500"; DG 7594: "Parameter groups 16-** and 34-** are read only and can thus not be changed"."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QAbstractItemView, QApplication

from motiontool.ui.drive_parameters import DriveParametersDialog
from motiontool.ui.parameter_dialogs import ParametersDialog
from tests.modal import answering
from tests.shots import shot_path
from tests.ui.test_controller_dialogs import button, choose_group, click, later

KEY_MS = 20   # a key every 20 ms, a fast typist
SCREENSHOT = "fc300_parameters.png"   # docs/screenshots/ (tests/shots.py)


def loaded(qtbot, dialog: DriveParametersDialog) -> None:
    qtbot.waitUntil(lambda: all(r.current is not None for r in dialog.rows.values()) and dialog.ok.isEnabled(),
                    timeout=10_000)


def cell(dialog: DriveParametersDialog, number: int):
    return dialog.rows[number].item


def type_value(qtbot, dialog: DriveParametersDialog, number: int, text: str) -> None:
    """Click the value cell, type (the first key opens the editor, as in a spreadsheet), Return."""
    item = cell(dialog, number)
    table = item.tableWidget()
    qtbot.mouseClick(table.viewport(), Qt.MouseButton.LeftButton, pos=table.visualItemRect(item).center())
    for key in [*text, Qt.Key.Key_Return]:   # the table, then the editor its first key opened
        focused = QApplication.focusWidget()
        assert focused is not None and dialog.isAncestorOf(focused)
        qtbot.wait(KEY_MS)   # the pause before the key: a delay inside the click would let Return's editor go
        qtbot.keyClick(focused, key)
    # the delegate commits a Return queued: the value is in once the editor has closed
    qtbot.waitUntil(lambda: table.state() == QAbstractItemView.State.NoState, timeout=2000)


def from_axis_dialog(window, qtbot, edit) -> None:
    """Controller ▸ Parameters ▸ Axis..., its "Drive (FC 300)..." button, `edit(dialog)`, then Cancel the Axis."""
    def axis(dialog):
        assert isinstance(dialog, ParametersDialog)
        later(lambda: click(qtbot, button(dialog, "Drive (FC 300)...")))

    def drive(dialog):
        assert isinstance(dialog, DriveParametersDialog)
        dialog.activateWindow()
        qtbot.waitUntil(dialog.isActiveWindow, timeout=2000)
        loaded(qtbot, dialog)
        edit(dialog)

    def close_axis(dialog):
        assert isinstance(dialog, ParametersDialog)
        click(qtbot, button(dialog, "Cancel"))

    with answering(qtbot, axis, drive, close_axis):
        window.actions_by_text["Axis..."].trigger()


def test_4_13_typed_in_the_drive_dialog_is_written_and_nothing_else(window, qtbot):
    def edit(dialog):
        assert [dialog.groups.item(i).text() for i in range(dialog.groups.count())] == [
            "1-** Load and Motor", "3-** Reference / Ramps", "4-** Limits / Warnings", "5-** Digital In/Out",
            "16-** Data Readouts"]
        choose_group(qtbot, dialog, "4-** Limits / Warnings")
        table = cell(dialog, 413).tableWidget()
        row = cell(dialog, 413).row()
        assert [table.item(row, c).text() for c in range(6)] == [
            "4-13", "Motor Speed High Limit [RPM]", "1500", "RPM", "67", "4-11 .. 60000"]
        window.bridge.link.write_parameter("4-14", 600)   # another tool changes 4-14 while the dialog shows 50.0 Hz
        type_value(qtbot, dialog, 413, "1800")
        assert dialog.pending() == {"4-13": 1800} and cell(dialog, 413).font().bold()
        assert dialog.message.text() == "1 changed value(s): OK writes them"
        dialog.grab().save(str(shot_path(SCREENSHOT)))   # docs: the 4-** page with a changed value, before OK
        click(qtbot, button(dialog, "OK"))
        qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=10_000)

    from_axis_dialog(window, qtbot, edit)
    link = window.bridge.link
    assert link.read_parameter("4-13") == 1800
    assert link.read_parameter("4-14") == 600    # not the 500 the dialog had read
    assert "wrote FC 300 4-13" in window.messages.toPlainText()


def test_values_are_shown_in_lcp_units_and_readouts_are_read_only(window, qtbot):
    def edit(dialog):
        assert cell(dialog, 124).text() == "8.20"          # 1-24 Motor Current, index -2: 820 → 8.20 A
        assert cell(dialog, 341).text() == "0.01"          # 3-41 Ramp 1 Ramp Up Time (DG 7672-7676)
        assert cell(dialog, 120).text() == "4.00"          # 1-20 Motor Power [kW]
        assert cell(dialog, 1613).text() == "0.0"          # 16-13 Frequency at standstill, index -1
        assert cell(dialog, 1603).text().startswith("0x")  # status word as bits
        choose_group(qtbot, dialog, "16-** Data Readouts")
        assert not cell(dialog, 1630).flags() & Qt.ItemFlag.ItemIsEditable
        type_value(qtbot, dialog, 1630, "600")             # typing into a readout changes nothing
        assert cell(dialog, 1630).text() == "565" and dialog.pending() == {}
        click(qtbot, button(dialog, "Cancel"))

    from_axis_dialog(window, qtbot, edit)


def test_a_value_outside_its_range_is_refused_with_the_reason_and_never_sent(window, qtbot):
    def edit(dialog):
        choose_group(qtbot, dialog, "4-** Limits / Warnings")
        type_value(qtbot, dialog, 411, "2000")            # 4-11 ranges up to 4-13 = 1500
        assert dialog.message.text() == ("Refused: 4-11 Motor Speed Low Limit [RPM]: 2000 is outside "
                                         "0 .. 1500")
        type_value(qtbot, dialog, 412, "1.25")            # 4-12 holds tenths of a Hz
        assert "has more decimals than the parameter holds (steps of 0.1)" in dialog.message.text()
        click(qtbot, button(dialog, "OK"))
        assert dialog.isVisible() and dialog.message.text().startswith("Not written: 4-11")
        type_value(qtbot, dialog, 413, "2500")            # raising 4-13 lets the 4-11 = 2000 typed before fit
        assert dialog.pending() == {"4-13": 2500, "4-11": 2000} and cell(dialog, 411).font().bold()
        type_value(qtbot, dialog, 412, "0")                # back to what the drive has: nothing to write
        assert dialog.refused() == []
        click(qtbot, button(dialog, "OK"))
        qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=10_000)

    from_axis_dialog(window, qtbot, edit)
    link = window.bridge.link
    assert (link.read_parameter("4-11"), link.read_parameter("4-13")) == (2000, 2500)


def test_4_13_saved_to_a_file_comes_back_on_a_fresh_controller_through_the_menus(window, qtbot, tmp_path):
    """DG 2886-2898: Save to file, then Restore from file into another controller with the sets ticked; the drive's
    settings are the set "FC 300 drive parameters" (C19)."""
    from motiontool.ui.controller_menu import RestoreDialog
    from tests.modal import file_reply

    def edit(dialog):
        choose_group(qtbot, dialog, "4-** Limits / Warnings")
        type_value(qtbot, dialog, 413, "1800")
        click(qtbot, button(dialog, "OK"))
        qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=10_000)

    from_axis_dialog(window, qtbot, edit)
    path = tmp_path / "backup.zbc"
    with answering(qtbot, file_reply(path)):
        window.actions_by_text["Save to file..."].trigger()
    assert "\n[fc300]\n4-13 = 1800\n" in path.read_text()

    def restore(dialog):
        assert isinstance(dialog, RestoreDialog)
        dialog.controller.setCurrentIndex(dialog.controller.findData(2))
        assert dialog.checks["drive"].text() == "FC 300 drive parameters" and dialog.checks["drive"].isChecked()
        click(qtbot, dialog.restore_button)

    fresh = window.controllers.link(2, interface=window.connection.interface_key)
    assert fresh.read_parameter("4-13") == 1500
    with answering(qtbot, file_reply(path), restore):
        window.actions_by_text["Restore from file..."].trigger()
    assert fresh.read_parameter("4-13") == 1800


def test_the_drive_dialog_has_its_own_menu_entry(window, qtbot):
    """Controller ▸ Parameters ▸ Drive (FC 300)... opens the dialog directly, beside Global, Axis and Name."""
    def drive(dialog):
        assert isinstance(dialog, DriveParametersDialog)
        dialog.activateWindow()
        qtbot.waitUntil(dialog.isActiveWindow, timeout=2000)
        loaded(qtbot, dialog)
        assert cell(dialog, 413).text() == "1500"
        click(qtbot, button(dialog, "Cancel"))

    with answering(qtbot, drive):
        window.actions_by_text["Drive (FC 300)..."].trigger()
