"""The watch and the oscilloscope on the simulated APC: read parameters by alias and the DPL program's variables
(issue 20: "the scope and watch record read parameters by alias")."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QToolButton

from motiontool.controller.dpl_program import dpl_link
from motiontool.dpl.image import DplImage
from motiontool.scope.ui import ScopeWindow
from motiontool.ui.watch import WatchAddDialog
from tests.dpl.manual import PROGRAMS
from tests.ui.test_dpl_execute import PROGRAM


def click(qtbot, window, action):
    button = next(b for b in window.findChildren(QToolButton) if b.defaultAction() is action)
    qtbot.mouseClick(button, Qt.MouseButton.LeftButton)


def double_click(qtbot, view, pos) -> None:
    """As a user does: the first click selects, the second (a double click) adds."""
    qtbot.mouseClick(view.viewport(), Qt.MouseButton.LeftButton, pos=pos)
    qtbot.mouseDClick(view.viewport(), Qt.MouseButton.LeftButton, pos=pos)


def test_the_scope_records_apc_read_parameters_by_alias(qtbot):
    """A Free Run group of APC_FB_POS and APC_PROF_OUT_SPD while §7.1 moves 5 revolutions."""
    link = dpl_link()
    link.write_parameter("18.11", 50)
    source = (PROGRAMS / "s7_1_position.dpl").read_text(encoding="utf-8")
    link.download(DplImage("s7_1_position.dpl", source).to_bytes(), name="s7_1_position.dpl")
    w = ScopeWindow(link, "free_run", ask=False)
    qtbot.addWidget(w)
    w.show()
    for signal in ("APC_FB_POS", "APC_PROF_OUT_SPD"):
        w.add_signal_curve(signal, group="Test Group (Free Run)")
    click(qtbot, w, w.start_action)
    link.start()
    for _ in range(60):
        link.advance(50)
        w.run.tick()
    click(qtbot, w, w.stop_action)
    times, positions = w.scope.curve("1: APC_FB_POS").raw()
    _, speeds = w.scope.curve("1: APC_PROF_OUT_SPD").raw()
    assert len(times) > 2500 and positions[-1] == 5 * 65536 == link.read_parameter("APC_FB_POS")
    assert max(speeds) > 0 and speeds[-1] == 0


def test_the_watch_offers_apc_read_parameters_and_the_programs_variables(window, qtbot, tmp_path):
    path = tmp_path / "jog.dpl"
    path.write_text(PROGRAM, encoding="utf-8")
    qtbot.keyClick(window.open_file(path), Qt.Key.Key_F5)
    pane = window.debugger.watch
    dialog = WatchAddDialog(pane)
    qtbot.addWidget(dialog)
    dialog.show()
    qtbot.waitExposed(dialog)
    groups = [dialog.system.topLevelItem(i) for i in range(dialog.system.topLevelItemCount())]
    assert [g.text(0) for g in groups] == ["APC read parameters"]
    names = [groups[0].child(i).text(0) for i in range(groups[0].childCount())]
    assert names[:3] == ["APC_POS_CTRL_EN", "APC_ABS_MODE", "APC_POS_RST_OFF"] and "APC_FB_POS" in names
    item = groups[0].child(names.index("APC_FB_POS"))
    dialog.system.scrollToItem(item)
    double_click(qtbot, dialog.system, dialog.system.visualItemRect(item).center())
    row = dialog.program.item(pane.variables.index("N%"))
    double_click(qtbot, dialog.program, dialog.program.visualItemRect(row).center())
    window.actions_by_text["Watch Start"].trigger()
    qtbot.waitUntil(lambda: pane.values()[0] not in ("", "0"), timeout=10_000)
    assert [e.label for e in pane.entries] == ["Axis 1: APC_FB_POS", "N%"]
    assert int(pane.values()[1]) > 0
