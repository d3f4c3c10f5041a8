"""Gearing refinements: offset filter, SYNCVELREL, velocity filter, REVERS; WAITAX in sync; DG example D05."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.kernel.master import MasterConfig
from motiontool.kernel.sync import OffsetFilter, velocity_filter_ms
from tests.kernel.helpers import start

EXAMPLES = Path(__file__).parents[1] / "aposs" / "manual"
IDLE = "WAITT 100000000\n"
FAST = {"FFVEL": 1000, "KPROP": 100}


@settings(max_examples=80, deadline=None)
@given(st.integers(-200_000, 200_000), st.floats(1.0, 3000.0), st.integers(-5000, 5000), st.floats(0, 50.0))
def test_offset_filter_delivers_every_qc_exactly_in_its_time(amount, duration, second, delay):
    """DG 9833-9843: an offset is realised over the offset filter time as a 20/60/20 trapezoid; several changes
    superimpose; the sum of the whole-qc steps is exactly the offset (nothing is lost to rounding)."""
    f = OffsetFilter()
    f.add(amount, duration)
    total, peak = 0, 0.0
    for tick in range(1, int(delay + duration) + 3):
        if tick == int(delay) + 1:
            f.add(second, duration / 2)
        total += f.step()
        peak = max(peak, abs(f.velocity))
    assert f.pending == 0 and total == amount + second
    if second == 0 and duration >= 20 and abs(amount) >= 100:
        assert peak == pytest.approx(abs(amount) / duration / 0.8, rel=0.06)  # 1.25 × the mean speed


def test_offset_filter_duration_zero_is_at_once():
    f = OffsetFilter()
    f.add(500, 0)
    assert f.pending == 500 and f.step() == 500 and f.jumped and f.pending == 0


def test_syncposoffs_change_is_realised_over_syncofftime():
    """DG 9829-9833: "step size = Master Marker Distance / Offset Filter Time … it will take Offset Filter Time
    to realize an offset of par. 33-17 Master Marker Distance." SYNCMPULSM 4096, SYNCOFFTIME 400 ms: an
    offset of 2048 qc takes 200 ms; the slave follows it with the 20/60/20 shape (peak 1.25 × mean). RAMPMIN
    0.1 s lets the slave accelerate enough for that (see the next test)."""
    program = "VEL 100\nACC 100\nDEC 100\nSYNCP\nWAITT 500\nSET SYNCPOSOFFS 2048\n" + IDLE
    run = start(program, settings=dict(FAST, SYNCOFFTIME=400, RAMPMIN=100), master=MasterConfig(velocity=8.0))
    ctl = run.controller
    run.advance(500)
    rel = []
    for _ in range(260):
        run.advance(1)
        rel.append(ctl.axis.cpos - ctl.master.mapos)
    steps = [b - a for a, b in zip(rel, rel[1:], strict=False)]
    moving = [i for i, d in enumerate(steps) if abs(d) > 0.5]
    assert 190 <= len(moving) <= 205                   # ≈ 200 ms
    assert rel[-1] - rel[0] == pytest.approx(2048, abs=2)
    assert max(steps) == pytest.approx(2048 / 200 * 1.25, rel=0.1)
    assert ctl.syncerr() < 20 and ctl.axis.sync.locked


def test_a_too_short_offset_time_is_stretched_to_the_slave_acceleration():
    """DG 9841: the trapezoid's "limiting accelerations and velocity" are planned; with RAMPMIN 1 s (ACC 100 %
    = 0.1024 qc/ms²) 2048 qc need √(2048 / (0.16 · 0.1024)) ≈ 354 ms, not the 200 ms SYNCOFFTIME gives, and
    the slave stays locked to the master the whole time."""
    program = "VEL 100\nACC 100\nDEC 100\nSYNCP\nWAITT 500\nSET SYNCPOSOFFS 2048\n" + IDLE
    run = start(program, settings=dict(FAST, SYNCOFFTIME=400), master=MasterConfig(velocity=8.0))
    ctl = run.controller
    run.advance(502)
    assert ctl.axis.sync.offset_filter.pending
    locked, moved = True, 1
    while ctl.axis.sync.offset_filter.pending:
        run.advance(1)
        locked = locked and ctl.axis.sync.locked
        moved += 1
    assert locked and 350 <= moved <= 358


def test_syncvelrel_bounds_the_catch_up_speed():
    """DG 9488-9492: catching up "it runs with … VEL or … MAVEL + (MAVEL * SYNCVELREL/100) depending which of
    the two is less". The slave starts SYNCP 20000 qc behind (SYNCPOSOFFS) with SYNCVELREL 50: never faster
    than 1.5 × the master; without it the slave uses VEL."""
    def peak(velrel):
        run = start("VEL 100\nACC 100\nDEC 100\nSYNCP\n" + IDLE,
                    settings=dict(FAST, SYNCVELREL=velrel, SYNCPOSOFFS=20000), master=MasterConfig(velocity=10.0))
        best = 0.0
        for _ in range(60):
            run.advance(100)
            best = max(best, run.controller.axis.profile.velocity)
        return best, run.controller
    limited, ctl = peak(50)
    assert limited == pytest.approx(15.0, abs=0.01)
    assert ctl.syncerr() < 20                       # it has caught up within the 4 s
    free, _ = peak(0)
    assert free > 30


def test_syncv_velocity_filter_uses_the_standard_table():
    """DG 9763-9800: Cmdvel = Old_Cmdvel + (Actvel − Old_Cmdvel)·ms/τ_filt, τ from the table by the master encoder
    resolution (1024 → 9300 µs) unless 33-26 SYNCVFTIME is set (µs). A master speed step 0 → 10 qc/ms gives
    63 % after τ."""
    assert velocity_filter_ms(0, 1024) == pytest.approx(9.3)
    assert velocity_filter_ms(500, 4096) == pytest.approx(1.9)      # −999 … 999 = standard table
    assert velocity_filter_ms(-50000, 1024) == pytest.approx(50.0)
    assert velocity_filter_ms(0, 2000) == pytest.approx(4.5)
    table = MasterConfig(table=((0, 0.0), (100, 0.0), (100.001, 10.0)))
    for vftime, tau in ((0, 9.3), (50000, 50.0)):
        run = start("VEL 100\nACC 100\nDEC 100\nSYNCV\n" + IDLE, settings={"SYNCVFTIME": vftime}, master=table)
        run.advance(100 + round(tau))
        v = run.controller.axis.sync.vcmd
        assert v == pytest.approx(10 * (1 - (1 - 1 / tau) ** round(tau)), rel=0.02)
        assert 5.9 < v < 6.6


def test_revers_2_blocks_reversing_in_sync():
    """DG 8790-8805: REVERS 2 "Reversing blocked" is valid for SYNCV/SYNCP: when the master runs backwards
    the slave stands; with 1 it may reverse only because the master reverses (so it does here)."""
    back = MasterConfig(table=((0, 5.0), (1000, 5.0), (1200, -5.0)))
    for revers, backwards in ((2, False), (1, True), (0, True)):
        run = start("VEL 100\nACC 100\nDEC 100\nSYNCV\n" + IDLE, settings={"REVERS": revers}, master=back)
        low = 0.0
        for _ in range(20):
            run.advance(100)
            low = min(low, run.controller.axis.profile.velocity)
        assert (low < -1) == backwards


def test_waitax_in_synchronisation_returns_at_once():
    """WAITAX "waits until target position is reached" (DG 7054); a synchronisation has no target position
    (AXEND bit 1 clear, kernel-spec p.4), so the program goes on while the slave keeps following."""
    run = start("VEL 100\nACC 100\nDEC 100\nSYNCP\nWAITAX\nPRINT \"on\"\n" + IDLE, settings=FAST,
                master=MasterConfig(velocity=5.0))
    run.advance(50)
    assert run.prints == ["on"] and run.controller.axis.mode == "sync"


@pytest.mark.slow  # several seconds on an idle machine: make test runs it, make test-fast does not
def test_d05_position_sync_example_homes_synchronises_and_trims_the_offset():
    """D05 (DG 1007-1137): input 2 homes (input 3 = home switch, I_FUNCTION_3 1), input 1 starts SYNCP;
    OUT 1 shows SYNCSTAT & 4 (inside SYNCACCURACY); input 4 raises SYNCPOSOFFS by the "Offset step" (19-00)
    once per press, re-armed 500 ms after the last pass (each pass re-defines ON TIME 500, so a held input
    steps only once); input 1 low stops (MOTOR STOP). With the default plant the home switch is 8192 qc long
    and HOME_TYPE 0 leaves it at HOME_VEL/10, so homing takes about 13 s."""
    source = (EXAMPLES / "D05_position_sync_corrected.m").read_text()
    presses = [(4, 1, 16000), (4, 0, 16100), (4, 1, 16800), (4, 0, 16900), (4, 1, 17600), (4, 0, 17700)]
    inputs = [(2, 1, 100), (2, 0, 300), (1, 1, 14000), *presses, (1, 0, 19000)]
    run = start(source, settings=dict(FAST, **{"1900": 1000}), inputs=inputs, master=MasterConfig(velocity=5.0))
    ctl = run.controller
    run.advance(13900)
    assert ctl.homed and ctl.axis.mode == "idle" and ctl.io.outputs.get(2) == 1      # "Homing done"
    while ctl.axis.mode != "sync":
        run.advance(1)
    start_master, start_slave = ctl.master.mapos, ctl.axis.cpos   # the relation SYNCP locks (DG 948, K17)
    assert start_master >= 70_000 and start_slave == 0
    run.advance(15900 - ctl.time_ms)
    assert ctl.axis.mode == "sync" and ctl.io.outputs.get(1) == 1                    # within accuracy
    run.advance(2000)
    offset = ctl.params["SYNCPOSOFFS"]
    # the first press only arms the step; as printed, increase_offset adds the step to old_offset (read once
    # at SYNCP), so the third press sets the same 1000 again (decrease_offset reads GET SYNCPOSOFFS)
    assert offset == 1000
    run.advance(900)
    assert ctl.axis.cpos - (ctl.master.mapos - start_master) == pytest.approx(offset, abs=1)
    assert abs(ctl.syncerr()) < 20
    run.advance(2000)
    assert ctl.axis.mode == "idle" and ctl.io.outputs.get(1) == 0 and ctl.io.outputs.get(2) == 0
    assert not run.errors


def test_d05_as_printed_reads_parameter_132_when_synchronisation_stops_and_the_controller_reports_112():
    """D05 as printed (DG 1069): `IF (new_offset != old_offset) AND (GET 132 == 0)` — there is no parameter 132 (the
    "Offset type" is 19-01, GET 1901): when input 1 goes low the controller reports error 112 ("Unknown param.",
    DG 11520-11524) at that line and the program's error handler sets the error output 8."""
    source = (EXAMPLES / "D05_position_sync.m").read_text()
    line = next(n for n, text in enumerate(source.splitlines(), 1) if "(GET 132 == 0) THEN" in text)
    inputs = [(2, 1, 100), (2, 0, 300), (1, 1, 14000), (1, 0, 16000)]
    run = start(source, settings=FAST, inputs=inputs, master=MasterConfig(velocity=5.0))
    run.advance(17000)
    assert [(e.number, e.line) for e in run.errors] == [(112, line)]
    assert run.controller.io.outputs.get(8) == 1 and run.state == "running"   # waiting in errhandle for input 8


