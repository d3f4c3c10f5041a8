"""Scenarios S6 (file housekeeping) and S7 (mouse editing) of ide-spec.md on real widgets."""

from __future__ import annotations

from PySide6.QtCore import Qt

from motiontool.camcurve.layout import encode
from motiontool.camcurve.spline import profile
from motiontool.cameditor.transfer import download_config
from motiontool.formats.zbc import ConfigFile
from tests.camcurve.conftest import marker_curve, stamping_curve
from tests.cameditor.ui.helpers import (
    R,
    add_array,
    click,
    double_click,
    drag,
    hover,
    menu_action,
    to_pixel,
)


def _stamping(editor) -> None:
    config = ConfigFile(parameters={"33-10": 2048, "33-11": 55})
    config.add_curve(stamping_curve())
    editor.load_config(config, None)


def test_s7_hover_highlights_the_row_and_shows_the_hand(qtbot, editor):
    """DG L3638-3640: resting on a fix point turns the cursor into a hand and highlights its table row;
    "Mouse accuracy" (default 4) decides how near."""
    _stamping(editor)
    assert editor.options.accuracy.value() == 4
    p = to_pixel(editor, 1500, 1200)
    hover(qtbot, editor, p + type(p)(7, 0))  # marker half width 4.5 + accuracy 4
    assert editor.diagram.box.hovered == 1
    assert editor.diagram.box.cursor().shape() == Qt.CursorShape.PointingHandCursor
    assert editor.fix_table.selected_row() == 1
    hover(qtbot, editor, p + type(p)(30, 0))
    assert editor.diagram.box.hovered == -1
    assert editor.diagram.box.cursor().shape() != Qt.CursorShape.PointingHandCursor


def test_s7_drag_with_snap_on_grid_and_continuous_recalc(qtbot, editor):
    """DG L3642-3650: dragging moves the point; with Snap on Grid it jumps to grid lines; with Continuous Recalc
    off the Curve Info changes only on release; Undo restores the old position."""
    _stamping(editor)
    editor.options.boxes["snap_on_grid"].setChecked(True)
    editor.options.boxes["continuous_recalc"].setChecked(False)
    info_before = editor.curve_info.labels["max_acceleration"].text()
    seen = []

    def during():
        seen.append((editor.curve_info.labels["max_acceleration"].text(), editor.fix_table.model.curve.fix_points[1]))

    drag(qtbot, editor, to_pixel(editor, 1500, 1200), to_pixel(editor, 1130, 1410), between=during)
    assert seen and seen[0][0] == info_before  # not recalculated during the drag
    assert seen[0][1].master % 100 == 0  # the table row follows, on the grid
    p = editor.curve().fix_points[1]
    assert p.master % 100 == 0 and p.master != 1500
    assert editor.curve_info.labels["max_acceleration"].text() != info_before  # recalculated on release
    editor.actions_by_name["undo"].trigger()
    assert editor.curve() == stamping_curve()


def test_s7_double_click_and_popup_insert(qtbot, editor):
    """DG L3652-3668: a double-click on empty space adds a point there; popup Insert on Curve adds one on the
    curve at the clicked master position; popup on a point changes its type."""
    _stamping(editor)
    editor.options.boxes["snap_on_grid"].setChecked(True)
    double_click(qtbot, editor, to_pixel(editor, 3000, 1000))
    pts = editor.curve().fix_points
    assert len(pts) == 5 and pts[3].master == 3000 and abs(pts[3].slave - 1000) < 40
    editor.actions_by_name["undo"].trigger()
    click(qtbot, editor, to_pixel(editor, 700, 2500), R)
    menu_action(editor, "Insert on Curve").trigger()
    pts = editor.curve().fix_points
    assert len(pts) == 5 and pts[1].master == 700
    assert pts[1].slave == round(profile(stamping_curve()).slave(700))
    click(qtbot, editor, to_pixel(editor, 4000, 3600), R)
    menu_action(editor, "Trapezoid").trigger()  # no straight section follows: refused with the reason
    assert editor.curve().fix_points[-1].type == "C" and "Trapezoid" in editor.message_line.text()


