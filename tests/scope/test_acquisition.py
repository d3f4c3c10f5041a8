"""Acquisition through the embedded link (the real simulated controller, no mocks)."""

import numpy as np
import pytest

from motiontool.aposs.driver import compile_source
from motiontool.controller.embedded import EmbeddedLink
from motiontool.scope.acquisition import (
    FreeRun,
    Polling,
    SingleShot,
    default_group,
    list_testsetp,
    load_testsetp,
    new_curve,
    polling_load,
    reload_testsetp,
)
from motiontool.scope.curves import Scope, smooth
from motiontool.scope.derived import DerivedSpec, compute
from motiontool.scope.tune import Tune

POSA = "VEL 20\nACC 50\nDEC 50\nPOSA 100000\nDELAY 200\n"
TESTSETP = "DIM test[3000]\nTESTSETP 1 4097 4098 0x01270001 test\nTESTSTART 0\nPOSA 2000\nDELAY 1500\nTESTSTOP 0\n"


def start(link, source):
    result = compile_source(source, "p.m")
    assert result.ok, [d.format() for d in result.diagnostics]
    link.download(result.image.to_bytes())
    link.start()


def test_free_run_of_a_posa_shows_a_trapezoid_and_tracking_error_growing_while_accelerating():
    """DG 4638-4648: Free Run streams the group live. A POSA is a trapezoid: accelerate, constant velocity,
    decelerate; the tracking error of a P controller grows with the commanded acceleration."""
    link = EmbeddedLink()
    scope = Scope("free_run")
    group = default_group(scope, "free_run")
    assert group.name == "Test Group (Free Run)"
    for signal in ("APOS", "CPOS", "TRACKERR"):
        new_curve(scope, signal, group.name, "free_run")
    run = FreeRun(scope, link, group.name, subscribe=True)
    run.start()
    start(link, POSA)
    link.advance(6000)
    run.stop()
    cpos = scope.curve("1: CPOS")
    t, y = cpos.raw()
    assert t.size > 5000 and np.all(np.diff(t) == 1) and run.dropped == 0
    vel = smooth(compute(DerivedSpec("derivative", cpos.name), lambda n: scope.curve(n).raw())[1], 5)
    moving = np.nonzero(vel > 100)[0]
    v = vel[moving[0]:moving[-1] + 1]
    peak = v.max()
    flat = np.nonzero(v > 0.98 * peak)[0]
    assert flat[-1] - flat[0] > 0.5 * v.size                  # a long constant-velocity phase …
    ramp_up, ramp_down = v[:flat[0]], v[flat[-1]:]
    assert ramp_up.size > 100 and ramp_down.size > 100        # … between an acceleration and a deceleration
    assert np.all(np.diff(ramp_up[5:-5]) > -1e-6) and np.all(np.diff(ramp_down[5:-5]) < 1e-6)
    te = scope.curve("1: TRACKERR").raw()[1][moving[0]:moving[0] + flat[0]]
    assert np.all(np.diff(te[5:-5]) >= 0) and te[-5] > 5 * max(te[5], 1.0)  # grows while accelerating


def test_polling_reads_at_the_poll_rate_and_reports_the_bus_load():
    """DG 5406-5418: polled curves go under Other Curves; the title shows "[<poll ms>ms <load>%]"."""
    link = EmbeddedLink()
    scope = Scope("polling")
    scope.settings.poll_ms = 50
    for signal in ("APOS", "KPROP"):
        new_curve(scope, signal, "", "polled")
    poll = Polling(scope, link)
    poll.start()
    for _ in range(10):
        link.advance(50)
        poll.poll()
    t, y = scope.curve("1: KPROP").raw()
    assert list(np.diff(t)) == [50.0] * 9 and set(y) == {30.0}
    assert poll.title() == f"[50ms {polling_load(2, 50, 125_000):.0f}%]" == "[50ms 9%]"
    for n in range(30):
        new_curve(scope, "4119", "", "polled", name=f"c{n}")
    assert poll.load > 100


def test_single_shot_at_1_ms_uploads_exactly_the_configured_count():
    """DG 5318: Fixed count → "not more than that many sets of points"; DG 5867-5869: nothing while recording,
    the upload when stopped."""
    link = EmbeddedLink()
    scope = Scope("single_shot")
    group = default_group(scope, "single_shot")
    group.interval_ms, group.count = 1, 1234
    for signal in ("4097", "4098", "4102"):
        new_curve(scope, signal, group.name, "single_shot")
    shot = SingleShot(scope, link, group.name)
    start(link, POSA)
    shot.start()
    link.advance(500)
    assert all(len(c.buffer) == 0 for c in scope.curves)      # nothing drawn while recording
    link.advance(2000)
    assert shot.stop() == 1234
    for c in scope.curves:
        t, _ = c.raw()
        assert t.size == 1234 and set(np.diff(t)) == {1.0}
    assert scope.curves[0].name == "1: REG_ACTPOS [4097]"


