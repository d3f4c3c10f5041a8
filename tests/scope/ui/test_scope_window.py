"""The oscilloscope window against the embedded simulated controller (pytest-qt, real widgets, no mocks).

Screenshots land in $MOTIONTOOL_SHOTS (default: pytest's tmp dir) for a person to look at."""

import os
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from PySide6.QtCore import QSettings, Qt
from PySide6.QtWidgets import QApplication, QMessageBox, QToolButton

from motiontool.aposs.driver import compile_source
from motiontool.controller.embedded import EmbeddedLink
from motiontool.scope.curves import smooth
from motiontool.scope.derived import DerivedSpec, compute
from motiontool.scope.numbers import GROUP
from motiontool.scope.ui import ScopeWindow, open_scope, open_scope_file
from motiontool.scope.ui.curve_list import ACTIVE, BA, GRID, LAST, MAX, STATUS, A
from motiontool.scope.ui.dialogs import RecordingDialog
from tests.modal import answering, button_reply
from tests.scope.ui.mouse import drag, to_pixel

POSA = "VEL 20\nACC 50\nDEC 50\nPOSA 100000\nDELAY 300\n"


def shot(widget, name, tmp_path):
    folder = Path(os.environ.get("MOTIONTOOL_SHOTS", tmp_path))
    folder.mkdir(parents=True, exist_ok=True)
    widget.grab().save(str(folder / f"scope_{name}.png"))


def start_program(link, source):
    result = compile_source(source, "p.m")
    assert result.ok, [d.format() for d in result.diagnostics]
    link.download(result.image.to_bytes())
    link.start()


def click(qtbot, window, action):
    button = next(b for b in window.findChildren(QToolButton) if b.defaultAction() is action)
    assert button.isEnabled()
    qtbot.mouseClick(button, Qt.LeftButton)


