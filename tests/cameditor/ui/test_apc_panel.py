"""The CAM editor's APC tables tab (issue 20): the worked example drawn, edits through the table, the checks,
export/import of DPL, the calculators, conversion to and from MCO curves, and a test run on the simulated APC
whose trace equals the drawing — all driven through the widgets as a user does."""

from __future__ import annotations

import os
from pathlib import Path

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QComboBox

from motiontool.cameditor.apcdpl import import_dpl
from motiontool.cameditor.apctable import ApcCamTable
from motiontool.cameditor.ui.window import CamEditor
from tests.dpl.manual import PROGRAMS


def editor(qtbot) -> CamEditor:
    w = CamEditor()
    w.confirm = False
    qtbot.addWidget(w)
    w.show()
    qtbot.waitExposed(w)
    w.kinds.setCurrentIndex(1)
    return w


def edit_cell(qtbot, grid, row: int, col: int, text: str) -> None:
    grid.setCurrentCell(row, col)
    grid.editItem(grid.item(row, col))
    editor_widget = grid.focusWidget()
    editor_widget.selectAll()
    qtbot.keyClicks(editor_widget, text)
    qtbot.keyClick(editor_widget, Qt.Key.Key_Return)
    qtbot.waitUntil(lambda: grid.item(row, col).text() == text)   # the view commits on the next event pass


def test_the_worked_example_edits_and_checks(qtbot):
    w = editor(qtbot)
    panel = w.apc_panel
    assert panel.table.slave_travel == 600748 and panel.findings.item(0).text().startswith("no speed steps")
    edit_cell(qtbot, panel.grid, 1, 1, "400000")                     # the steady part too short now
    assert panel.table.segments[1].slave == 400000
    texts = [panel.findings.item(i).text() for i in range(panel.findings.count())]
    assert texts[0].startswith("warning: speed step between segments 0 and 1")
    edit_cell(qtbot, panel.grid, 1, 0, "zero")
    assert "segment 1: 'zero' is not a whole number of counts" in panel.message.text()
    assert panel.table.segments[1].master == 218454                   # the last good table stays
    edit_cell(qtbot, panel.grid, 1, 0, "218454")
    law = panel.grid.cellWidget(2, 2)
    assert isinstance(law, QComboBox)
    law.setCurrentIndex(5)                                            # Cosine2, as a user picks it
    assert panel.table.segments[2].law == 5
    qtbot.mouseClick(panel.buttons["add"], Qt.MouseButton.LeftButton)
    assert len(panel.table.segments) == 4


def test_export_and_import_dpl_through_the_buttons(qtbot, tmp_path):
    w = editor(qtbot)
    panel = w.apc_panel
    target = tmp_path / "cam.dpl"
    assert panel.export_dialog(path=target)
    assert import_dpl(target.read_text(encoding="utf-8")) == panel.table
    assert panel.import_dialog(path=PROGRAMS / "s7_3_cam.dpl")
    assert [s.law for s in panel.table.segments] == [2, 0, 3, 4, 0, 5] and panel.grid.rowCount() == 6
    assert not panel.import_dialog(path=tmp_path / "missing.dpl")
    assert "missing.dpl" in panel.message.text()


def test_trapezoid_calculator_and_mco_conversion(qtbot):
    w = editor(qtbot)
    panel = w.apc_panel
    assert panel.trapezoid_dialog(values={"mode": "distances", "pmt": 382294, "pst": 600748, "psa": 109227,
                                          "psd": 54613})
    assert [s.master for s in panel.table.segments] == [109227, 218454, 54613]
    qtbot.mouseClick(panel.buttons["to_mco"], Qt.MouseButton.LeftButton)
    assert w.kinds.currentWidget() is w.main_split and w.curve().name == "Cam"
    w.kinds.setCurrentIndex(1)
    panel.set_table(ApcCamTable("Other", panel.table.segments[:1]))
    qtbot.mouseClick(panel.buttons["from_mco"], Qt.MouseButton.LeftButton)
    assert panel.table.master_length == 382294 and panel.table.slave_travel == 600748
    assert "largest position error" in panel.message.text()


def test_the_test_run_on_the_simulated_apc_equals_the_drawing(qtbot, tmp_path):
    """Issue 20: "a CAM table exported from the editor runs in the simulator and its trace equals the editor's
    drawing" — Test run downloads the exported program over a Link; every sample matches the drawing."""
    w = editor(qtbot)
    panel = w.apc_panel
    panel.numerator.setValue(3)
    panel.denominator.setValue(2)
    qtbot.mouseClick(panel.buttons["test"], Qt.MouseButton.LeftButton)
    assert panel.trace is not None and len(panel.trace[0]) > 7000
    assert "largest difference from the drawing 0 counts" in panel.message.text()
    folder = Path(os.environ.get("MOTIONTOOL_SHOTS", tmp_path))
    folder.mkdir(parents=True, exist_ok=True)
    w.grab().save(str(folder / "cameditor_apc_test_run.png"))
