"""Acceptance scenarios S1-S7 of ide-spec.md (CAM editor) on real widgets, against the embedded controller."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import Qt

from motiontool.aposs.driver import compile_source
from motiontool.camcurve.layout import encode
from motiontool.camcurve.spline import profile
from motiontool.formats.zbc import read_config
from tests.camcurve.conftest import marker_curve, slavesync_curve, stamping_curve
from tests.cameditor.ui.helpers import (
    add_array,
    add_fix_points,
    add_pairs,
    choose_type,
    field,
)


def build_stamping(qtbot, editor) -> None:
    """S1 steps 1-7 through the editor's own widgets."""
    field(qtbot, editor.encoder_card.fields["32-01"], "500")
    field(qtbot, editor.encoder_card.fields["32-12"], "25")
    field(qtbot, editor.encoder_card.fields["32-11"], "9")
    field(qtbot, editor.sync_card.fields["33-10"], "2048")
    field(qtbot, editor.sync_card.fields["33-11"], "55")
    add_array(editor, "stamping", 4000, 40, True)
    qtbot.mouseClick(editor.options.boxes["snap_on_grid"], Qt.MouseButton.LeftButton)
    assert editor.options["snap_on_grid"]
    add_fix_points(editor, "0, 0\n1500, 1200\n2500, 2400\n4000, 3600")
    choose_type(qtbot, editor, 2, "T")
    field(qtbot, editor.curve_info.cycles, "60")


def test_s1_stamping_curve_from_scratch(qtbot, editor, link, tmp_path):
    """DG L1435-1476: master 4000 MU, 40 intervals ("interval time of 25 ms"), "Master and slave must run
    synchronously with the same velocity between the position 1500 and 2500"; "Set the point 2500 to T: 1500
    becomes T automatically"; the stamping array has 92 elements (DIM stamping[92])."""
    build_stamping(qtbot, editor)
    curve = editor.curve()
    assert curve == stamping_curve()
    assert editor.message_line.isHidden(), editor.message_line.text()
    assert editor.curve_info.labels["interval_size"].text() == "100 MU"
    assert editor.curve_data.slave_length.text() == "3600"
    assert editor.curve_info.labels["interval_time"].text() == "25"
    # velocity flat at 1.2 UU/MU on 1500..2500, drawn green there and red elsewhere
    qtbot.mouseClick(editor.options.boxes["velocity"], Qt.MouseButton.LeftButton)
    xs, vs = editor.diagram.side_items["velocity"].getData()
    inside = (xs >= 1500) & (xs <= 2500)
    assert np.allclose(vs[inside], 1.2)
    gx, gy = editor.diagram.green.getData()
    assert np.all(np.isfinite(gy[(gx > 1500) & (gx < 2500)]))
    assert np.all(np.isnan(gy[(gx < 1400) | (gx > 2600)]))
    rx, ry = editor.diagram.red.getData()
    assert np.all(np.isnan(ry[(rx > 1500) & (rx < 2500)]))
    # acceleration below its limit: not red
    qtbot.mouseClick(editor.options.boxes["acceleration"], Qt.MouseButton.LeftButton)
    qtbot.mouseClick(editor.options.boxes["acceleration_limit"], Qt.MouseButton.LeftButton)
    acc = editor.curve_info.labels["max_acceleration"]
    pct = float(acc.text().split("(")[1].split("%")[0])
    assert pct < 100 and "c00000" not in acc.styleSheet()
    assert editor.diagram.limit_lines["acceleration"][0].isVisible()
    # save: title and Length show 92
    path = tmp_path / "stamping.zbc"
    assert editor.save_file(path)
    assert editor.length_field.text() == "92"
    assert "stamping" in editor.windowTitle() and "92 elements" in editor.windowTitle()
    config = read_config(path)
    assert config.array("stamping").values == encode(stamping_curve())
    assert config.parameters["33-10"] == 2048 and config.parameters["32-12"] == 25
    # Restore into controller 1 and run the manual's program start: no error 191
    assert editor.write_to_controller(), editor.message_line.text()
    events = []
    link.subscribe(events.append)
    source = ("DIM stamping[92]\nSETCURVE stamping\nDEFMCPOS 1000\nPOSA CURVEPOS\nSYNCC 0\nSYNCCSTART 0\n"
              "PRINT \"engaged\"\n")
    result = compile_source(source, "stamping.m")
    assert result.ok, [d.format() for d in result.diagnostics]
    link.download(result.image.to_bytes())
    link.start()
    link.advance(3000)
    assert [e.number for e in events if e.kind == "error"] == []
    assert "engaged" in [e.text for e in events if e.kind == "print"]


