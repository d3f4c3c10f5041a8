"""Markers, MIPOS/IPOS and SYNCM marker synchronisation (kernel-spec d.3, f.3; kernel/markers.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from motiontool.kernel.markers import Z_WIDTH_QC, MarkerSensor, _index_markers
from motiontool.kernel.master import MasterConfig
from motiontool.kernel.plant import PlantConfig
from tests.kernel.helpers import start

LOOP = "WHILE 1 DO\nENDWHILE\n"
EXAMPLES = Path(__file__).parents[1] / "aposs" / "manual"
IDLE = "WAITT 100000000\n"  # waiting costs no program time, so long simulations stay fast
SYNC = "VEL 100\nACC 100\nDEC 100\n"
EXTERNAL = {"SYNCMTYPM": 2, "SYNCMTYPS": 2, "SYNCMPULSM": 10000, "SYNCMPULSS": 10000, "FFVEL": 1000,
            "KPROP": 100}


def _syncm(settings=None, master=None, plant=None, ms=0, program=SYNC + "SYNCM\n" + IDLE):
    values = dict(EXTERNAL)
    values.update(settings or {})
    run = start(program, settings=values,
                master=master or MasterConfig(velocity=10.0, marker_period_qc=10000, marker_offset_qc=5000),
                plant=plant or PlantConfig(slave_marker_period_qc=10000, slave_marker_offset_qc=2000))
    if ms:
        run.advance(ms)
    return run


def _slave_at_master_markers(run, count=3, period=10000, slave_marker=2000):
    """Where the slave is relative to its markers (mod the marker distance) whenever a master marker passes."""
    ctl = run.controller
    seen = []
    while len(seen) < count:
        run.advance(1)
        for _, slave_then in ctl.markers.master_events:
            seen.append((slave_then - slave_marker) % period)
    return seen


# --- sensors and latching -------------------------------------------------------------------------------------
@settings(max_examples=60, deadline=None)
@given(st.floats(-50.0, 50.0).filter(lambda v: abs(v) > 0.05), st.floats(0, 999.0), st.floats(1.0, 300.0))
@example(speed=1.0, offset=5e-324, width=2.0)  # an edge a denormal past the start (found by CI)
def test_sensor_edges_are_found_at_their_position_in_either_direction(speed, offset, width):
    """CR 2274: "The position value in MIPOS is accurate to +/- 1qc" — every edge passed is found once, at
    its exact position, in the order it happens."""
    sensor = MarkerSensor(period=1000, offset=offset, width=width)
    p, found = 0.0, []
    for _ in range(400):
        found += sensor.edges(p, p + speed)
        p += speed
    lo, hi = min(0.0, p), max(0.0, p)
    expected = sorted(b for k in range(-30, 30) for b in (offset + 1000 * k, offset + 1000 * k + width)
                      if lo < b <= hi)
    assert sorted(b for b, _ in found) == pytest.approx(expected)
    positions = [b for b, _ in found]
    assert positions == sorted(positions, reverse=speed < 0)
    rising = [b for b, r in found if r]
    starts = {round(offset + 1000 * k, 6) for k in range(-30, 30)}
    ends = {round(offset + 1000 * k + width, 6) for k in range(-30, 30)}
    assert all(round(b, 6) in (starts if speed > 0 else ends) for b in rising)



@settings(max_examples=200, deadline=None)
@given(st.floats(-3e6, 3e6), st.floats(-6e6, 6e6).filter(lambda v: v != 0), st.sampled_from([1, 2, 4, 1000, 4096]),
       st.booleans())
@example(p0=-1.0, step=3.0, period=1, rising=False)  # a pulse as wide as its period: flanks on the same qc
@example(p0=4095.5, step=-4096.0, period=4096, rising=True)
def test_index_markers_are_the_index_sensors_flanks(p0, step, period, rising):
    """The index pulses' shortcut (kernel/markers.py _index_markers, issue 30) gives the same positions, fractions and
    order as the encoder's index pulse as a MarkerSensor, filtered on the flank (CR 2274: MIPOS ±1 qc)."""
    assume(abs(step) / period <= 5000)   # a tick passes a few pulses; the sensor's list of millions took 86 s
    p1 = p0 + step
    sensor = MarkerSensor(period=period, width=Z_WIDTH_QC)
    want = [(b, (b - p0) / (p1 - p0)) for b, r in sensor.edges(p0, p1) if r == rising]
    assert _index_markers(p0, p1, period, rising) == want