def test_s7_zoom_clears_auto_scale_and_zoom_reset_restores(qtbot, editor):
    """DG L3606-3626: a left-drag rectangle zooms and clears Auto Scale; right-drag pans; Zoom Reset shows all."""
    _stamping(editor)
    full = editor.diagram.box.viewRange()
    assert editor.options["auto_scale"]
    drag(qtbot, editor, to_pixel(editor, 1000, 500), to_pixel(editor, 2000, 1500))
    assert not editor.options["auto_scale"]
    (x0, x1), _ = editor.diagram.box.viewRange()
    assert 900 < x0 < 1100 and 1900 < x1 < 2100
    drag(qtbot, editor, to_pixel(editor, 1500, 1000), to_pixel(editor, 1300, 1000), button=R)
    (x0p, _x1p), _ = editor.diagram.box.viewRange()
    assert x0p > x0 + 100  # panned right by ~200 MU
    editor.actions_by_name["zoom_reset"].trigger()
    assert editor.diagram.box.viewRange() == full


def test_s6_new_read_from_controller_add_export_import(qtbot, editor, link, tmp_path):
    """ide-spec 4.6, 4.15-4.18: New has no curves; Read from controller replaces everything; Add CAM array
    gives a two-point straight line; Export then Import gives the same curve; a corrupt .dat is refused."""
    editor.new_file()
    assert editor.slots == [] and editor.curve() is None
    config = ConfigFile(parameters={"33-10": 2048})
    config.add_curve(marker_curve())
    download_config(link, config, sets=("global", "axis", "user", "arrays"))
    editor.actions_by_name["read"].trigger()
    assert editor.curve() == marker_curve()
    assert editor.parameters["33-10"] == 2048
    assert editor.array_combo.itemText(0) == "0 marker"
    add_array(editor, "line", 2000, 20, True)
    assert [(p.master, p.slave) for p in editor.curve().fix_points] == [(0, 0), (2000, 2000)]
    assert editor.array_combo.count() == 2
    editor.select_array(0)
    dat = tmp_path / "c.dat"
    assert editor.export_dat(dat)
    assert dat.read_text().count("\n") == 6 + len(encode(marker_curve()))
    editor.edits.edit("Add points", lambda c: c.__class__(**{**c.__dict__, "slave_stop_position": 5}))
    assert editor.curve() != marker_curve()
    assert editor.import_dat(dat)
    assert editor.curve() == marker_curve()
    broken = tmp_path / "broken.dat"
    broken.write_text(dat.read_text().replace("\n1\n", "\nx\n", 1))
    before = editor.curve()
    assert not editor.import_dat(broken)
    assert f"{broken}:8: expected one integer" in editor.message_line.text() and editor.curve() == before


def test_s6_cnf_and_zbc_reopen_identically(editor, tmp_path):
    _stamping(editor)
    assert editor.save_file(tmp_path / "old.cnf")
    assert editor.open_file(tmp_path / "old.cnf")
    assert editor.save_file(tmp_path / "new.zbc")
    assert (tmp_path / "old.cnf").read_bytes() == (tmp_path / "new.zbc").read_bytes()
    assert editor.curve() == stamping_curve()


def test_a_curve_the_array_cannot_hold_is_not_saved(editor, tmp_path):
    """The controller needs at least 4 fix points (cam-array-layout.md FixPointNo); the two-point line of Add
    CAM array is refused at save with the curve named, and nothing is written."""
    add_array(editor, "line", 2000, 20, True)
    assert not editor.save_file(tmp_path / "x.zbc")
    assert "curve line" in editor.message_line.text() and not (tmp_path / "x.zbc").exists()