def run_for(window, link, ms, step=50):
    for _ in range(ms // step):
        link.advance(step)
        window.run.tick()
        answered(window)


def answered(window) -> None:
    """The scope asks the recording's status and its polls on threads of their own: let them answer, as the
    window's event loop does between two display refreshes."""
    deadline = time.monotonic() + 10
    while (window.run.status_job.busy or window.run.poll_job.busy) and time.monotonic() < deadline:
        QApplication.processEvents()
        time.sleep(0.001)


@pytest.fixture
def link():
    return EmbeddedLink()


@pytest.fixture
def make(qtbot):
    def make(link, variant, **kw):
        w = ScopeWindow(link, variant, ask=False, **kw)
        qtbot.addWidget(w)
        w.show()
        return w
    return make


def test_free_run_posa_trapezoid_and_tracking_error(qtbot, link, make, tmp_path):
    """DG 4638-4648 / ide-spec S20: a Free Run group of APOS, CPOS, TRACKERR draws live during a POSA: the
    velocity is a trapezoid and the tracking error grows while the axis accelerates."""
    w = make(link, "free_run")
    group = "Test Group (Free Run)"
    assert [g.name for g in w.scope.groups] == [group]
    for signal in ("APOS", "CPOS", "TRACKERR"):
        w.add_signal_curve(signal, group=group)
    click(qtbot, w, w.start_action)
    start_program(link, POSA)
    run_for(w, link, 1000)
    assert w.run.running and not w.chart.region.isVisible()  # navigation not drawn while recording (DG 5843)
    x, _ = w.chart.items["1: CPOS"].getData()
    assert x is not None and x.size > 10                  # drawn live
    run_for(w, link, 5000)
    click(qtbot, w, w.stop_action)
    assert link.status().program_state in ("running", "ended")  # Stop ends only the recording (DG 4627, 5859)
    cpos = w.scope.curve("1: CPOS")
    vel = smooth(compute(DerivedSpec("derivative", cpos.name), lambda n: w.scope.curve(n).raw())[1], 5)
    moving = np.nonzero(vel > 100)[0]
    v = vel[moving[0]:moving[-1] + 1]
    flat = np.nonzero(v > 0.98 * v.max())[0]
    assert flat[-1] - flat[0] > 0.5 * v.size and flat[0] > 100 and v.size - flat[-1] > 100
    te = w.scope.curve("1: TRACKERR").raw()[1][moving[0]:moving[0] + flat[0]]
    assert np.all(np.diff(te[5:-5]) >= 0) and te[-5] > 5 * max(te[5], 1.0)
    item = w.list.item_for("1: APOS")
    # grouped by thin spaces (issue 23 item 8)
    assert float(item.text(MAX).replace(GROUP, "")) == pytest.approx(100000, abs=1)
    assert item.text(LAST) == "100\u2009000"
    assert w.chart.region.isVisible()
    w.chart.left_curve, w.chart.right_curve = "1: CPOS", "1: TRACKERR"
    w.redraw()
    shot(w, "free_run", tmp_path)


def test_pause_then_start_keeps_the_data_and_marks_the_pause(qtbot, link, make):
    """DG 5943: Pause then Start keeps the data and draws a red bar where recording paused."""
    w = make(link, "free_run")
    w.add_signal_curve("4119", group="Test Group (Free Run)")
    click(qtbot, w, w.start_action)
    run_for(w, link, 200)
    click(qtbot, w, w.pause_action)
    link.advance(100)
    click(qtbot, w, w.start_action)
    run_for(w, link, 200)
    click(qtbot, w, w.stop_action)
    t = w.scope.curves[0].raw()[0]
    assert t[0] <= 20 and t[-1] >= 480 and len(w.scope.pauses) == 1 and len(w.chart.pause_lines) == 1
    assert np.max(np.diff(t)) >= 100   # the gap of the pause


def test_single_shot_at_1_ms_uploads_exactly_the_configured_count(qtbot, link, make, tmp_path):
    """DG 5287-5324, 5867-5869 / ide-spec S22: the recording dialog, nothing drawn while recording; a recording
    that stops when full has ended then, and "when the run ends, the Oscilloscope will upload" (DG 5434) exactly
    the fixed count of sets at the sample interval, without Stop (issue 23 item 11: it waited for Stop)."""
    w = make(link, "single_shot")
    group = w.scope.group("Test Group (Single Shot)")
    dialog = RecordingDialog(group, w)
    dialog.fixed.setChecked(True)
    dialog.count.setValue(750)
    dialog.interval.setValue(1)
    dialog.stop_full.setChecked(True)
    dialog.accept()
    assert (group.count, group.interval_ms, group.cyclic, group.destination) == (750, 1, False, "DYNMEM")
    for signal in ("4097", "4098", "4102"):
        w.add_signal_curve(signal, group=group.name)
    start_program(link, POSA)
    click(qtbot, w, w.start_action)
    run_for(w, link, 700)
    assert all(len(c.buffer) == 0 for c in w.scope.curves)   # nothing drawn while recording
    assert "[recording " in w.windowTitle()
    run_for(w, link, 1300)                                    # full at 750 ms: uploaded without Stop
    assert not w.run.single_shot.running and "[recording" not in w.windowTitle()
    for c in w.scope.curves:
        t, _ = c.raw()
        assert t.size == 750 and set(np.diff(t)) == {1.0}
    assert w.list.item_for("1: REG_ACTPOS [4097]") is not None
    shot(w, "single_shot", tmp_path)


def test_testsetp_scope_finds_the_programs_recording(qtbot, link, make, tmp_path):
    """DG 5326-5347 / ide-spec S23: uploaded automatically, one curve per value, the first grey, names
    "Axis: Name [Index]", Active empty and Start disabled."""
    start_program(link, "DIM test[3000]\nTESTSETP 1 4097 4098 0x01270001 test\nTESTSTART 0\nPOSA 20000\n"
                        "DELAY 100\nTESTSTOP 0\n")
    link.advance(3000)
    w = make(link, "testsetp")
    names = [c.name for c in w.scope.curves]
    assert names[:2] == ["1: REG_ACTPOS [4097]", "1: REG_COMPOS [4098]"] and len(names) == 3
    item = w.list.item_for(names[0])
    assert item.background(0).color().name() == "#d8d8d8"
    assert item.data(ACTIVE, Qt.CheckStateRole) is None        # Active column empty
    assert not w.start_action.isEnabled()
    shot(w, "testsetp", tmp_path)


def test_tune_shows_overshoot_for_a_high_kprop_and_less_after_lowering_it(qtbot, link, make, tmp_path):
    """ide-spec 6.60 (DECISION), DG 8638-8653: change KPROP and repeat; runs overlaid."""
    w = make(link, "tune")
    panel = w.tune_panel
    assert w.tune_dock.isVisible() and panel.pid["KPROP"].value() == 30
    results = []
    for kprop in (20000, 3000):
        panel.pid["KPROP"].setValue(kprop)
        qtbot.mouseClick(panel.run, Qt.LeftButton)
        assert not panel.run.isEnabled()
        link.advance(2500)
        qtbot.waitUntil(lambda: panel.run.isEnabled(), timeout=3000)
        results.append(w.run.tune.results[-1])
    high, low = results
    assert high.overshoot > 5 and low.overshoot < high.overshoot / 2
    assert panel.results.rowCount() == 2 and panel.results.item(0, 1).text() == "20000"
    assert [g.name for g in w.scope.groups] == ["Tune run 1", "Tune run 2"] and len(w.scope.curves) == 8
    assert "overshoot" in panel.state.text()
    shot(w, "tune", tmp_path)
    for c in w.scope.curves:   # the spectrum of the ringing of run 1 (KPROP 20000)
        c.visible = c.name == "Run 1: TRACKERR"
    fft = w.show_fft()
    qtbot.addWidget(fft)
    f, a = fft.spectra["Run 1: TRACKERR"]
    assert list(fft.spectra) == ["Run 1: TRACKERR"] and f[-1] == pytest.approx(500, abs=1)  # 1 ms samples
    shot(fft, "fft", tmp_path)


def test_cursors_read_the_right_delta_t(qtbot, link, make):
    """DG 4781-4787, 5030-5038: cursors A and B; columns A, B, B−A; Δt and 1/Δt."""
    w = make(link, "free_run")
    w.add_signal_curve("4119", group="Test Group (Free Run)")   # sys_clock: value = time
    click(qtbot, w, w.start_action)
    run_for(w, link, 1000)
    click(qtbot, w, w.stop_action)
    click(qtbot, w, w.cursor_a)
    click(qtbot, w, w.cursor_b)
    plot, view = w.chart.plot, w.chart.view
    for i, target in ((0, 200.0), (1, 450.0)):   # right-drag the line (ide-spec 6.8)
        drag(qtbot, plot, to_pixel(plot, view, w.scope.cursors[i], 0.5), to_pixel(plot, view, target, 0.5),
             Qt.MouseButton.RightButton)
        assert w.scope.cursors[i] == pytest.approx(target, abs=3)
    ta, tb = w.scope.cursors
    assert f"Δt {tb - ta:.1f} ms" in w.readout.text() and f"1/Δt {1000 / (tb - ta):.4g} Hz" in w.readout.text()
    item = w.list.item_for(w.scope.curves[0].name)
    assert float(item.text(BA)) == pytest.approx(tb - ta, abs=1.5)   # sys_clock: the value is the time
    assert w.list.headerItem().text(A) == f"A {ta - w.chart.origin():.0f}ms"   # as the time axis reads


def test_polling_title_shows_rate_and_load(qtbot, link, make, tmp_path):
    """DG 5406-5418 / ide-spec S21: "[<poll ms>ms <load>%]" while recording."""
    w = make(link, "polling")
    w.poll_box.setValue(50)
    assert w.scope.settings.poll_ms == 50
    w.add_signal_curve("APOS")
    w.add_signal_curve("KPROP")
    click(qtbot, w, w.start_action)
    assert w.windowTitle().endswith("[50ms 9%]")
    start_program(link, POSA)
    for k in range(60):              # the poll timer reads on the poll thread: one sample per controller instant
        link.advance(50)
        qtbot.waitUntil(lambda k=k: w.run.polling.polls == k + 1, timeout=5000)
    click(qtbot, w, w.stop_action)
    assert len(w.scope.curve("1: KPROP").buffer) == 60
    assert w.list.item_for("1: APOS").parent().text(0) == "Other Curves"   # polled: no group (DG 5406)
    shot(w, "polling", tmp_path)


def test_a_poll_of_a_stopped_run_that_answers_late_is_not_taken_into_the_next(qtbot, link, make):
    """The polls' reads go on a thread of their own (issue 27 item 2); Stop then Start while a read is on a slow
    line: its answer, of the old run, must not land in the new run's emptied curves."""
    w = make(link, "polling")
    w.poll_box.setValue(50)
    w.add_signal_curve("APOS")
    held, reads = threading.Event(), []
    plain = link.read_signals

    def slow_line(signals):
        values = plain(signals)
        reads.append(values[-1])   # the controller's time, read last
        if len(reads) == 1:
            held.wait(10)          # the first poll's answer (of time 0) is late
        return values

    link.read_signals = slow_line
    click(qtbot, w, w.start_action)
    qtbot.waitUntil(lambda: len(reads) == 1, timeout=5000)
    click(qtbot, w, w.stop_action)
    link.advance(500)
    click(qtbot, w, w.start_action)           # a new run while the old read is still on the line
    held.set()
    qtbot.waitUntil(lambda: w.run.polling.polls >= 1 and not w.run.poll_job.busy, timeout=5000)
    click(qtbot, w, w.stop_action)
    t, _ = w.scope.curve("1: APOS").raw()
    assert t.size >= 1 and t.min() >= 500        # only samples of the new run


def test_saved_file_reopens_offline_with_its_data(qtbot, link, make, tmp_path):
    """DG 5277-5285 / ide-spec S20.6: reopened, the data is there, Status is white, nothing connected."""
    w = make(link, "free_run")
    w.add_signal_curve("4119", group="Test Group (Free Run)")
    click(qtbot, w, w.start_action)
    run_for(w, link, 300)
    click(qtbot, w, w.stop_action)
    w.save_to(tmp_path / "t.zbo")
    again = open_scope_file(tmp_path / "t.zbo")
    qtbot.addWidget(again)
    assert again.link is None and len(again.scope.curves[0].buffer) == len(w.scope.curves[0].buffer)
    assert again.list.item_for(again.scope.curves[0].name).background(STATUS).color().name() == "#ffffff"
    assert "t.zbo" in again.windowTitle()


def test_open_scope_from_the_main_window(qtbot, tmp_path):
    """DG 5265-5273: the scope binds to the APOSS window's controller, connecting the default one."""
    from motiontool.ui.main_window import MainWindow

    settings = QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat)
    main = MainWindow(settings=settings, realtime_factor=20.0)
    qtbot.addWidget(main)
    try:
        scope = open_scope(main.bridge, parent=main, settings=main.settings)
        assert scope.link is main.bridge.link is not None
        scope.add_signal_curve("4119", group="Test Group (Free Run)")
        click(qtbot, scope, scope.start_action)
        qtbot.waitUntil(lambda: len(scope.scope.curves[0].buffer) > 20, timeout=5000)
        click(qtbot, scope, scope.stop_action)
        samples = len(scope.scope.curves[0].buffer)
        with answering(qtbot, button_reply(QMessageBox.StandardButton.Cancel)) as answers:
            scope.delete_action.trigger()  # Delete data asks too (issue 23 item 11); Cancel keeps the samples
        assert answers.seen == ["QMessageBox 'Oscilloscope'"] and len(scope.scope.curves[0].buffer) == samples
        with answering(qtbot, button_reply(QMessageBox.StandardButton.Discard)) as answers:
            scope.close()  # an unsaved recording: the user is asked (issue 23 item 9)
        assert answers.seen == ["QMessageBox 'Oscilloscope'"] and not scope.isVisible()
    finally:
        main.bridge.detach(close=False)
        main.controllers.close()