def test_mipos_latches_the_master_marker_inside_the_tick():
    """CR 2263-2274 / DG 9567-9581: MIPOS is the last master marker (33-19 type 2 = external marker, input 5)
    relative to the master zero, accurate to ±1 qc although the master moves 7.3 qc per ms."""
    run = start(LOOP, settings={"SYNCMTYPM": 2},
                master=MasterConfig(velocity=7.3, marker_period_qc=1000, marker_offset_qc=123.4))
    ctl = run.controller
    run.advance(250)
    assert ctl.params.get(3454) == 1123                                # 34-54 Master Index Position
    mapos = ctl.master.mapos
    ctl.master.defmorigin()
    assert ctl.markers.mipos() == 1123 - mapos                         # relative to the new master zero


def test_master_index_pulse_type_0_latches_every_revolution():
    """DG 9567-9574: 33-19 type 0 = encoder Z positive flank; one index per revolution of the master
    encoder (32-31 MENCODER 1024 lines = 4096 qc)."""
    run = start(LOOP, settings={"SYNCMTYPM": 0}, master=MasterConfig(velocity=-9.0))
    run.advance(1000)  # the master runs backwards to −9000: the last index passed is −8192
    assert abs(run.controller.markers.mipos() + 8192) <= 1


def test_c10_on_int_5_handler_reads_mipos_after_delay_2():
    """C10 (CR 2291-2310): ON INT 5 latches the master marker; after DELAY 2 MIPOS is the hardware-latched
    position while MAPOS read in the handler is later."""
    source = (EXAMPLES / "C10_mipos_latch.m").read_text()
    run = start(source, master=MasterConfig(velocity=20.0, marker_period_qc=5000, marker_offset_qc=2500.5,
                                              marker_width_qc=400))
    run.advance(1000)
    pairs = list(zip(run.prints[::2], run.prints[1::2], strict=False))
    assert len(pairs) >= 2
    for interrupt, triggered in pairs[:2]:
        int_mpos = int(interrupt.split(":")[1])
        mipos = int(triggered.split(":")[1])
        assert (mipos - 2500) % 5000 == 0             # the marker's own position …
        assert 0 < int_mpos - mipos <= 3 * 20         # … MAPOS in the handler is up to a few ms later


def test_scripted_input_6_latches_ipos_and_on_ipos_counts_from_the_marker():
    """CR 1778-1790: IPOS is the slave marker position (33-20 type 2, input 6), in UU; DG 7158: ON IPOS fires
    at a distance from the last marker."""
    program = ("ON IPOS 500 GOSUB hit\nCVEL 10\nCSTART\n" + IDLE +
               "SUBMAINPROG\nSUBPROG hit\nPRINT APOS - IPOS\nRETURN\nENDPROG\n")
    run = start(program, settings={"SYNCMTYPS": 2}, inputs=[(6, 1, 1000), (6, 0, 1010)])
    ctl = run.controller
    run.advance(1005)
    ipos = ctl.params.get(3453)                       # 34-53 Slave Index Position
    assert ipos == ctl.uu(ctl.markers.ipos_qc()) and ipos > 0
    run.advance(2000)
    assert run.prints and 500 <= int(run.prints[0]) <= 520


