"""The oscilloscope's numbers on a controller that has been up for hours (issue 23 item 8): the time axis read
`1.3244e+06` ms, values were in scientific notation, the live window was ~1 s and kept the last zoom, a second
Load TESTSETP added the same set again and a TESTSETP set was read against an empty curve's 0..1 axis.

DG 4737: "the time is derived from the controller's internal clock. As a result, test runs will not start at
time 0. The "Shift to 0" toolbar button can be used to reset the start time to 0, making the chart more
readable." DG 5967: "The *Origin* setting determines the initial state of the Shift to 0 toggle button."
"""

import re

import pytest
from PySide6.QtCore import Qt
from PySide6.QtGui import QImage, QPainter

from motiontool.controller.embedded import EmbeddedLink
from motiontool.scope.numbers import GROUP
from motiontool.scope.ui import ScopeWindow
from motiontool.scope.ui.curve_list import MAX
from tests.scope.test_acquisition import TESTSETP
from tests.scope.ui.test_scope_window import POSA, click, run_for, shot, start_program

UP_MS = 5 * 3_600_000 + 1_234_567     # up for five hours, as a real controller is
GROUP_NAME = "Test Group (Free Run)"


def drawn_texts(axis) -> list[str]:
    """The tick labels the axis draws (pyqtgraph's own layout of them)."""
    image = QImage(axis.width() or 80, axis.height() or 80, QImage.Format.Format_ARGB32)
    painter = QPainter(image)
    try:
        specs = axis.generateDrawSpecs(painter)
    finally:
        painter.end()
    return [text for _rect, _flags, text in specs[2]] if specs else []


def up_for_hours() -> EmbeddedLink:
    link = EmbeddedLink()
    link.service.controller.time_ms = UP_MS
    return link


def window(qtbot, link, variant="free_run"):
    w = ScopeWindow(link, variant, ask=False)
    qtbot.addWidget(w)
    w.show()
    qtbot.waitExposed(w)
    return w


def test_a_recording_on_a_controller_up_for_hours_reads_from_0_with_grouped_values(qtbot, tmp_path):
    link = up_for_hours()
    w = window(qtbot, link)
    w.add_signal_curve("APOS", group=GROUP_NAME)
    w.add_signal_curve("CPOS", group=GROUP_NAME)
    start_program(link, POSA)
    click(qtbot, w, w.start_action)
    run_for(w, link, 6000)
    click(qtbot, w, w.stop_action)
    assert w.shift_action.isChecked()      # a new window: Origin "Relative"
    times = drawn_texts(w.chart.time_axis)
    assert times and times[0] == "0" and not any("e" in t for t in times), times
    assert max(float(t) for t in times) < 7   # seconds from the recording's start, not hours of uptime
    assert w.chart.time_axis.labelText == "time from the recording's start [s]"
    values = drawn_texts(w.chart.left_axis)
    assert values and not any("e" in v for v in values) and any(GROUP in v for v in values), values
    assert w.list.item_for("1: APOS").text(MAX) == f"100{GROUP}000"
    click(qtbot, w, w.cursor_a)
    number, unit = re.match(r"A ([\d.\u2009]+) (m?s)", w.readout.text()).groups()
    assert 0 < float(number.replace(GROUP, "")) / (1000 if unit == "ms" else 1) < 6, w.readout.text()
    click(qtbot, w, w.cursor_b)
    assert re.search(r"Δt [\d.]+ s", w.readout.text()), w.readout.text()
    qtbot.wait(50)   # the status bar lays the longer read-out out before the picture
    shot(w, "readable", tmp_path)
    click(qtbot, w, w.shift_action)        # Shift to 0 off: the controller's clock, still no exponent
    absolute = drawn_texts(w.chart.time_axis)
    assert w.chart.time_axis.labelText == "controller time [s]"
    assert absolute and all(t.startswith(f"19{GROUP}2") for t in absolute), absolute   # 5 h = 18 000 s


def test_the_live_window_is_a_setting_of_10_s_and_does_not_keep_the_last_zoom(qtbot):
    link = up_for_hours()
    w = window(qtbot, link)
    w.add_signal_curve("APOS", group=GROUP_NAME)
    start_program(link, POSA)
    assert w.live_box.value() == 10
    click(qtbot, w, w.start_action)
    run_for(w, link, 3000)
    (x0, x1), _ = w.chart.view.viewRange()
    assert x1 - x0 == pytest.approx(10_000, rel=0.01) and abs(x0) < 100   # fills from the left
    run_for(w, link, 10_000)
    (x0, x1), _ = w.chart.view.viewRange()
    newest = w.scope.time_span()[1] - w.chart.origin()
    assert x1 - x0 == pytest.approx(10_000, rel=0.01) and x0 <= newest <= x1 + 60
    click(qtbot, w, w.stop_action)         # Zoom Reset: all 13 s
    w.live_box.setFocus()
    w.live_box.selectAll()
    qtbot.keyClicks(w.live_box, "4", delay=120)
    qtbot.keyClick(w.live_box, Qt.Key.Key_Return)
    assert w.live_box.value() == 4
    click(qtbot, w, w.start_action)
    run_for(w, link, 6000)
    (x0, x1), _ = w.chart.view.viewRange()
    assert x1 - x0 == pytest.approx(4_000, rel=0.01)
    click(qtbot, w, w.stop_action)


def test_testsetp_is_drawn_against_its_own_axis_and_a_second_load_adds_nothing(qtbot):
    link = up_for_hours()
    start_program(link, TESTSETP)
    link.advance(3000)
    w = window(qtbot, link)
    w.add_signal_curve("APOS")             # polled, never recorded: empty
    click(qtbot, w, w.mode_actions["testsetp"])
    recorded = [c for c in w.scope.curves if c.source.method == "testsetp"]
    assert len(recorded) == 3
    assert len(w.scope.curve(w.chart.left_curve).buffer) > 0     # not the empty curve's 0..1
    assert len({c.colour for c in w.scope.curves}) == len(w.scope.curves)
    click(qtbot, w, w.load_action)
    assert len(w.scope.curves) == 4 and "shown already" in w.statusBar().currentMessage()
    times = drawn_texts(w.chart.time_axis)
    assert times[0] == "0" and not any("e" in t for t in times), times