def test_curve_properties_scale_validate_smooth_and_share(qtbot, link, make, tmp_path):
    """ide-spec S24 (DG 5125-5161, 5191-5225): scaling offset 0 scale 0.1 divides Last/Min/Max by 10; a
    maximum of 4900 paints cells red; smoothing 2 averages 5 points in the chart while the list stays raw;
    a shared axis uses the other curve's range; Center zero makes the range symmetric after Zoom Reset."""
    from motiontool.scope.ui.curve_list import MIN
    from motiontool.scope.ui.dialogs import PropertiesDialog

    w = make(link, "free_run")
    group = "Test Group (Free Run)"
    w.add_signal_curve("APOS", group=group)
    w.add_signal_curve("CPOS", group=group)
    click(qtbot, w, w.start_action)
    start_program(link, POSA)
    run_for(w, link, 6000)
    click(qtbot, w, w.stop_action)
    item = w.list.item_for("1: APOS")
    assert item.text(MAX) == "100\u2009000"
    dialog = PropertiesDialog(w.scope.curve("1: APOS"), [c.name for c in w.scope.curves], w)
    dialog.scaling.setChecked(True)
    dialog.offset.setValue(0)
    dialog.scale.setValue(0.1)
    dialog.high.setText("4900")
    dialog.smoothing.setValue(2)
    dialog.center_zero.setChecked(True)
    dialog.zero_mark.setChecked(True)
    dialog.accept()
    assert w.edit_properties("1: APOS", dialog=dialog)
    item = w.list.item_for("1: APOS")
    assert item.text(MAX) == "10\u2009000" and item.text(MIN) == "0"
    assert item.background(MAX).color().name() == "#ff9090" and item.background(MIN).style() == Qt.NoBrush
    curve = w.scope.curve("1: APOS")
    lo, hi = w.chart.range_of(curve)
    assert lo == -hi
    (mark,) = w.chart.zero_marks.points()       # "a small triangle on the left edge at y = 0" (DG 5199-5203)
    assert mark.pos().y() == pytest.approx(0.5)
    raw = curve.scaled(curve.raw()[1])
    assert curve.display()[1][100] == pytest.approx(raw[98:103].mean())
    share = PropertiesDialog(w.scope.curve("1: CPOS"), [c.name for c in w.scope.curves], w)
    share.share.setCurrentText("1: APOS")
    share.accept()
    w.edit_properties("1: CPOS", dialog=share)
    assert w.chart.range_of(w.scope.curve("1: CPOS")) == (lo, hi)
    shot(w, "properties", tmp_path)