def test_testsetp_finds_a_programs_recording_and_reloads_a_rerun():
    """DG 5326-5347: one curve per recorded value, first with grey background, "Axis: Name [Index]";
    ide-spec S23: re-run then Reload replaces the data; a Difference between two runs."""
    link = EmbeddedLink()
    start(link, TESTSETP)
    link.advance(3000)
    found = list_testsetp(link)
    assert [r.name for r in found] == ["test"]
    scope = Scope("testsetp")
    curves = load_testsetp(scope, link, found[0].index)
    assert [c.name for c in curves] == ["1: REG_ACTPOS [4097]", "1: REG_COMPOS [4098]",
                                        f"1: SYSVAR 0x1270001 [{0x01270001}]"]
    assert [c.first_of_set for c in curves] == [True, False, False]
    assert len(curves[0].buffer) == 1000   # DIM test[3000] / 3 values
    first = curves[0].raw()[0].copy()
    recorded_at = curves[0].source.info["recorded_at_ms"]
    link.advance(10)
    start(link, TESTSETP)
    link.advance(3000)
    reload_testsetp(scope, link, curves[0])
    # the rerun's data, in the curve's place (decision S15): the recording's other curves stay beside it
    assert curves[0].source.info["recorded_at_ms"] > recorded_at
    assert np.array_equal(curves[0].raw()[0], first)
    second = load_testsetp(scope, link, list_testsetp(link)[-1].index, label="run 2 ")
    assert second[1].raw()[0][0] == first[0]   # a second run lies over the first (issue 16, 2l)
    diff = compute(DerivedSpec("difference", curves[1].name, second[1].name), lambda n: scope.curve(n).raw())
    assert diff[1].size == 1000 and np.isfinite(diff[1]).all()


def test_tune_shows_overshoot_for_a_high_kprop_and_less_after_lowering_it():
    """ide-spec 6.60 / DG 4704-4712, 8638-8653: KPROP is the proportional factor of the position loop; a much
    too high gain overshoots, a lower one does not. Runs stay overlaid in the scope."""
    link = EmbeddedLink()
    scope = Scope("tune")
    tune = Tune(scope, link)
    tune.write_parameters({"KPROP": 20000})
    high = tune.run_synchronously()
    tune.write_parameters({"KPROP": 3000})
    low = tune.run_synchronously()
    assert high.parameters["KPROP"] == 20000 and low.parameters["KPROP"] == 3000
    assert high.overshoot > 5 and low.overshoot < high.overshoot / 2
    assert low.settling_ms is not None and (high.settling_ms is None or low.settling_ms < high.settling_ms)
    assert low.peak_tracking_error > 0
    assert len(scope.curves) == 8 and scope.curves[4].name == "Run 2: CPOS"
    assert scope.curve("Run 2: CPOS").raw()[0][0] == 0.0   # overlaid: time from each run's start
    tune.config.distance = 0
    with pytest.raises(ValueError, match="distance 0"):
        tune.begin()


def test_free_run_with_a_trigger_captures_the_window_around_the_move():
    """Beyond the manual (peers.md: halscope pre-trigger; "a real oscilloscope trigger mode that stops after N
    points", MCUViewer #108): trigger on CPOS rising through 1000 UU with 50 samples before it."""
    from motiontool.scope.trigger import Trigger

    link = EmbeddedLink()
    scope = Scope("free_run")
    group = default_group(scope, "free_run")
    for signal in ("CPOS", "4119"):
        new_curve(scope, signal, group.name, "free_run")
    run = FreeRun(scope, link, group.name, subscribe=True)
    run.trigger = ("1: CPOS", Trigger(level=1000, edge="rising", pre=50, post=200))
    run.start()
    link.advance(300)                      # nothing moves: nothing is captured
    assert len(scope.curve("1: CPOS").buffer) == 0
    start(link, POSA)
    link.advance(3000)
    assert not run.running and run.captures == 1   # single: stopped after one capture
    t, y = scope.curve("1: CPOS").raw()
    assert t.size == 250 and y[49] < 1000 <= y[50]
    clock = scope.curve("1: sys_clock [4119]").raw()[1]
    assert np.array_equal(clock, t)


def test_polled_program_variable_curve():
    """DG 5552-5622: Variable curves show a program variable; here polled through the link's debug read."""
    link = EmbeddedLink()
    result = compile_source("n = 0\nWHILE 1 DO\nn = n + 1\nDELAY 10\nENDWHILE\n", "p.m", debug=True)
    assert result.ok, [d.format() for d in result.diagnostics]
    link.download(result.image.to_bytes())
    link.start()
    scope = Scope("polling")
    scope.settings.poll_ms = 100
    new_curve(scope, "n", "", "variable", name="1: n")
    new_curve(scope, "4119", "", "polled")
    poll = Polling(scope, link)
    poll.start()
    for _ in range(5):
        link.advance(100)
        poll.poll()
    t, n = scope.curve("1: n").raw()
    assert list(t) == [100, 200, 300, 400, 500]
    assert np.all(np.diff(n) >= 9) and np.all(np.diff(n) <= 11)
