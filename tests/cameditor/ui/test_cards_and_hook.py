"""Curve Data "Set" dialogs, card errors, and the Tools → CAM-Editor entry point (given the window's session as
its bridge, ui/tool_windows.py)."""

from __future__ import annotations

from PySide6.QtCore import QSettings

from motiontool.formats.zbc import ConfigFile
from tests.camcurve.conftest import stamping_curve
from tests.cameditor.ui.helpers import field, ok


def _stamping(editor) -> None:
    config = ConfigFile()
    config.add_curve(stamping_curve())
    editor.load_config(config, None)


def test_set_changes_master_length_and_intervals_together(qtbot, editor):
    """DG L3737-3743: "Set" changes master length and number of intervals together, not the slave length."""
    _stamping(editor)
    editor.curve_data.set_length.click()
    editor.dialog.master_length.setValue(5000)
    editor.dialog.intervals.setValue(50)
    ok(editor.dialog)
    c = editor.curve()
    assert (c.master_length, c.intervals, c.slave_length) == (5000, 50, 3600)
    assert editor.curve_data.master_length.text() == "5000" and editor.curve_data.intervals.text() == "50"


def test_specified_gradients_warn_on_a_mismatch(qtbot, editor):
    """DG L3725: "The CAM-Editor will warn the user if the start and end gradients do not match"."""
    _stamping(editor)
    editor.curve_data.type_group.button(3).click()
    assert editor.curve_data.set_gradients.isEnabled()
    editor.curve_data.set_gradients.click()
    editor.dialog.start.setValue(0.5)
    editor.dialog.end.setValue(0.7)
    ok(editor.dialog)
    assert (editor.curve().start_gradient, editor.curve().end_gradient) == (0.5, 0.7)
    assert "differ" in editor.message_line.text()


def test_a_refused_card_value_is_named_and_nothing_changes(qtbot, editor):
    _stamping(editor)
    before = editor.curve()
    field(qtbot, editor.curve_data.fields["correction_start"], "5000")  # outside the 4000 cycle
    assert editor.curve() == before
    assert "correction_start" in editor.message_line.text() and "0..4000" in editor.message_line.text()
    assert editor.curve_data.fields["correction_start"].text() == "0"
    field(qtbot, editor.marker_card.fields["33-19"], "7")  # marker type 0..3
    assert "33-19" in editor.message_line.text() and "33-19" not in editor.parameters


def test_open_cam_editor_uses_the_main_windows_link(qtbot, tmp_path):
    from motiontool.ui.main_window import MainWindow

    settings = QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat)
    w = MainWindow(settings=settings, realtime_factor=50.0)
    w.ask_to_save = False
    qtbot.addWidget(w)
    try:
        assert w.development.connect_default()
        w.actions_by_text["CAM-Editor"].trigger()
        editor = w.cam_editor
        w.actions_by_text["CAM-Editor"].trigger()
        assert w.cam_editor is editor  # one editor per main window
        editor.confirm = False
        assert editor.link_provider() is w.bridge.link
        assert editor.read_from_controller()
        editor.close()
    finally:
        w.bridge.detach(close=False)
        w.controllers.close()
