"""CAM editor defects a new user hit (issue 16, 2b, 2c, 2j), driven with real mouse events and clicks."""

from __future__ import annotations

from PySide6.QtCore import QPoint, Qt

from motiontool.formats.zbc import ConfigFile, read_config
from tests.camcurve.conftest import stamping_curve
from tests.cameditor.ui.helpers import drag, to_pixel
from tests.modal import answering, file_reply


def _stamping(editor) -> None:
    config = ConfigFile(parameters={"33-10": 2048, "33-11": 55})
    config.add_curve(stamping_curve())
    editor.load_config(config, None)


def _show(qtbot, editor, option: str) -> None:
    box = editor.options.boxes[option]
    qtbot.mouseClick(box, Qt.MouseButton.LeftButton, pos=QPoint(8, box.height() // 2))
    assert box.isChecked()
    qtbot.wait(50)  # the plot lays itself out again around the new axis


def test_with_an_overlay_shown_a_fix_point_still_drags_and_a_rectangle_still_zooms(qtbot, editor):
    """DG L3642-3650 (drag a fix point), L3606-3614 (left-drag zooms): with Velocity or Acceleration shown the
    overlay's own view box took every mouse drag, so neither worked."""
    _stamping(editor)
    for overlay in ("velocity", "acceleration"):
        _show(qtbot, editor, overlay)
        before = editor.curve().fix_points[1]
        drag(qtbot, editor, to_pixel(editor, before.master, before.slave),
             to_pixel(editor, before.master + 200, before.slave + 300))
        after = editor.curve().fix_points[1]
        assert after.master > before.master + 100 and after.slave > before.slave + 150, overlay
        (x0, x1), _ = editor.diagram.box.viewRange()
        drag(qtbot, editor, to_pixel(editor, 2600, 500), to_pixel(editor, 3400, 1500))
        (z0, z1), _ = editor.diagram.box.viewRange()
        assert z1 - z0 < 0.5 * (x1 - x0), overlay
        assert not editor.options["auto_scale"]
        editor.actions_by_name["zoom_reset"].trigger()


def test_a_dragged_point_lands_on_whole_numbers_and_the_curve_saves(qtbot, editor, tmp_path):
    """The controller array stores longs (docs/formats/cam-array.md): a fix point dragged without Snap on Grid
    used to keep the mouse's fraction (2990.705224274406), and Save then refused the curve."""
    _stamping(editor)
    assert not editor.options["snap_on_grid"]
    p = editor.curve().fix_points[2]
    drag(qtbot, editor, to_pixel(editor, p.master, p.slave), to_pixel(editor, p.master + 123.4, p.slave + 456.7))
    moved = editor.curve().fix_points[2]
    assert (moved.master, moved.slave) != (p.master, p.slave)
    assert moved.master == int(moved.master) and moved.slave == int(moved.slave)
    path = tmp_path / "dragged.zbc"
    with answering(qtbot, file_reply(path)):
        editor.actions_by_name["save"].trigger()
    assert path.exists(), editor.message_line.text()
    saved = read_config(path).curve("stamping").fix_points[2]
    assert (saved.master, saved.slave) == (moved.master, moved.slave)


def test_velocity_and_acceleration_have_scales_and_a_legend_of_their_own(qtbot, editor):
    """DG L3811, L3892: velocity, acceleration and jerk are drawn over the profile; each shown one gets its own
    right-hand scale in its colour and a legend entry with its unit, also when several are shown at once."""
    _stamping(editor)
    diagram = editor.diagram
    assert diagram.legend_entries() == ["Slave position [UU]"]
    _show(qtbot, editor, "velocity")
    _show(qtbot, editor, "acceleration")
    assert diagram.legend_entries() == ["Slave position [UU]", "Velocity [UU/MU]", "Acceleration [UU/MU²]"]
    axes = diagram.side_axes()
    assert set(axes) == {"velocity", "acceleration"}
    for name, axis in axes.items():
        assert axis.isVisible(), name
        low, high = axis.range
        values = diagram.layers[diagram.side_items[name]]
        assert low <= values.min() and values.max() <= high, name  # the scale covers what it labels
    _show(qtbot, editor, "jerk")
    assert set(diagram.side_axes()) == {"velocity", "acceleration", "jerk"}
    editor.options.boxes["velocity"].click()
    assert set(diagram.side_axes()) == {"acceleration", "jerk"}
    assert "Velocity [UU/MU]" not in diagram.legend_entries()