def test_master_jitter_is_deterministic_per_seed():
    from motiontool.kernel.master import Master
    traces = []
    for seed in (1, 1, 2):
        m = Master(MasterConfig(velocity=5.0, jitter=0.5, seed=seed))
        for t in range(1, 2001):
            m.tick(t)
        traces.append(m.position)
    assert traces[0] == traces[1] != traces[2]
    assert abs(traces[0] - 10000) < 200   # noise, not drift


# --- SYNCM -------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(("mode", "first"), [(0, 7000), (1, -3000), (2, 7000), (3, 7000), (4, -3000), (5, -3000),
                                             (6, -3000)])
def test_syncm_start_behaviour_chooses_the_first_pair(mode, first):
    """DG 9695-9701: 0 the slave marker after the first master marker; 1 the first slave marker with the following
    master marker; 3 forward, 4 backward, 5 shortest correction after reaching master velocity; 6 the first two
    markers. Master markers at 5000 + k·10000, slave markers at 2000 + k·10000: forward needs +7000, backward
    −3000. Afterwards the slave marker passes with every master marker."""
    run = _syncm({"SYNCMSTART": mode}, ms=4000)
    corrections = run.controller.axis.sync.markers.corrections
    assert corrections[0] == pytest.approx(first, abs=30)
    assert all(abs(c) <= 30 for c in corrections[1:])
    assert all(min(s, 10000 - s) <= 25 for s in _slave_at_master_markers(run))  # the lag of the loop only
    assert run.controller.syncstat() & (1 | 4 | 8 | 16) == 1 | 4 | 8 | 16        # READY ACCURACY MMHIT SMHIT


def test_syncm_1000_series_offset_only_after_the_first_correction():
    """DG 9707: "1000 = as [0], but an offset (par. 33-12 SYNCPOSOFFS) is not active before the first marker
    correction is done." Before it, the slave runs as without offset; afterwards the slave marker passes
    the offset (600 qc, gear 1:1) before the master marker."""
    run = _syncm({"SYNCMSTART": 1000, "SYNCPOSOFFS": 600})
    ctl = run.controller
    run.advance(400)
    assert abs(ctl.axis.apos - ctl.master.mapos) < 30   # no offset yet
    run.advance(3600)
    assert ctl.axis.sync.markers.corrections[0] == pytest.approx(7000, abs=30)
    assert all(abs(s - 600) <= 25 for s in _slave_at_master_markers(run))


def test_syncm_offset_with_start_0_is_kept_relative_to_the_markers():
    """DG 9411-9428 with DG 9695: the slave marker is aligned with the master marker plus SYNCPOSOFFS."""
    run = _syncm({"SYNCMSTART": 0, "SYNCPOSOFFS": -800}, ms=4000)
    assert all(abs(s - 9200) <= 25 for s in _slave_at_master_markers(run))


def test_syncm_marker_ratio_aligns_every_third_slave_index():
    """DG 9528: "If the motor always requires 3 rotations until the article arrives … a ratio of 3:1; only
    every 3rd slave pulse is evaluated." Slave marker = index pulse (type 0, 4096 qc), master marker every
    12288 qc, SYNCMARKS 3."""
    settings = {"SYNCMTYPS": 0, "SYNCMPULSS": 4096, "SYNCMARKS": 3, "SYNCMPULSM": 12288, "SYNCMSTART": 5}
    run = _syncm(settings, master=MasterConfig(velocity=12.0, marker_period_qc=12288, marker_offset_qc=1000),
                 plant=PlantConfig(), ms=6000)
    corrections = run.controller.axis.sync.markers.corrections
    assert len(corrections) >= 3 and all(abs(c) <= 30 for c in corrections[1:])
    assert all(min(s, 4096 - s) <= 25 for s in _slave_at_master_markers(run, period=4096, slave_marker=0))