def test_triggered_free_run_stops_after_one_capture(qtbot, link, make, tmp_path):
    """Beyond the manual: a single triggered capture with pre-trigger samples, then the run ends itself."""
    from motiontool.scope.ui.dialogs import TriggerDialog

    w = make(link, "free_run")
    w.add_signal_curve("CPOS", group="Test Group (Free Run)")
    w.add_signal_curve("TRACKERR", group="Test Group (Free Run)")
    dialog = TriggerDialog([c.name for c in w.scope.curves], w)
    dialog.enabled.setChecked(True)
    dialog.curve.setCurrentText("1: CPOS")
    dialog.level.setValue(500)
    dialog.pre.setValue(100)
    dialog.post.setValue(400)
    dialog.accept()
    w.run.trigger_dialog(dialog=dialog)
    click(qtbot, w, w.start_action)
    run_for(w, link, 300)
    assert w.run.running and len(w.scope.curves[0].buffer) == 0   # armed, waiting
    start_program(link, POSA)
    run_for(w, link, 2000)
    assert not w.run.running and w.run.free_run.captures == 1
    t, y = w.scope.curve("1: CPOS").raw()
    assert t.size == 500 and y[99] < 500 <= y[100]
    shot(w, "trigger", tmp_path)


def test_add_curve_dialog_adds_polled_and_derived_curves(qtbot, link, make):
    """DG 5406-5418: "Polled (no group)" curves go under Other Curves; DG 5630-5674: a Difference derived curve
    sits right after its base curve."""
    from motiontool.scope.ui.dialogs import AddCurveDialog

    w = make(link, "free_run")
    w.add_signal_curve("APOS", group="Test Group (Free Run)")
    dlg = AddCurveDialog([g.name for g in w.scope.groups], [c.name for c in w.scope.curves], w)
    dlg.signal.setText("CPOS")
    dlg.method.setCurrentText("Polled (no group)")
    w.add_curve_dialog(dlg=dlg)
    assert w.scope.curve("1: CPOS").source.method == "polled"
    assert w.list.item_for("1: CPOS").parent().text(0) == "Other Curves"
    dlg = AddCurveDialog([g.name for g in w.scope.groups], [c.name for c in w.scope.curves], w)
    dlg.kind.setCurrentText("Derived")
    dlg.derived_kind.setCurrentText("difference")
    dlg.base.setCurrentText("1: APOS")
    dlg.second.setCurrentText("1: CPOS")
    dlg.name.setText("APOS - CPOS")
    w.add_curve_dialog(dlg=dlg)
    assert [c.name for c in w.scope.curves] == ["1: APOS", "APOS - CPOS", "1: CPOS"]


