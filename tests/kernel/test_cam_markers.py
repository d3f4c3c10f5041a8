"""Marker correction in CAM mode: SYNCCMM / SYNCCMS and SYNCMSTART 2000 (kernel/cam_markers.py, kernel-spec g.2).

A straight curve with 1 MU = 1 master qc and 1 UU = 1 slave qc keeps the numbers readable: MasterCycleLen 10000
MU, SlaveCycleLen 10000 UU, the master runs 10 qc/ms (one cycle per second). The product's marker position is 5000
and the sensor is 2000 before the working point, so the marker is expected at curve position 3000; the products
come 500 late (marker at 3500). Correction window 4000 … 8000, maximum correction 150 per cycle.
"""

from __future__ import annotations

import math

import pytest

from motiontool.camcurve import Curve, FixPoint, encode
from motiontool.controller.embedded import EmbeddedLink
from motiontool.kernel.master import MasterConfig
from motiontool.kernel.plant import PlantConfig
from tests.kernel.helpers import start

UNITS = {"SYNCFACTM": 1, "SYNCFACTS": 1, "POSFACT_Z": 1, "POSFACT_N": 1, "FFVEL": 1000, "KPROP": 100,
         "SYNCMTYPM": 2, "SYNCMTYPS": 2}
WINDOW = (4000, 8000)


def line(**kw) -> Curve:
    points = (FixPoint(0, 0), FixPoint(2500, 2500), FixPoint(5000, 5000), FixPoint(10000, 10000))
    data = {"correction_start": WINDOW[0], "correction_end": WINDOW[1], "max_correction": 150,
            "master_marker_pos": 5000, "slave_marker_pos": 5000, **kw}
    return Curve("line", 10000, points, intervals=10, cycles_per_min=6, **data)


def run_cam(command: str, curve: Curve | None = None, settings=None, master=None, plant=None, ms: int = 0,
            start_mode: str = ""):
    curve = curve or line()
    values = encode(curve)
    link = EmbeddedLink(plant or PlantConfig(), master=master or MasterConfig(velocity=10.0))
    link.call("restore_arrays", arrays=[{"name": "line", "values": values}])
    program = (f"DIM line[{len(values)}]\nSETCURVE line\nDEFMCPOS 0\n{start_mode}{command} 0\nSYNCCSTART 0\n"
               "WAITT 100000000\n")
    run = start(program, settings={**UNITS, "SYNCMPULSM": 2000, "SYNCMPULSS": 2000, **(settings or {})}, link=link)
    run.advance(ms)
    assert not run.errors, [e.text for e in run.errors]
    return run


def boxes(*positions, period=10000.0, offset=3500.0) -> MasterConfig:
    if positions:
        return MasterConfig(velocity=10.0, marker_positions_qc=positions)
    return MasterConfig(velocity=10.0, marker_period_qc=period, marker_offset_qc=offset)


def trace(run, ms: int, what):
    """(curve master position in the cycle, value) after every ms."""
    ctl = run.controller
    out = []
    for _ in range(ms):
        run.advance(1)
        out.append((ctl.axis.sync.cam.master_position() % 10000, what(ctl)))
    return out


def changes(samples):
    return [(m, b - a) for (_, a), (m, b) in zip(samples, samples[1:], strict=False) if abs(b - a) > 1e-9]


def in_window(m: float, slack: float = 15.0) -> bool:
    return WINDOW[0] <= m <= WINDOW[1] + slack