def test_save_reopen_save_is_byte_identical(qtbot, editor, tmp_path):
    build_stamping(qtbot, editor)
    add_pairs(editor, "1000, 1500\n2500, 3000")
    first, second = tmp_path / "a.zbc", tmp_path / "b.zbc"
    assert editor.save_file(first)
    assert editor.open_file(first)
    assert editor.curve().start_stop_pairs == marker_curve().start_stop_pairs
    assert editor.save_file(second)
    assert first.read_bytes() == second.read_bytes()


def test_s2_tangent_pairing_and_undo(qtbot, editor):
    """DG L1441-1445 and L3573-3577: setting 2500 to T also sets 1500; Undo restores both in one step, Redo
    re-applies both; CZ with no straight section after it is refused with a reason."""
    build_stamping(qtbot, editor)
    choose_type(qtbot, editor, 1, "C")  # releasing a T point releases its partner
    assert [p.type for p in editor.curve().fix_points] == ["C", "C", "C", "C"]
    choose_type(qtbot, editor, 2, "T")
    assert [p.type for p in editor.curve().fix_points] == ["C", "T", "T", "C"]
    editor.actions_by_name["undo"].trigger()
    assert [p.type for p in editor.curve().fix_points] == ["C", "C", "C", "C"]
    editor.actions_by_name["redo"].trigger()
    assert [p.type for p in editor.curve().fix_points] == ["C", "T", "T", "C"]
    before = editor.curve()
    choose_type(qtbot, editor, 3, "CZ")
    assert editor.curve() == before
    assert editor.message_line.isVisible()
    assert "CZ" in editor.message_line.text() or "Trapezoid" in editor.message_line.text()


def test_undo_is_greyed_and_kept_per_curve(qtbot, editor):
    """DG L3575-3577: Undo is disabled when there is nothing to undo; each curve has its own undo list."""
    add_array(editor, "one", 4000, 40, True)
    assert not editor.actions_by_name["undo"].isEnabled()
    add_fix_points(editor, "1000, 500")
    add_array(editor, "two", 2000, 20, True)
    assert not editor.actions_by_name["undo"].isEnabled()
    add_fix_points(editor, "500, 100\n700, 300")  # one batch = one step
    editor.select_array(0)
    assert editor.actions_by_name["undo"].isEnabled()
    editor.actions_by_name["undo"].trigger()
    assert len(editor.curve().fix_points) == 2
    editor.select_array(1)
    assert len(editor.curve().fix_points) == 4
    editor.actions_by_name["undo"].trigger()
    assert len(editor.curve().fix_points) == 2


def test_s3_marker_corrected_printing(qtbot, editor, tmp_path):
    """DG L1500-1552: pairs 1000/1500 and 2500/3000, marker distance 2375, tolerance 200, type 2, master marker
    position 1000 → detection line at 2625 over a band 2425..2825; correction 3000 → 1000 wraps; 112 elements."""
    build_stamping(qtbot, editor)
    add_pairs(editor, "1000, 1500\n2500, 3000")
    field(qtbot, editor.curve_data.fields["slave_stop_position"], "0")
    field(qtbot, editor.marker_card.fields["33-17"], "2375")
    field(qtbot, editor.marker_card.fields["33-21"], "200")
    field(qtbot, editor.marker_card.fields["33-19"], "2")
    field(qtbot, editor.curve_data.fields["master_marker_pos"], "1000")
    field(qtbot, editor.curve_data.fields["correction_start"], "3000")
    field(qtbot, editor.curve_data.fields["correction_end"], "1000")
    field(qtbot, editor.curve_data.name, "marker")
    assert editor.curve() == marker_curve()
    for key in ("master_marker", "correction", "velocity_limit", "acceleration_limit", "engage"):
        qtbot.mouseClick(editor.options.boxes[key], Qt.MouseButton.LeftButton)
    d = editor.diagram
    assert d.master_marker_line.isVisible() and d.master_marker_line.value() == 2625
    assert d.master_band.isVisible() and d.master_band.getRegion() == (2425, 2825)
    bars = [b.getRegion() for b in d.correction_bars if b.isVisible()]
    assert sorted(bars) == [(0, 1000), (3000, 4000)]
    assert all(line.isVisible() for line in d.limit_lines["velocity"] + d.limit_lines["acceleration"])
    lines = [line.value() for line in d.limit_lines["velocity"]]
    assert lines[0] == -lines[1] > 0
    # selecting pair 1 draws the engage path 0 → profile on 1000..1500, and its flags turn red
    view = editor.pair_table.view
    qtbot.mouseClick(view.viewport(), Qt.MouseButton.LeftButton, pos=view.visualRect(view.model().index(0, 1)).center())
    xs, ys = d.engage_item.getData()
    assert xs[0] == 1000 and ys[0] == 0 and xs[-1] == 1500
    assert abs(ys[-1] - profile(marker_curve()).slave(1500)) < 1e-6
    red_flags = [f for f in d.flags
                 if hasattr(f, "fill") and f.fill.color().red() > 200 and f.fill.color().green() < 60]
    assert len(red_flags) == 2
    assert editor.save_file(tmp_path / "marker.zbc")
    assert editor.length_field.text() == "112" and "112 elements" in editor.windowTitle()