def test_syncffvel_from_normtrackerr_nearly_removes_the_sync_error():
    """DG 10068-10079: SYNCFFVEL 1000 "adds a feed forward to MPCMD … of VCMD"; "If you find out that your
    normal NORMTRACKERR is 100 percent, then you should set the SYNCFFVEL to 1000" — REG_NORMTRACKERR (SYSVAR
    4124) is the tracking error relative to VCMD in %. Without velocity feed-forward in the PID (FFVEL 0)
    the slave lags; with SYNCFFVEL = 10 × NORMTRACKERR the sync error nearly vanishes."""
    def run_with(ffvel):
        run = start("VEL 100\nACC 100\nDEC 100\nSYNCP\n" + IDLE, settings={"SYNCFFVEL": ffvel, "KPROP": 100},
                    master=MasterConfig(velocity=10.0))
        run.advance(2000)
        return run.controller
    plain = run_with(0)
    norm = plain.read_pseudo(0, 4124)
    assert norm == pytest.approx(100 * plain.axis.tracking_error / 10.0, abs=1) and norm > 50
    assert plain.syncerr() > 5
    assert run_with(10 * norm).syncerr() <= 1


def test_d04_velocity_sync_example_follows_the_conveyor_and_the_printed_else_stops_it():
    """D04 (DG 850-942): input 1 starts SYNCV, OUT 1 = "In synchronizing mode"; the slave runs at master
    velocity × SYNCFACTS/SYNCFACTM (DG 810, 9318-9324; here 3:2). As printed, "IF (IN 1 == 1) AND (sync_flag
    == 0) … ELSE MOTOR STOP" takes the ELSE branch on the next pass (sync_flag is 1), so the program
    alternates SYNCV and MOTOR STOP as a drive would and the slave hardly moves; the corrected copy stops once when
    input 1 is low ("Stop if input 1 is low", the form of D11) and the slave follows the conveyor."""
    source = (EXAMPLES / "D04_velocity_sync.m").read_text()
    settings = {"SYNCFACTM": 2, "SYNCFACTS": 3}
    master = MasterConfig(velocity=20.0)
    printed = start(source, settings=settings, inputs=[(1, 1, 100)], master=master)
    fastest = 0.0
    for _ in range(2000):
        printed.advance(1)
        fastest = max(fastest, abs(printed.controller.axis.profile.velocity))
    assert fastest < 1.0          # each SYNCV is stopped again in the same program slice: the belt stands
    fixed = start((EXAMPLES / "D04_velocity_sync_corrected.m").read_text(),
                  settings=settings, inputs=[(1, 1, 100), (1, 0, 2500)], master=master)
    fixed.advance(2000)
    ctl = fixed.controller
    assert ctl.axis.mode == "sync" and ctl.io.outputs.get(1) == 1
    assert ctl.axis.profile.velocity == pytest.approx(30.0) and ctl.avel() == pytest.approx(30000, abs=50)
    fixed.advance(1500)
    assert ctl.axis.mode == "idle" and ctl.io.outputs.get(1) == 0 and not fixed.errors


