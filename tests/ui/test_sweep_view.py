"""Tools ▸ Sweep Results (issue 30 item 2: "The IDE shows a finished sweep as a table and a heat map or line plot
(pyqtgraph) and can open any point's run in the scope"), used as an engineer does: a sweep run on the command line,
its CSV opened from the menu, a cell of the heat map clicked, the point opened in the oscilloscope.

DG 8649-8653: a larger KPROP makes the axis stiffer (less tracking error): the heat map shows it."""

from __future__ import annotations

import pyqtgraph as pg
from PySide6.QtCore import QPointF, Qt

from motiontool import cli
from motiontool.scope.ui.window import ScopeWindow
from motiontool.ui.sweep_view import SweepView
from tests.modal import answering, file_reply
from tests.shots import shot_path

PROGRAM = "POSA 204800\n"


def sweep(tmp_path, capsys, *args) -> tuple:
    program = tmp_path / "move.m"
    program.write_text(PROGRAM, encoding="utf-8")
    out = tmp_path / "sweep.csv"
    code = cli.main(["sweep", str(program), *args, "--seconds", "1", "--jobs", "1", "-o", str(out),
                     "--measure", "max(abs(TRACKERR))", "--measure", "last(APOS)"])
    assert code == 0, capsys.readouterr().err
    return program, out


def open_results(qtbot, window, csv_path) -> SweepView:
    with answering(qtbot, file_reply(csv_path)):
        window.actions_by_text["Sweep Results..."].trigger()
    qtbot.waitUntil(lambda: any(isinstance(v, SweepView) and v.isVisible() for v in window.findChildren(SweepView)),
                    timeout=5000)
    view = window.findChildren(SweepView)[-1]
    qtbot.waitExposed(view)
    return view


def test_a_two_parameter_sweep_as_a_heat_map_a_clicked_cell_opens_in_the_scope(window, qtbot, tmp_path, capsys):
    program, csv_path = sweep(tmp_path, capsys, "--vary", "32-60=10:70:30", "--vary", "32-61=0:100:100")
    window.open_file(program)                                # the program in the editor is offered for the runs
    view = open_results(qtbot, window, csv_path)
    assert view.table.rowCount() == 6 and view.program.text() == str(program)
    images = [i for i in view.plot.getPlotItem().items if isinstance(i, pg.ImageItem)]
    assert len(images) == 1 and images[0].image.shape == (3, 2)      # KPROP 10/40/70 × KDER 0/100
    errors = images[0].image
    assert errors[0, 0] > errors[2, 0] > 0                           # stiffer with a larger KPROP (DG 8649-8653)

    # the measure chosen with the keyboard, as a person does
    qtbot.keyClick(view.measure, Qt.Key.Key_Down, delay=120)     # the closed box, as after a Tab to it
    qtbot.waitUntil(lambda: view.measure.currentText() == "last(APOS)", timeout=3000)
    images = [i for i in view.plot.getPlotItem().items if isinstance(i, pg.ImageItem)]
    assert len(images) == 1 and abs(images[0].image[1, 1]) > 0

    # a click on the cell KPROP 70, KDER 100 selects that point in the table
    vb = view.plot.getPlotItem().vb
    scene = vb.mapViewToScene(QPointF(2.5, 1.5))
    pos = view.plot.mapFromScene(scene)
    qtbot.mouseClick(view.plot.viewport(), Qt.MouseButton.LeftButton, pos=pos)
    qtbot.waitUntil(lambda: bool(view.table.selectionModel().selectedRows()), timeout=3000)
    row = view.table.selectionModel().selectedRows()[0].row()
    assert view.results.points[row].tolist() == [70, 100]
    x, y = view._mark.getData()
    assert (list(x), list(y)) == ([2.5], [1.5])                     # the chosen cell is marked on the map
    assert "KPROP" in view.plot.getAxis("bottom").labelText and "KDER" in view.plot.getAxis("left").labelText
    view.grab().save(str(shot_path("sweep_view.png")))

    qtbot.mouseClick(view.seconds, Qt.MouseButton.LeftButton)       # the sweep's --seconds 1
    qtbot.keyClick(view.seconds, Qt.Key.Key_A, Qt.KeyboardModifier.ControlModifier, delay=120)
    qtbot.keyClicks(view.seconds, "1", delay=120)
    assert view.seconds.value() == 1.0
    qtbot.mouseClick(view.open_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: any(s.isVisible() for s in view.scopes), timeout=30000)
    scope = view.scopes[-1]
    assert isinstance(scope, ScopeWindow) and "point 6" in scope.windowTitle()
    names = [c.name for c in scope.scope.curves]
    assert {"TRACKERR", "APOS", "CPOS"} <= set(names)
    t, apos = scope.scope.curve("APOS").raw()
    assert t.size > 900 and apos[-1] == view.results.values[row, 1]   # the same run as the sweep's point
    assert "opened in the oscilloscope" in view.status.text()
    scope.close()
    view.close()


def test_one_parameter_is_a_line_and_a_failed_point_stays_red_with_its_error(window, qtbot, tmp_path, capsys):
    _program, csv_path = sweep(tmp_path, capsys, "--vary", "32-60=-10:50:30")   # KPROP -10 is refused
    view = open_results(qtbot, window, csv_path)
    assert view.results.failed == 1 and view.table.rowCount() == 3
    failed = view.table.item(0, view.table.columnCount() - 1)
    assert "32-60=-10" in failed.text() and failed.toolTip() == failed.text()
    assert not [i for i in view.plot.getPlotItem().items if isinstance(i, pg.ImageItem)]
    (line,) = [i for i in view.plot.getPlotItem().listDataItems() if isinstance(i, pg.PlotDataItem)]
    x, _y = line.getData()
    assert list(x) == [-10, 20, 50]
    assert view.program.text() == ""                        # no program open: it is asked for
    qtbot.mouseClick(view.table.viewport(), Qt.MouseButton.LeftButton,
                     pos=view.table.visualItemRect(view.table.item(1, 0)).center())
    qtbot.mouseClick(view.open_button, Qt.MouseButton.LeftButton)
    assert "Give the swept program" in view.status.text()
    view.close()


def test_a_file_that_is_no_sweep_is_said_and_nothing_opens(window, qtbot, tmp_path):
    bad = tmp_path / "other.csv"
    bad.write_text("a,b\n1,2\n", encoding="utf-8")
    seen = []

    def say(box):
        seen.append(box.text())
        box.accept()

    with answering(qtbot, file_reply(bad), say):
        window.actions_by_text["Sweep Results..."].trigger()
    assert seen and "other.csv, line 1: not a sweep's CSV" in seen[0]
    assert not [v for v in window.findChildren(SweepView) if v.isVisible()]