def test_s4_master_length_guards_and_large_marker_distances(qtbot, editor):
    """DG L3745-3752: the last point cannot precede the correction start etc.; DG L1582-1606: distance 4100 →
    900, distance 3900 with position 800 → 900."""
    build_stamping(qtbot, editor)
    add_pairs(editor, "1000, 1500\n2500, 3000")
    field(qtbot, editor.curve_data.fields["correction_start"], "3000")
    field(qtbot, editor.curve_data.fields["correction_end"], "1000")
    field(qtbot, editor.curve_data.fields["master_marker_pos"], "1000")
    from tests.cameditor.ui.helpers import edit_cell

    before = editor.curve()
    edit_cell(qtbot, editor, 3, 1, "1000")
    assert editor.curve() == before
    assert "point 3 at 2500" in editor.message_line.text()
    edit_cell(qtbot, editor, 3, 1, "2800")
    assert editor.curve() == before
    assert "3000 is in the way" in editor.message_line.text()
    # dragging the last point to the left stops at the correction start
    from tests.cameditor.ui.helpers import drag, to_pixel

    drag(qtbot, editor, to_pixel(editor, 4000, 3600), to_pixel(editor, 2700, 3600))
    assert editor.curve().master_length == 3000
    editor.actions_by_name["undo"].trigger()  # one drag = one undo step
    assert editor.curve() == before
    qtbot.mouseClick(editor.options.boxes["master_marker"], Qt.MouseButton.LeftButton)
    field(qtbot, editor.marker_card.fields["33-17"], "4100")
    assert editor.diagram.master_marker_line.value() == 900
    field(qtbot, editor.marker_card.fields["33-17"], "3900")
    field(qtbot, editor.curve_data.fields["master_marker_pos"], "800")
    assert editor.diagram.master_marker_line.value() == 900


def test_s5_slave_synchronization(qtbot, editor, tmp_path):
    """DG L1655-1729: 3600 MU, 36 intervals (27.7 ms at 60/min, 83.3 ms at 20/min), pair 200/1000, slave marker
    1000 with distance 3900 and tolerance 200, correction 2800 → 750, 108 elements."""
    add_array(editor, "slavesync", 3600, 36, True)
    assert editor.curve_info.labels["interval_time"].text() == "27.8"  # 60000 / (60 × 36) = 27.78 ("27.7")
    add_fix_points(editor, "0, 0\n1200, 1500\n2400, 2500\n3600, 4000")
    choose_type(qtbot, editor, 2, "T")
    field(qtbot, editor.curve_info.cycles, "20")
    assert editor.curve_info.labels["interval_time"].text() == "83.3"
    add_pairs(editor, "200, 1000")
    for number, value in (("33-18", "3900"), ("33-22", "200"), ("33-20", "2")):
        field(qtbot, editor.marker_card.fields[number], value)
    field(qtbot, editor.curve_data.fields["slave_marker_pos"], "1000")
    field(qtbot, editor.curve_data.fields["correction_start"], "2800")
    field(qtbot, editor.curve_data.fields["correction_end"], "750")
    assert editor.curve() == slavesync_curve()
    qtbot.mouseClick(editor.options.boxes["slave_marker"], Qt.MouseButton.LeftButton)
    assert editor.diagram.slave_marker_line.isVisible() and editor.diagram.slave_band.isVisible()
    assert editor.save_file(tmp_path / "slavesync.zbc")
    assert editor.length_field.text() == "108" and "108 elements" in editor.windowTitle()