def test_syncm_window_missing_master_marker_sets_mmerr_and_skips_the_correction():
    """DG 9624: "If there is no marker within the tolerance window the corresponding flag (SYNCSTAT) is set and
    no marker correction takes place. The corresponding other marker is also ignored"; DG 9636: distance 30000,
    window 1000 → only 29000 … 31000. A noise pulse at 17000 is ignored, the product due at 65000 comes
    at 66500, outside the window.
    SYNCSTATCLR 32 clears the flag (CR 3060-3061)."""
    boxes = (5000, 17000, 35000, 66500, 95000, 125000, 155000)
    program = SYNC + "SYNCM\nWAITT 9000\nPRINT SYNCSTAT\nSYNCSTATCLR 32\nPRINT SYNCSTAT\n" + IDLE
    run = _syncm({"SYNCMPULSM": 30000, "SYNCMPULSS": 30000, "SYNCMWINM": 1000, "SYNCMWINS": 1000},
                 master=MasterConfig(velocity=20.0, marker_positions_qc=boxes),
                 plant=PlantConfig(slave_marker_period_qc=30000, slave_marker_offset_qc=2000), program=program)
    run.advance(9100)
    markers = run.controller.axis.sync.markers
    assert markers.master.count == 5                       # 17000 (noise) and 66500 (outside) not accepted
    assert int(run.prints[0]) & 32 and not int(run.prints[1]) & 32
    assert int(run.prints[0]) & 8 and int(run.prints[1]) & 8
    # the slave marker after the missing box is ignored: evaluations at 5000, 35000, 95000, 125000, 155000
    assert len(markers.corrections) == 4


def test_syncm_maximum_correction_clamps_and_negative_switches_it_off():
    """DG 10004-10032: SYNCMMAXCORR > 0 "limits the marker correction by the given value", < 0 "no correction
    at all is done"."""
    run = _syncm({"SYNCMMAXCORR": 2000}, ms=1500)
    ctl = run.controller
    assert ctl.axis.sync.markers.corrections[0] == pytest.approx(7000, abs=30)
    assert ctl.axis.sync.slave_shift == 2000
    off = _syncm({"SYNCMMAXCORR": -1}, ms=3000)
    assert off.controller.axis.sync.slave_shift == 0 and len(off.controller.axis.sync.markers.corrections) >= 2


def test_syncm_fault_and_ready_counting():
    """DG 9733: SYNCFAULT = how often an inaccuracy may occur before FAULT; DG 9757: "ACCURACY is checked during
    every correction. If ACCURACY is fulfilled then 1 is added until the set marker number has been achieved."
    The slave has 1 % slip against its markers (10100 qc apart): every correction is ~100 qc, outside
    SYNCACCURACY 50 → no READY, FAULT after 2 inaccurate evaluations with SYNCFAULT 2 …"""
    slip = PlantConfig(slave_marker_period_qc=10100, slave_marker_offset_qc=2000)
    run = _syncm({"SYNCACCURACY": 50, "SYNCFAULT": 2, "SYNCREADY": 3, "SYNCMPULSS": 10100}, plant=slip, ms=2600)
    ctl = run.controller
    assert len(ctl.axis.sync.markers.corrections) == 3 and not ctl.syncstat() & 2   # start + 2 inaccurate
    run.advance(1000)
    assert ctl.syncstat() & 3 == 2
    # … while with SYNCACCURACY 200 they are accurate and READY comes with the 3rd evaluation
    ok = _syncm({"SYNCACCURACY": 200, "SYNCREADY": 3, "SYNCMPULSS": 10100}, plant=slip, ms=2600)
    assert ok.controller.syncstat() & 3 == 0
    ok.advance(1000)
    assert ok.controller.syncstat() & 3 == 1