def test_negative_velocity_filter_smooths_syncp_and_its_error_sum_leaves_no_drift():
    """DG 9800-9811: "If the speed filter is defined with a negative number, the corresponding value also applies for
    angle/position synchronization SYNCP … filtering takes place as described above, but the errors made are summed
    up. This error sum is taken into the calculation with 1000/(τ*10) in each case, so that no position deviation can
    occur over prolonged periods. The value returned by SYNCERR always contains the error made." SYNCVFTIME −100000:
    τ = 100 ms. The master runs at 10 qc/ms from the start: the slave's command velocity rises as 1 − e^(−t/τ)
    (63 % after τ) instead of at ACC; SYNCERR shows the lag; after a few seconds the slave is exactly on the master
    again, the error sum having decayed with 10 τ (K20)."""
    program = "VEL 100\nACC 100\nDEC 100\nm0 = MAPOS\nSYNCP\nPRINT m0\n" + IDLE
    run = start(program, settings={**FAST, "SYNCVFTIME": -100000}, master=MasterConfig(velocity=10.0))
    ctl = run.controller
    velocities = []
    for _ in range(300):
        run.advance(1)
        velocities.append(ctl.axis.profile.velocity)
    # the filtered velocity (1 − e^(−t/τ)) plus the fed-back error sum (a few % of it)
    assert 10 * (1 - math.exp(-0.5)) <= velocities[50] <= 10 * (1 - math.exp(-0.5)) + 0.8
    assert 10 * (1 - math.exp(-1)) <= velocities[100] <= 10 * (1 - math.exp(-1)) + 1.2
    steps = [b - a for a, b in zip(velocities[2:], velocities[3:150], strict=False)]
    assert all(x >= y - 1e-9 for x, y in zip(steps, steps[1:], strict=False))   # first order: no ACC plateau
    assert ctl.syncerr() > 300                            # the filter's error is in SYNCERR
    run.advance(9700)                                     # the error sum decays with 10 τ = 1 s
    m0 = int(run.prints[0])
    assert ctl.axis.cpos == pytest.approx(ctl.master.mapos - m0, abs=1)    # no drift left
    assert abs(ctl.syncerr()) <= 12 and not run.errors     # what is left: the drive lags about 1 ms (10 qc)
    plain = start(program, settings=FAST, master=MasterConfig(velocity=10.0))
    plain.advance(51)
    assert plain.controller.axis.profile.velocity == pytest.approx(50 * ctl.axis.scaling.acceleration(100), abs=0.1)
