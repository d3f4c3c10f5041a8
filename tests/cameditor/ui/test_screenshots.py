"""Screenshots of the editor with the manual's curves, for a person to look at (saved under the test's tmp dir
and, when MOTIONTOOL_SHOTS is set, in that directory)."""

from __future__ import annotations

import os
from pathlib import Path

from motiontool.formats.zbc import ConfigFile
from tests.camcurve.conftest import marker_curve


def test_screenshot_marker_curve_with_overlays(qtbot, editor, tmp_path):
    config = ConfigFile(parameters={"32-01": 500, "32-12": 25, "32-11": 9, "33-10": 2048, "33-11": 55,
                                    "33-17": 2375, "33-21": 200, "33-19": 2})
    config.add_curve(marker_curve())
    editor.load_config(config, Path("marker.zbc"))
    for key in ("velocity", "slave_stop", "engage", "disengage", "master_marker", "correction", "snap_on_grid"):
        editor.options.boxes[key].setChecked(True)
    editor.pair_table.select_pair(1)
    editor.zoom_reset()
    qtbot.wait(50)
    out = Path(os.environ.get("MOTIONTOOL_SHOTS", tmp_path))
    out.mkdir(parents=True, exist_ok=True)
    image = editor.grab()
    assert image.save(str(out / "cam_editor_marker.png"))
    assert image.width() >= 1000


def test_screenshot_stamping_curve_with_velocity_and_acceleration(qtbot, editor, tmp_path):
    """S1's curve as the user sees it after step 7: velocity (blue, right axis) and the acceleration limit."""
    from tests.camcurve.conftest import stamping_curve

    config = ConfigFile(parameters={"32-01": 500, "32-12": 25, "32-11": 9, "33-10": 2048, "33-11": 55})
    config.add_curve(stamping_curve())
    editor.load_config(config, Path("stamping.zbc"))
    for key in ("velocity", "velocity_limit"):
        editor.options.boxes[key].setChecked(True)
    editor.cards.setCurrentWidget(editor.curve_info)
    editor.zoom_reset()
    qtbot.wait(50)
    out = Path(os.environ.get("MOTIONTOOL_SHOTS", tmp_path))
    out.mkdir(parents=True, exist_ok=True)
    assert editor.grab().save(str(out / "cam_editor_stamping.png"))