# --- SYNCCMM: the curve master position is corrected -------------------------------------------------------------
def test_synccmm_corrects_inside_the_window_by_at_most_the_maximum_per_cycle_and_converges():
    """DG 1612: with master marker correction "the curve" is corrected; DG 3762-3765: "Correction Start and End:
    This specifies the master positions where the master correction should begin and end"; curve info
    MaximumCorrection (per cycle). The products come 490 late (the program starts 1 ms after the master): the
    curve master position is moved back by 150, 150, 150, 40 — only between 4000 and 8000 — after which the
    marker is met exactly."""
    run = run_cam("SYNCCMM", master=boxes())
    samples = trace(run, 6000, lambda ctl: ctl.axis.sync.cam.mu_shift)
    markers = run.controller.axis.sync.markers
    assert markers.errors[:4] == pytest.approx([490, 340, 190, 40])
    assert markers.corrections[:4] == pytest.approx([-150, -150, -150, -40])
    assert all(abs(e) < 1e-6 for e in markers.errors[4:]) and len(markers.errors) == 6
    steps = changes(samples)
    assert steps and all(in_window(m) for m, _ in steps)                      # only inside the window
    per_cycle: dict[int, float] = {}
    for i, ((_, a), (_, b)) in enumerate(zip(samples, samples[1:], strict=False)):
        per_cycle[i // 1000] = per_cycle.get(i // 1000, 0.0) + (b - a)
    assert all(abs(total) <= 150 + 1e-6 for total in per_cycle.values())    # never more than the maximum
    assert samples[-1][1] == pytest.approx(-490)                              # converged: −490 in all
    # smooth: the blend starts and ends without a jump of the curve master velocity
    assert max(abs(d) for _, d in steps) < 150 * 1.875 * 10 / 4000 + 1e-6


def test_synccmm_marker_inside_the_window_is_corrected_in_the_rest_of_it():
    """DG 1588-1594: a marker "recognized at the master position 900" of a window ending at 1000 leaves "little time
    left … to correct the error" — the correction runs from the marker to the window end. Marker at 6000 (expected
    5000: marker position 7000, distance 2000), window 4000 … 8000."""
    run = run_cam("SYNCCMM", line(master_marker_pos=7000, max_correction=0), master=boxes(offset=6000))
    samples = trace(run, 1200, lambda ctl: ctl.axis.sync.cam.mu_shift)
    steps = changes(samples)
    assert 5990 <= steps[0][0] <= 6030 and steps[-1][0] <= 8000 + 15
    assert samples[-1][1] == pytest.approx(-990)


def test_correction_start_equal_to_end_corrects_at_once():
    """Correction Start = Correction End (the editor's default 0/0): no window, the correction is made at once and
    the slave catches up within VEL/ACC (as SYNCM without filter times, DG 9990)."""
    run = run_cam("SYNCCMM", line(correction_start=0, correction_end=0, max_correction=0), master=boxes())
    samples = trace(run, 600, lambda ctl: ctl.axis.sync.cam.mu_shift)
    steps = changes(samples)
    assert len(steps) == 1 and steps[0][1] == pytest.approx(-490)
    run.advance(1000)
    ctl = run.controller
    assert ctl.axis.sync.locked and abs(ctl.axis.cpos - ctl.axis.apos) <= 15


def test_a_correction_added_at_once_is_caught_up_within_acc():
    """DG 1532-1541 / decision K33: without a window the correction is added at once and the slave catches it up
    within its limits — the commanded position must not jump by the whole correction in one tick (a small one of
    about 20 MU here: larger than ACC allows per tick, smaller than VEL)."""
    run = run_cam("SYNCCMM", line(correction_start=0, correction_end=0, max_correction=0), master=boxes(offset=3030.0),
                  ms=5)
    ctl = run.controller
    pg, mo = ctl.axis.profile, ctl.axis.sync
    limit = max(mo.acc, mo.dec) * (1 + 1e-9) + 1e-9
    steps = trace(run, 600, lambda c: (pg.velocity, c.axis.sync.cam.mu_shift))
    assert any(b[1] != a[1] for (_, a), (_, b) in zip(steps, steps[1:], strict=False))  # the correction came
    assert max(abs(b[0] - a[0]) for (_, a), (_, b) in zip(steps, steps[1:], strict=False)) <= limit


def test_synccmm_tolerance_window_ignores_noise_and_flags_the_missing_box():
    """DG 9624 (33-21, "[qc] or in CAM mode [MU]"): "only those markers are accepted which are within the window. If
    there is no marker within the tolerance window the corresponding flag (SYNCSTAT) is set and no marker correction
    takes place." One marker is expected per curve cycle: a noise pulse at 19000 and the box due at 33500 that comes
    at 36000 are ignored, MMERR (32) is set, the others are corrected (SYNCMARKM 1)."""
    positions = (3500, 13500, 19000, 23500, 36000, 43500, 53500)
    run = run_cam("SYNCCMM", master=boxes(*positions), settings={"SYNCMWINM": 200}, ms=5600)
    ctl = run.controller
    markers = ctl.axis.sync.markers
    assert markers.master.count == 5 and len(markers.errors) == 5
    assert ctl.syncstat() & (8 | 32) == 8 | 32                               # MMHIT and MMERR
    assert markers.corrections == pytest.approx([-150, -150, -150, -40, 0])


def test_synccmm_sensor_beyond_one_cycle_uses_the_marker_fifo():
    """DG 9550: "If the parameter is larger than one master cycle length (Mt), a marker-FIFO register will be created";
    DG 1590: "The value is entered into the buffer when the marker appears. The buffer is read out only when the
    next marker is recognized." Distance 12000 (one cycle + 2000): the first box is corrected at the second marker;
    corrections made for a box count against the ones behind it, so the total is again −490."""
    run = run_cam("SYNCCMM", master=boxes(), settings={"SYNCMPULSM": 12000}, ms=10)
    markers = run.controller.axis.sync.markers
    run.advance(590)
    assert markers.errors == [] and len(markers.fifo) == 1                   # buffered, nothing corrected yet
    run.advance(6000)
    assert markers.corrections[:4] == pytest.approx([-150, -150, -150, -40])
    assert run.controller.axis.sync.cam.mu_shift == pytest.approx(-490)


def test_syncmmaxcorr_limits_in_qc_and_negative_only_monitors():
    """DG 10020-10028 (33-30): "SYNCMMAXCORR is used to limit the maximum correction done by marker correction. This
    is working with SYNCM and SYNCC"; "The value < 0 sets the parameter so that no correction at all is done"."""
    run = run_cam("SYNCCMM", line(max_correction=0), master=boxes(), settings={"SYNCMMAXCORR": 100}, ms=2600)
    assert run.controller.axis.sync.markers.corrections[:2] == pytest.approx([-100, -100])
    off = run_cam("SYNCCMM", master=boxes(), settings={"SYNCMMAXCORR": -1}, ms=3000)
    markers = off.controller.axis.sync.markers
    assert len(markers.errors) == 3 and off.controller.axis.sync.cam.mu_shift == 0
    assert off.controller.syncstat() & 8


def test_syncstat_ready_and_fault_count_the_cam_evaluations():
    """DG 9733-9761: SYNCFAULT / SYNCREADY count the evaluations "during a marker synchronization (SYNCM and
    SYNCCMM)"; ACCURACY (33-13, qc) is checked at every correction. The start correction is not counted."""
    run = run_cam("SYNCCMM", master=boxes(), settings={"SYNCACCURACY": 100, "SYNCFAULT": 1, "SYNCREADY": 2})
    ctl = run.controller
    run.advance(1400)                        # markers at 350, 1350 … ms: 490 (start), 340 (inaccurate)
    assert ctl.syncstat() & 3 == 0
    run.advance(1000)                        # 190: the second inaccurate one → FAULT
    assert ctl.syncstat() & 3 == 2
    run.advance(1000)                        # 40: accurate, one of two
    assert ctl.syncstat() & 3 == 2
    run.advance(1000)                        # 0: the second accurate one → READY
    assert ctl.syncstat() & 3 == 3


# --- SYNCCMS: the slave position is corrected ---------------------------------------------------------------------
def slave_boxes(*positions, offset=3500.0) -> PlantConfig:
    if positions:
        return PlantConfig(slave_marker_positions_qc=positions)
    return PlantConfig(slave_marker_period_qc=10000, slave_marker_offset_qc=offset)


def test_synccms_moves_the_slave_inside_the_window_and_converges():
    """DG 1612: "In contrast to the synchronization with master marker correction, here the slave position is being
    corrected instead of the curve." Slave marker position 5000, SYNCMPULSS 2000: the slave marker is expected at
    curve slave position 3000; the products lie 500 further back, so the slave is moved forward by 150 per cycle
    inside the window until its markers come at 3000; the curve master position is not touched."""
    run = run_cam("SYNCCMS", master=MasterConfig(velocity=10.0), plant=slave_boxes())
    samples = trace(run, 6000, lambda ctl: ctl.axis.sync.base)
    ctl = run.controller
    markers = ctl.axis.sync.markers
    assert markers.corrections[:4] == pytest.approx([150, 150, 150, 50], abs=12)
    assert all(abs(e) <= 12 for e in markers.errors[4:])                     # the loop's lag only
    steps = changes(samples)
    assert steps and all(in_window(m) for m, _ in steps)
    assert samples[-1][1] - samples[0][1] == pytest.approx(500, abs=12)
    assert ctl.axis.sync.cam.mu_shift == 0


def test_synccms_tolerance_window_and_missing_slave_marker():
    """DG 9654 (33-22, "[qc] or in CAM mode [UU]"): a slave marker outside the window is ignored, a missing one sets
    SMERR (64) and nothing is corrected for it."""
    plant = slave_boxes(3500, 13350, 17000, 30000, 33050)
    run = run_cam("SYNCCMS", master=MasterConfig(velocity=10.0), plant=plant, settings={"SYNCMWINS": 300}, ms=3600)
    ctl = run.controller
    markers = ctl.axis.sync.markers
    assert markers.slave.count == 3                                           # 17000 and 30000 are not accepted
    assert ctl.syncstat() & (16 | 64) == 16 | 64
    assert len(markers.errors) == 3


# --- SYNCMSTART 2000 -----------------------------------------------------------------------------------------------
def test_syncmstart_2000_starts_counting_the_curve_master_position_at_the_master_marker():
    """DG 9716: "2000 = Counting of the master pulses in MU begins with the master marker"; DG 1558-1560: "SET
    SYNCMSTART 2000 // Counting of the master pulse does not begin until the next edge comes from the sensor";
    CR 675-680: updating starts "after SYNCC and the first master marker". The master runs from the start, the
    first box passes at 3500: until then CMASTERCPOS stays 0, afterwards it counts from 0."""
    run = run_cam("SYNCC", master=boxes(), start_mode="SET SYNCMSTART 2000\n", ms=300)
    ctl = run.controller
    assert ctl.read_pseudo(0, 4230) == 0 and ctl.master.mapos > 2000
    run.advance(500)
    assert ctl.read_pseudo(0, 4230) == pytest.approx(ctl.master.mapos - 3500, abs=11)
    assert ctl.axis.sync.markers.corrections == []                           # plain SYNCC: no correction


def test_a_sync_command_in_cam_mode_switches_the_marker_correction_it_names():
    """DG 7261-7263: SYNCC/SYNCCMM/SYNCCMS n in CAM mode start a new cycle count; the marker correction is the one
    the command names (decision K45): SYNCCMM after SYNCC corrects from the next marker on, SYNCC switches it off."""
    values = encode(line())
    link = EmbeddedLink(PlantConfig(), master=boxes())
    link.call("restore_arrays", arrays=[{"name": "line", "values": values}])
    program = (f"DIM line[{len(values)}]\nSETCURVE line\nDEFMCPOS 0\nSYNCC 0\nSYNCCSTART 0\nWAITT 1500\n"
               "SYNCCMM 0\nWAITT 4000\nSYNCC 0\nWAITT 100000000\n")
    run = start(program, settings={**UNITS, "SYNCMPULSM": 2000, "SYNCMPULSS": 2000}, link=link)
    run.advance(1000)
    ctl = run.controller
    assert ctl.axis.sync.markers is None                      # plain SYNCC: no marker handling
    run.advance(1000)
    markers = ctl.axis.sync.markers
    assert markers is not None and markers.side == "master"
    run.advance(3000)
    assert markers.corrections and ctl.axis.sync.cam.mu_shift != 0   # the late boxes are corrected
    run.advance(1000)
    assert ctl.axis.sync.markers is None and ctl.axis.mode == "cam"



def test_syncmmaxcorr_is_in_slave_qc_also_when_the_curve_master_is_corrected():
    """DG 10020: "SYNCMMAXCORR … This is working with SYNCM and SYNCC. The value is given in qc (slave)". With 1 MU =
    2 master qc (SYNCFACTM 2, SYNCFACTS 1) the gear turns one master qc into half a slave qc, so a curve master
    correction of x MU moves the slave x slave qc: SYNCMMAXCORR 100 allows 100 MU (it allowed 50, taken as master
    qc). K34."""
    run = run_cam("SYNCCMM", line(max_correction=0), master=boxes(period=20000, offset=7000),
                  settings={"SYNCFACTM": 2, "SYNCFACTS": 1, "SYNCMMAXCORR": 100}, ms=1000)
    markers = run.controller.axis.sync.markers
    assert markers.errors[0] == pytest.approx(500, abs=10) and markers.corrections[:1] == pytest.approx([-100])


def test_a_changed_tolerance_window_applies_in_cam_mode_from_the_next_curve_restart():
    """CR 3936-3944 (SETCURVE while SYNCC is active): "33-21 and 33-22 Master and Slave Marker Tolerance Window, and
    all Curve-Array information will be updated, after the next restart of the curve"; DG 9636 ("Changes of the
    parameter will become active immediately – not only after the next SYNCM command") is read for SYNCM (K39).
    The box of the second cycle comes 600 MU late: a window of 100 set from the IDE during that cycle does not
    reject it yet; the third box, 600 late again, is then outside the window (it applied at once before)."""
    run = run_cam("SYNCCMM", line(max_correction=0), master=boxes(3500, 14100, 24700), ms=1100)
    run.link.write_parameter("SYNCMWINM", 100)     # at curve master 11000: the second cycle has begun
    run.advance(1500)
    markers = run.controller.axis.sync.markers
    assert markers.master.count == 2 and len(markers.errors) == 2   # the box at 14100 was accepted
    run.advance(1000)
    assert markers.master.count == 2 and run.controller.syncstat() & 32


def _shift_after_the_first_marker(run, ms: int) -> list[float]:
    """The curve master shift (MU) each ms from the first evaluated marker on."""
    ctl = run.controller
    run.advance(10)
    markers = ctl.axis.sync.markers
    while not markers.corrections:
        run.advance(1)
    out = []
    for _ in range(ms):
        out.append(ctl.axis.sync.cam.mu_shift)
        run.advance(1)
    return out


def test_syncofftime_shapes_a_cam_marker_correction_as_a_trapezoid():
    """DG 9833-9843 (33-27 SYNCOFFTIME): "The Offset Filter Time defines the time which should be used to compensate
    one marker distance … a trapezoidal movement … 20 % for acceleration, 60 % with constant velocity, and another
    20 % … not only used for offsets, but also for start corrections (first marker correction), normal marker
    corrections". In CAM one marker distance is one curve cycle (10000 MU): SYNCOFFTIME 10000 realises the box's
    −490 MU in 490 ms, half of it after 245 ms, at most 1.25 × the mean rate (K52; before it was not modelled)."""
    run = run_cam("SYNCCMM", line(correction_start=0, correction_end=0, max_correction=0), master=boxes(),
                  settings={"SYNCOFFTIME": 10000})
    shifts = _shift_after_the_first_marker(run, 700)
    x = run.controller.axis.sync.markers.corrections[0]      # the box came 490 MU late (see above): −490
    assert x == pytest.approx(-490)
    assert shifts[0] > -2 and shifts[245] == pytest.approx(x / 2, abs=3) and shifts[495] == pytest.approx(x, abs=1)
    assert max(abs(b - a) for a, b in zip(shifts, shifts[1:], strict=False)) == pytest.approx(1.25, abs=0.02)
    assert shifts[-1] == pytest.approx(x, abs=1)


def test_syncmftime_filters_a_cam_marker_correction():
    """DG 9905-9911 (33-29 SYNCMFTIME): "A marker error is corrected within a period of 2000 ms"; "the time which is
    needed to get an output corresponding to a steady input should be nearly SYNCMFTIME". SYNCMFTIME 3000: the
    box's −490 MU are corrected as a first-order filter with the time constant 1 s — 63 % after 1 s, 95 % after 3 s;
    the boxes that follow measure what is left and do not add it twice (K52)."""
    run = run_cam("SYNCCMM", line(correction_start=0, correction_end=0, max_correction=0), master=boxes(),
                  settings={"SYNCMFTIME": 3000})
    shifts = _shift_after_the_first_marker(run, 3001)
    x = run.controller.axis.sync.markers.corrections[0]
    assert x == pytest.approx(-490)
    assert shifts[990] == pytest.approx(x * (1 - math.exp(-0.99)), abs=3)
    assert shifts[3000] == pytest.approx(x * (1 - math.exp(-3)), abs=3)
    assert all(b <= a + 1e-9 for a, b in zip(shifts, shifts[1:], strict=False))       # never back