def test_status_colours_for_running_error_and_lost(qtbot, link, make):
    """DG 4916-4944 / ide-spec 6.14, S21.3: bright green running, dark green idle, red error (DECISION),
    orange lost (DECISION)."""
    w = make(link, "free_run")
    w.add_signal_curve("APOS", group="Test Group (Free Run)")

    def colour(expected: str) -> None:
        """Ask the state again; the answer comes from a thread (issue 27 item 2: the scope never waits for it)."""
        w._on_status(None)
        qtbot.waitUntil(lambda: w.list.item_for("1: APOS").background(STATUS).color().name() == expected,
                        timeout=10_000)

    colour("#006400")
    start_program(link, "DELAY 1000\n")
    link.advance(10)
    colour("#00e000")
    link.advance(1000)
    start_program(link, "DIM a[2]\na[5] = 1\n")   # index outside the array: a controller error
    link.advance(10)
    colour("#e00000")
    link.close()
    colour("#ff9900")


def test_grid_column_gives_a_curve_the_left_or_right_axis(qtbot, link, make):
    """DG 4878-4912 / ide-spec 6.13: one curve owns each axis side; a shared curve shows an up-arrow."""
    w = make(link, "free_run")
    for signal in ("APOS", "CPOS", "TRACKERR"):
        w.add_signal_curve(signal, group="Test Group (Free Run)")
    w.scope.curve("1: CPOS").axis.share = "1: APOS"
    w.redraw()
    assert (w.chart.left_curve, w.chart.right_curve) == ("1: APOS", "1: TRACKERR")
    item = w.list.item_for("1: TRACKERR")
    rect = w.list.visualItemRect(item)
    x = w.list.header().sectionPosition(GRID) + 5
    qtbot.mouseClick(w.list.viewport(), Qt.LeftButton, pos=rect.topLeft().__class__(x, rect.center().y()))
    assert w.chart.left_curve == "1: TRACKERR" and w.chart.right_curve == "1: APOS"
    assert item.text(GRID) == "L" and w.list.item_for("1: APOS").text(GRID) == "R"
    assert w.list.item_for("1: CPOS").text(GRID) == "↑R"
    assert w.chart.left_axis.labelText.startswith("1: TRACKERR")


@pytest.mark.parametrize("variant, group", [("single_shot", "Test Group (Single Shot)"),
                                            ("free_run", "Test Group (Free Run)")])
def test_add_curve_offers_the_group_the_variant_records_with(qtbot, link, make, variant, group):
    """Issue 23 item 11: Add Curve in the Single Shot scope offered the Free Run group first (DG 5428: Free Run
    groups only in the Free Run scope, Single Shot groups only in the Single Shot scope)."""
    from motiontool.scope.ui.dialogs import AddCurveDialog

    w = make(link, "free_run")
    w.set_variant(variant)
    seen = {}

    def look(dialog):
        assert isinstance(dialog, AddCurveDialog)
        seen["group"] = dialog.method.currentText()
        dialog.reject()

    with answering(qtbot, look):
        w.add_action.trigger()
    assert seen["group"] == group
