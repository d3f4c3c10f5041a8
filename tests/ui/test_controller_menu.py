"""Controller menu: Programs, Parameters → Save to file / Restore from file, Reset (ide-spec 2.16-2.30)."""

import pytest

from motiontool.cameditor.transfer import SETS
from motiontool.formats.zbc import read_config
from motiontool.ui import controller_menu as cm


def test_menu_entries_are_enabled(window):
    for text in ("Programs...", "Save to file...", "Restore from file...", "Parameter...", "Arrays...",
                 "User Parameters...", "Complete..."):
        assert window.actions_by_text[text].isEnabled(), text


def test_save_to_file_and_restore_into_another_controller(window, tmp_path, qtbot):
    """DG 2884-2900: "the entire controller configuration (i.e. global parameters, axis parameters, user
    parameters, and arrays) can be uploaded and saved as a file"; Restore loads the chosen sets into the
    chosen controller and overwrites them."""
    assert window.development.connect_default()
    link = window.bridge.link
    link.write_parameter("KPROP", 77)
    link.write_parameter("19-00", 5)
    link.call("restore_arrays", arrays=[{"name": "table", "values": [1, 2, 3]}])
    path = tmp_path / "backup.zbc"
    assert cm.save_parameters(window, path)
    config = read_config(path)
    assert config.parameters["32-60"] == 77 and config.parameters["19-00"] == 5
    assert config.array("table").values == [1, 2, 3]
    # into controller 2, axis parameters and arrays only
    assert cm.restore_parameters(window, path, controller_id=2, sets=("axis", "arrays"))
    other = window.controllers.link(2)
    assert other.read_parameter("KPROP") == 77
    assert other.read_parameter("19-00") == 0
    assert other.read_array(0) == [1, 2, 3]


def test_restore_refuses_a_broken_file_and_leaves_the_controller_alone(window, tmp_path):
    assert window.development.connect_default()
    path = tmp_path / "broken.zbc"
    assert cm.save_parameters(window, path)
    path.write_text(path.read_text().replace("32-60 KPROP = 30", "32-60 KPROP = 30x"))
    window.bridge.link.write_parameter("KPROP", 44)
    assert not cm.restore_parameters(window, path, controller_id=1, sets=SETS)
    assert window.bridge.link.read_parameter("KPROP") == 44
    assert f"{path}:" in window.messages.toPlainText() and "30x" in window.messages.toPlainText()


@pytest.mark.parametrize(("what", "kprop", "user", "arrays"), [
    ("parameters", 30, 5, 1), ("user", 77, 0, 1), ("arrays", 77, 5, 0), ("all", 30, 0, 0)])
def test_reset_entries(window, what, kprop, user, arrays):
    """DG 2948-2980: Parameter resets global and axis parameters, Arrays deletes the arrays, User Parameters
    the 19-xx, Complete everything."""
    assert window.development.connect_default()
    link = window.bridge.link
    link.write_parameter("KPROP", 77)
    link.write_parameter("19-00", 5)
    link.call("restore_arrays", arrays=[{"name": "table", "values": [1]}])
    assert cm.reset(window, what, ask=False)
    assert link.read_parameter("KPROP") == kprop
    assert link.read_parameter("19-00") == user
    assert len(link.call("list_arrays")) == arrays


def test_programs_save_start_delete(window, qtbot):
    """DG 2627-2794: Save compiles the current program into permanent memory under the next number; Start
    runs the selected one; Delete removes it."""
    editor = window.new_file()
    # the delay: an Autostart program that ends restarts at once (DG 2766-2768), so it prints once a second
    editor.setPlainText('PRINT "stored"\nDELAY 1000\n')
    assert window.development.connect_default()
    dialog = cm.ProgramsDialog(window)
    qtbot.addWidget(dialog)
    assert dialog.store(name="FIRSTPROGRAM")
    assert dialog.store(number=7, name="SEVEN")
    assert [(p.number, p.name) for p in dialog.programs()] == [(0, "FIRSTPRO"), (7, "SEVEN")]
    assert dialog.table.rowCount() == 2
    dialog.table.selectRow(1)
    assert dialog.start()
    qtbot.waitUntil(lambda: "[01] stored" in window.messages.toPlainText(), timeout=15000)
    dialog.table.selectRow(0)
    dialog.autostart(True)
    assert dialog.table.item(0, 2).text() == "⊙" and dialog.table.item(1, 2).text() == ""  # DG 2727
    window.bridge.link.call("power_on")  # DG 2707: the Autostart program starts at power on
    qtbot.waitUntil(lambda: window.messages.toPlainText().count("[01] stored") >= 2, timeout=15000)
    dialog.autostart(False)
    assert dialog.table.item(0, 2).text() == ""
    dialog.delete()
    assert [p.number for p in dialog.programs()] == [7]
    dialog.delete_all()
    assert dialog.table.rowCount() == 0


def test_diagnostic_report_holds_the_whole_state(window, tmp_path):
    """DG 3029-3031: "a text file containing the entire current state of the controller"."""
    assert window.development.connect_default()
    window.bridge.link.write_parameter("KPROP", 61)
    path = tmp_path / "report.txt"
    assert cm.diagnostic_report(window, path)
    text = path.read_text()
    for part in ("[status]", "[error history]", "[programs]", "[readouts]", "34-50 = 0",
                 "32-60 KPROP = 61", "# motiontool configuration file, format 1"):
        assert part in text, part
