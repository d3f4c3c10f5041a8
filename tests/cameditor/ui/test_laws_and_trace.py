"""Beyond the manual (issue 6 item 5) on real widgets: motion laws in the fix point table and the point popup
(decision C10), saving them (C12), and the measured trace overlay (C14)."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QComboBox

from motiontool.camcurve.model import FIX_POINT_TYPES
from motiontool.camcurve.spline import profile
from motiontool.formats.zbc import ConfigFile, read_config
from tests.cameditor.law_trace import law_curve, record_trace
from tests.cameditor.ui.helpers import L, R, add_array, add_fix_points, cell_center, choose_type, click, ok, to_pixel


def _law_curve(editor, interpolation=False) -> None:
    config = ConfigFile()
    config.add_curve(law_curve(interpolation))
    editor.load_config(config, Path("drdr.zbc"))


def test_type_cell_offers_the_laws(qtbot, editor):
    """Double-click on the Type cell: C, T, CZ, C3 and the five laws; choosing CYCL makes the segment ending at
    that point a cycloid, drawn and counted at once."""
    add_array(editor, "rise", 3600, 36)
    add_fix_points(editor, "900 0\n1800 1000\n2700 1000")
    view = editor.fix_table.view
    qtbot.mouseClick(view.viewport(), L, pos=cell_center(view, 2, 3))
    qtbot.mouseDClick(view.viewport(), L, pos=cell_center(view, 2, 3))
    combo = next(w for w in view.findChildren(QComboBox) if w.isVisible())
    assert [combo.itemText(i) for i in range(combo.count())] == list(FIX_POINT_TYPES)
    combo.hidePopup()
    qtbot.keyClick(combo, Qt.Key.Key_Escape)
    qtbot.wait(20)
    choose_type(qtbot, editor, 2, "CYCL")
    curve = editor.curve()
    assert [p.type for p in curve.fix_points] == ["C", "C", "CYCL", "C", "C"]
    assert curve.segment_kinds[1] == "law"
    assert editor.fix_table.model.index(2, 3).data() == "CYCL"
    assert editor.fix_table.model.index(2, 3).data(Qt.ItemDataRole.ToolTipRole).startswith("Cycloid (VDI 2143)")
    assert profile(curve).slave(1350) == 500  # cycloid: half the rise at half the segment
    editor.actions_by_name["undo"].trigger()
    assert editor.curve().fix_points[2].type == "C"


def test_popup_has_a_motion_law_submenu(qtbot, editor, tmp_path):
    _law_curve(editor)
    editor.zoom_reset()
    qtbot.wait(50)
    click(qtbot, editor, to_pixel(editor, 1800, 1000), R)
    menu = editor.edits.context_menu
    sub = next(a.menu() for a in menu.actions() if a.text() == "Motion law (VDI 2143)")
    names = [a.text() for a in sub.actions()]
    assert names == ["3-4-5 polynomial", "Modified sine", "Cycloid", "Modified trapezoid", "Simple harmonic"]
    assert next(a for a in sub.actions() if a.text() == "Cycloid").isChecked()
    next(a for a in sub.actions() if a.text() == "Modified trapezoid").trigger()
    assert editor.curve().fix_points[2].type == "MTRAP"
    assert editor.save_file(tmp_path / "laws.zbc")
    assert (tmp_path / "laws.zbc").read_text().startswith("# motiontool configuration file, format 2\n")
    assert read_config(tmp_path / "laws.zbc").curve("drdr").fix_points[2].type == "MTRAP"
    qtbot.wait(50)
    click(qtbot, editor, to_pixel(editor, 0, 0), R)  # the first point ends no segment: refused with the reason
    sub = next(a.menu() for a in editor.edits.context_menu.actions() if a.text() == "Motion law (VDI 2143)")
    sub.actions()[0].trigger()
    assert editor.curve().fix_points[0].type == "C" and "first point" in editor.message_line.text()


def test_trace_overlay_from_a_simulated_run(qtbot, editor, tmp_path):
    """Toolbar Trace…: a `motiontool run --trace` CSV of the kernel running the curve; CMASTERCPOS (4230) and APOS
    are proposed; the grey dashed overlay lies on the designed curve; Clear trace removes it."""
    _law_curve(editor)
    path = tmp_path / "run.csv"
    record_trace(path, law_curve())
    assert "trace" in editor.actions_by_name and "clear_trace" in editor.actions_by_name
    dialog = editor.trace_overlay.load(path)
    assert dialog is editor.dialog
    assert (dialog.master.currentText(), dialog.slave.currentText()) == ("4230", "APOS")
    ok(dialog)
    x, y = editor.trace_overlay.data
    good = ~np.isnan(x)
    assert good.sum() > 1000 and np.isnan(x).sum() >= 2  # several cycles, one stroke each
    assert ((x[good] >= 0) & (x[good] <= 3600)).all()
    assert np.max(np.abs(y[good] - profile(law_curve()).slave(x[good]))) < 25
    assert editor.trace_overlay.legend.isVisible()
    assert "4230" in editor.message_line.text()
    editor.options.boxes["velocity"].setChecked(True)
    editor.zoom_reset()
    qtbot.wait(50)
    out = Path(os.environ.get("MOTIONTOOL_SHOTS", tmp_path))
    out.mkdir(parents=True, exist_ok=True)
    assert editor.grab().save(str(out / "cam_editor_trace.png"))
    editor.actions_by_name["clear_trace"].trigger()
    assert len(editor.trace_overlay.data[0]) == 0 and not editor.trace_overlay.legend.isVisible()


def test_trace_follows_the_shown_curve_and_refuses_bad_files(qtbot, editor, tmp_path):
    _law_curve(editor)
    path = tmp_path / "t.csv"
    path.write_text("time_ms,MAPOS,APOS\n0,0,0\n1,5000,10\n")
    ok(editor.trace_overlay.load(path))
    x, _ = editor.trace_overlay.data
    assert x[~np.isnan(x)].tolist() == [0, 1400]  # 5000 mod 3600
    add_array(editor, "short", 1000, 10)  # another curve: the trace is wrapped onto its cycle
    x, _ = editor.trace_overlay.data
    assert x[~np.isnan(x)].tolist() == [0, 0]
    bad = tmp_path / "bad.csv"
    bad.write_text("time_ms,MAPOS,APOS\n0,0,0\n1,x,2\n")
    assert editor.trace_overlay.load(bad) is None
    assert f"{bad}:3:" in editor.message_line.text() and "'x' is not a number" in editor.message_line.text()
