"""APC tables tab ▸ From MCO curve (issue 23 item 10, decision C21): the table it makes has no speed step at any
join (it made 81 Linear segments with a step at each) and runs on the simulated APC as drawn. Driven with
clicks on the tab and the buttons."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QToolBar

from motiontool.formats.zbc import ConfigFile
from tests.camcurve.conftest import stamping_curve


def test_from_mco_curve_gives_a_table_without_speed_steps_that_runs_as_drawn(qtbot, editor):
    config = ConfigFile(parameters={"33-10": 2048, "33-11": 55})
    config.add_curve(stamping_curve())
    editor.load_config(config, None)
    bar = editor.kinds.tabBar()
    qtbot.mouseClick(bar, Qt.MouseButton.LeftButton, pos=bar.tabRect(1).center())
    panel = editor.apc_panel
    assert editor.kinds.currentWidget() is panel
    assert not [bar for bar in editor.findChildren(QToolBar) if bar.isVisible()]  # both rows serve the MCO tab
    qtbot.mouseClick(panel.buttons["from_mco"], Qt.MouseButton.LeftButton)
    assert "speed continuous at every join" in panel.message.text(), panel.message.text()
    findings = [panel.findings.item(i).text() for i in range(panel.findings.count())]
    assert findings == ["no speed steps; the delta-segment limit holds at this master speed"], findings
    assert panel.table.master_length == 4000 and panel.table.slave_travel == 3600
    assert len(panel.table.segments) < 81 and {s.law for s in panel.table.segments} == {2}
    qtbot.mouseClick(panel.buttons["test"], Qt.MouseButton.LeftButton)
    assert "largest difference from the drawing 0 counts" in panel.message.text(), panel.message.text()