def test_syncm_correction_with_offset_filter_time_is_spread_and_not_repeated():
    """DG 9833-9843: SYNCOFFTIME is the time to realise one master marker distance and shapes the start
    correction as a trapezoid; a correction still being realised is not corrected again at the next marker."""
    run = _syncm({"SYNCOFFTIME": 1000}, ms=500)
    ctl = run.controller
    velocities = []
    for _ in range(1200):
        run.advance(1)
        velocities.append(ctl.axis.profile.velocity)
    corrections = ctl.axis.sync.markers.corrections
    assert corrections[0] == pytest.approx(7000, abs=30)
    assert max(velocities) == pytest.approx(10 + 7000 / (0.8 * 700), rel=0.05)  # 0.7 s for 7000 qc, peak 1.25×
    run.advance(3000)
    assert all(abs(c) <= 30 for c in ctl.axis.sync.markers.corrections[1:])
    assert all(min(s, 10000 - s) <= 25 for s in _slave_at_master_markers(run))


def test_d06_marker_sync_example_measures_the_slave_distance_then_synchronises():
    """D06 (DG 1203-1340): input 2 measures the slave marker distance while running CVEL "Measuring velocity",
    then SET SYNCMPULSS (total_dist rnd marker_number); input 1 starts SYNCM with external markers
    (SYNCMTYPM/S 2) and the teddy (slave marker) is put into the box (master marker)."""
    # As printed, "IF (IN 1 == 1) AND (sync_flag == 0) … ELSE MOTOR STOP" also stops on the next pass while
    # input 1 stays high (sync_flag is 1 then): the program would alternate SYNCM and MOTOR STOP. The corrected copy
    # stops once when input 1 is low, as the comment says ("Stop when input 1 is low").
    source = (EXAMPLES / "D06_marker_sync_corrected.m").read_text()
    run = start(source, settings={"1900": 50, "FFVEL": 1000, "KPROP": 100, "SYNCMPULSM": 12000},
                inputs=[(2, 1, 100), (2, 0, 2500), (1, 1, 2600)],
                master=MasterConfig(velocity=10.0, marker_period_qc=12000, marker_offset_qc=3000),
                plant=PlantConfig(slave_marker_period_qc=12000, slave_marker_offset_qc=7000))
    run.advance(2700)
    ctl = run.controller
    assert ctl.params["SYNCMPULSS"] == 12000
    run.advance(3000)
    assert ctl.axis.mode == "sync" and ctl.axis.sync.markers is not None
    assert all(min(s, 12000 - s) <= 25 for s in _slave_at_master_markers(run, period=12000, slave_marker=7000))
    assert not run.errors
    printed = start((EXAMPLES / "D06_marker_sync.m").read_text(), settings={"FFVEL": 1000},
                    inputs=[(1, 1, 100)], master=MasterConfig(velocity=10.0))
    fastest = 0.0
    for _ in range(1000):
        printed.advance(1)
        fastest = max(fastest, abs(printed.controller.axis.profile.velocity))
    assert fastest < 1.0                       # as printed SYNCM and MOTOR STOP alternate: the slave stands


def test_on_statbit_30_reports_a_missing_master_marker_and_syncstatclr_rearms_it():
    """CR 3021-3068: byte 4 of the status bits is SYNCSTAT, "Bit 30 1 = SYNCMMERR"; the CR's example
    "ON STATBIT 30 GOSUB markererror … SYNCSTATCLR 32 /* clear error flag SYNCMMERR */". Two boxes are
    missing (due at 35000 and 95000, window 1000): the handler runs once for each."""
    program = ("ON STATBIT 30 GOSUB markererror\n" + SYNC + "SYNCM\n" + IDLE +
               "SUBMAINPROG\nSUBPROG markererror\nPRINT MAPOS\nSYNCSTATCLR 32\nRETURN\nENDPROG\n")
    boxes = (5000, 65000, 125000, 155000)
    run = _syncm({"SYNCMPULSM": 30000, "SYNCMPULSS": 30000, "SYNCMWINM": 1000},
                 master=MasterConfig(velocity=20.0, marker_positions_qc=boxes),
                 plant=PlantConfig(slave_marker_period_qc=30000, slave_marker_offset_qc=2000), program=program)
    run.advance(8000)
    missed = [int(p) for p in run.prints]
    assert len(missed) == 2
    assert 36000 < missed[0] <= 36100 and 96000 < missed[1] <= 96100   # noticed when the window has passed
    assert not run.controller.syncstat() & 32


def test_on_mipos_fires_at_a_distance_after_each_master_marker():
    """DG 7158: ON MIPOS = distance since the last master marker (qc); CR 2883-2984 position interrupts."""
    program = "SET SYNCMTYPM 2\nON MIPOS 300 GOSUB after\n" + IDLE + \
        "SUBMAINPROG\nSUBPROG after\nPRINT MAPOS - MIPOS\nRETURN\nENDPROG\n"
    run = start(program, master=MasterConfig(velocity=10.0, marker_period_qc=2000, marker_offset_qc=500))
    run.advance(1000)
    # before the first marker MIPOS is 0 (30 ms), then 300 qc after the markers at 500, 2500 … 8500
    assert run.print_times == [30, 80, 280, 480, 680, 880]
    assert all(300 <= int(p) <= 330 for p in run.prints)


def test_negative_velocity_filter_spreads_a_marker_correction_over_ten_time_constants():
    """DG 9807-9811: "If, for example, a filter factor of -100000 (100 ms) is used, a marker correction is
    balanced within 1 second (100 ms * 10)." (Realised here as the offset trapezoid over 1 s.)"""
    run = _syncm({"SYNCVFTIME": -100000}, ms=505)
    sync = run.controller.axis.sync
    assert sync.markers.corrections == [] and sync.slave_filter.pending == 0
    ticks = 0
    while not sync.markers.corrections:
        run.advance(1)
    while sync.slave_filter.pending:
        run.advance(1)
        ticks += 1
    assert sync.markers.corrections[0] == pytest.approx(7000, abs=30)
    assert 980 <= ticks <= 1001  # the last qc arrives a few ms early (rounding of the slow end)


def test_syncm_with_jittering_master_and_markers_stays_within_the_marker_jitter():
    """DG 1147: without windows every pulse incl. jitter is used to correct; DG 9636: with a window only
    markers near the expected distance count. Master speed noise ±1 qc/ms and products displaced by up to
    ±40 qc: the slave marker stays within the product jitter of its master marker, and the same seed gives
    the same corrections."""
    def run_once():
        run = _syncm({"SYNCMWINM": 500, "SYNCMWINS": 500},
                     master=MasterConfig(velocity=10.0, jitter=1.0, seed=7, marker_period_qc=10000,
                                         marker_offset_qc=5000, marker_jitter_qc=40), ms=6000)
        return run, list(run.controller.axis.sync.markers.corrections)
    run, corrections = run_once()
    assert all(abs(c) <= 100 for c in corrections[1:])
    assert all(min(s, 10000 - s) <= 100 for s in _slave_at_master_markers(run))
    assert run_once()[1] == corrections


def test_extended_marker_type_ands_the_marker_with_a_second_input():
    """DG 9581: "An extended marker type realizes a logical AND for marker input and a second input, e.g. to
    synchronize every second marker with a PLC control. This also influences the command MIPOS. MIPOS only delivers a
    new value, if the condition is true." Coding (K51): 10·n + t — here 72 = external rising flank (2) AND input 7."""
    program = "SET SYNCMTYPM 72\nWHILE 1 DO\n  DELAY 100\n  PRINT MIPOS\nENDWHILE\n"
    run = start(program, master=MasterConfig(velocity=10.0, marker_period_qc=2000, marker_offset_qc=500),
                inputs=[(7, 1, 300), (7, 0, 700)])
    run.advance(1000)
    # markers at 500, 2500, 4500, 6500, 8500 qc (50, 250, 450, 650, 850 ms): input 7 is on for 450 and 650 only
    assert [int(p) for p in run.prints[:9]] == [0, 0, 0, 0, 4500, 4500, 6500, 6500, 6500]
