"""The Design Guide's CAM application programs (DG 1342-1772) on the simulator, with a simulated conveyor master.

The programs are the manual's (tests/aposs/manual/D07-D09 and the CAM box fragment F_D10, with their OCR repairs; the
fragment gets the stamping set-up in the test); the curve arrays are the manual's
curves (tests/camcurve/conftest.py) encoded with camcurve.layout.encode and restored into the controller as a
.zbc download would (DG 1466-1468: "Load the .zbc file … by means of Parameters → Restore from file").
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from motiontool.camcurve import encode, interpolation_points, profile
from motiontool.controller.embedded import EmbeddedLink
from motiontool.kernel.master import MasterConfig
from motiontool.kernel.plant import PlantConfig
from tests.camcurve.conftest import marker_curve, stamping_curve
from tests.kernel.helpers import start

MANUAL = Path(__file__).parents[1] / "aposs" / "manual"
STAMPING, MARKER, SLAVESYNC, SLAVESYNC_PRINTED = (
    MANUAL / name for name in ("D07_cam_stamping.m", "D08_cam_marker_correction.m", "D09_cam_slave_marker_corrected.m",
                               "D09_cam_slave_marker.m"))
QC_PER_MU = 2048 / 55          # DG 1420: "2048/55 qc = 1 MU" (SYNCFACTM / SYNCFACTS)
QC_PER_UU = 25 / 9             # DG 1428: "25/9 qc = 1 UU" (POSFACT_Z / POSFACT_N)
CONVEYOR = 4000 * QC_PER_MU / 1000  # DG 1442, 1452: 60 boxes/min of 4000 MU → master qc per ms
# DG 1390-1431 (conveyor 25:11, 4096 PPR, 0.1 mm; roller 5:1, 500 PPR, 0.1°); the rest makes the simulated roller
# follow closely (velocity feed-forward) and gives HOME a reference switch near zero.
SETTINGS = {"SYNCFACTM": 2048, "SYNCFACTS": 55, "POSFACT_Z": 25, "POSFACT_N": 9, "ENCODER": 500, "FFVEL": 1000,
            "DFLTVEL": 100, "DFLTACC": 100, "I_FUNCTION_1": 1, "HOME_VEL": 50, "HOME_RAMP": 50}
PLANT = PlantConfig(home_switch_qc=2000)


def run_example(program: Path | str, curve, settings=None, inputs=None, master=None, plant=None):
    # the conveyor stands still until the test starts it; `master` can carry its photoelectric beam (input 5)
    link = EmbeddedLink(plant or PLANT, master=master or MasterConfig())
    link.call("restore_arrays", arrays=[{"name": curve.name, "values": encode(curve)}])
    text = program if isinstance(program, str) else program.read_text()
    run = start(text, settings={**SETTINGS, **(settings or {})}, inputs=inputs, link=link)
    ctl = run.controller
    for _ in range(200):  # HOME, SETCURVE, POSA CURVEPOS
        run.advance(100)
        if ctl.axis.mode == "cam" or run.state != "running":
            break
    assert not run.errors, [e.text for e in run.errors]
    return run


def start_conveyor(ctl, ramp_ms: int = 1000, speed: float = CONVEYOR) -> None:
    """The operator switches the conveyor on: it ramps up to 60 boxes/min."""
    now = ctl.time_ms
    ctl.master.config = MasterConfig(table=((now, 0.0), (now + ramp_ms, speed)))


def curve_master(ctl) -> float:
    return ctl.axis.sync.cam.master_position()


def slave_uu(ctl) -> float:
    return ctl.axis.cpos / QC_PER_UU


def test_stamping_roller_follows_the_curve_and_runs_at_1_2_through_the_tangent_section():
    """DG 1474-1494 (stamping): after HOME, SETCURVE, DEFMCPOS 1000, POSA CURVEPOS, SYNCC 0 and SYNCCSTART 0 "This
    does not cause any movement since the master is idle and in the correct position"; then the master is started.
    DG 1448: "Master and slave must run synchronously with the same velocity between the position 1500 and 2500" —
    the tangent (1500,1200)-(2500,2400) has slope 1.2 UU/MU; a cycle advances the roller one turn (3600 UU)."""
    run = run_example(STAMPING, stamping_curve())
    ctl = run.controller
    f = profile(stamping_curve())
    assert ctl.axis.mode == "cam" and ctl.read_pseudo(0, 4230) == 1000     # CMASTERCPOS (SYSVAR 4230)
    before = ctl.axis.cpos
    assert abs(slave_uu(ctl) - f.slave(1000)) < 1                           # POSA CURVEPOS
    run.advance(500)
    assert ctl.axis.cpos == before                                          # master idle: no movement
    assert ctl.syncstat() & 1                                               # on the curve (READY)
    start_conveyor(ctl)
    samples = []
    for _ in range(6000):
        run.advance(1)
        samples.append((curve_master(ctl), slave_uu(ctl), ctl.uu(ctl.axis.apos)))
    assert not run.errors
    # DG 1366: the controller interpolates linearly between the 41 interpolation points of the array
    grid, points = np.linspace(0, 4000, 41), interpolation_points(stamping_curve())

    def linear(m: float) -> float:
        return float(np.interp(m % 4000, grid, points)) + (m // 4000) * 3600

    chord = f.max_abs(2) * 100 ** 2 / 8 + 0.5  # chord error of 100 MU intervals + rounding of the stored points
    base = samples[0][1] - linear(samples[0][0])
    for m, s, _ in samples[::50]:
        assert s == pytest.approx(base + linear(m), abs=1e-6)              # CPOS on the curve (UU)
        assert abs(s - (base + f.slave(m))) <= chord                        # … within a chord of the spline
    lag = [abs(a - s) for _, s, a in samples]
    # the roller follows: APOS within 1°, on average within the ~1 ms loop lag of the plant (≤ 13 qc/ms = 4.8 UU)
    assert max(lag) <= 10 and sum(lag) / len(lag) <= 5
    tangent = {}
    for m, s, _ in samples:
        if 1600 < m % 4000 < 2400:
            tangent.setdefault(int(m // 4000), []).append((m, s))
    first, second = (tangent[k] for k in sorted(tangent)[:2])
    for section in (first, second):
        (m0, s0), (m1, s1) = section[0], section[-1]
        assert (s1 - s0) / (m1 - m0) == pytest.approx(1.2, abs=1e-9)       # synchronous at 1.2 UU/MU
    # whole cycles: the roller advances SlaveCycleLen 3600 UU (one turn) per MasterCycleLen 4000 MU
    (ma, sa), (mb, sb) = first[0], second[0]
    assert sb - 1.2 * (mb - ma - 4000) - sa == pytest.approx(3600, abs=1e-6)
    assert abs(ctl.syncerr()) <= 10 and ctl.syncstat() & 5 == 5                 # SYNCERR in UU, READY + ACCURACY


def test_printing_with_marker_engages_with_pair_1_and_disengages_with_pair_2_to_0_degrees():
    """DG 1500-1566 (printing with marker): pairs "1 1000 1500 / 2 2500 3000", "Slave Stop Position = 0";
    SYNCCSTART 1 "Engage roller with start point pair 1", WAITI 4 ON, SYNCCSTOP 2 0 "stop at position 0 degrees".
    Engaging forward runs from Start to Stop (DG 4040-4046): the roller stands until the curve master passes 1000
    and is on the curve at 1500; disengaging leaves the curve at 2500 and stands at 0° (mod 360°) at 3000.
    The photoelectric beam sees a box every 4000 MU; "SET SYNCMSTART 2000 // Counting of the master pulse does
    not begin until the next edge comes from the sensor" (DG 1558-1560) — the marker correction itself is
    tested in tests/kernel/test_cam_markers.py."""
    boxes = MasterConfig(marker_period_qc=4000 * QC_PER_MU, marker_offset_qc=20000)
    run = run_example(MARKER, marker_curve(), settings={"SYNCMPULSM": 2375, "SYNCMWINM": 200, "SYNCMTYPM": 2},
                      master=boxes)
    ctl = run.controller
    f = profile(marker_curve())
    assert ctl.read_pseudo(0, 4230) == 4000 - 1375                          # DEFMCPOS (1000 - 2375)
    rest = ctl.axis.cpos
    start_conveyor(ctl, ramp_ms=200)
    engaged_at = on_curve_at = None
    while on_curve_at is None:
        run.advance(1)
        m = curve_master(ctl) % 4000
        motion = ctl.axis.sync
        if engaged_at is None and ctl.axis.cpos != rest:
            engaged_at = m
        if motion.state == "curve":
            on_curve_at = m
        assert ctl.time_ms < 20_000
    assert 1000 <= engaged_at < 1010                                        # starts at Start = 1000
    assert 1500 <= on_curve_at < 1600                                       # on the curve from Stop = 1500 on
    run.advance(1500)
    motion = ctl.axis.sync
    assert ctl.axis.cpos == motion.target                                   # locked on the curve
    assert abs(slave_uu(ctl) - (motion.base / QC_PER_UU + f.slave(curve_master(ctl)))) <= 1.5  # linear vs spline
    ctl.io.inputs[4] = 1                                                    # the conveyor is being switched off
    left_at = None
    for _ in range(3000):
        run.advance(1)
        if ctl.axis.mode != "cam":
            break
        if left_at is None and ctl.axis.sync.state == "disengage":
            left_at = curve_master(ctl) % 4000
    assert 2500 <= left_at < 2510
    run.advance(500)
    assert ctl.axis.mode == "idle" and ctl.axis.profile.velocity == 0
    assert round(slave_uu(ctl)) % 3600 == 0                                 # stopped at 0 degrees
    assert abs(ctl.uu(ctl.axis.apos) - round(slave_uu(ctl))) <= 2
    assert run.state == "ended" and not run.errors


def test_cam_box_calls_the_drier_and_switches_outputs_at_curve_master_positions():
    """DG 1764-1772: "ON MCPOS 2500 GOSUB drier // Call up a subprogram when the master position 2500 is passed
    in positive direction" — OUT 1 1, DELAY 300, OUT 1 0, once per cycle; CR 2985-3016: ON posint … SETOUT sets an
    output in the background (output 2 on from 1500 to 2500 of every cycle). The fragment (F_D10) runs after the
    stamping set-up of DG 1474-1494 (ON MCPOS needs SETCURVE or DEFMCPOS first, CR 2894) and two SETOUT lines."""
    setup = ("DIM stamping[92]\nSETCURVE stamping\nDEFMCPOS 1000\nPOSA CURVEPOS\nON MCPOS 1500 SETOUT 2\n"
             "ON MCPOS 2500 SETOUT -2\nSYNCC 0\nSYNCCSTART 0\n")
    run = run_example(setup + (MANUAL / "F_D10_cam_box.m").read_text(), stamping_curve())
    ctl = run.controller
    start_conveyor(ctl, ramp_ms=10)
    trace = []
    for _ in range(3000):
        run.advance(1)
        trace.append((curve_master(ctl) % 4000, ctl.io.outputs.get(1, 0), ctl.io.outputs.get(2, 0)))
    assert not run.errors
    rises = [i for i in range(1, len(trace)) if trace[i][1] and not trace[i - 1][1]]
    falls = [i for i in range(1, len(trace)) if not trace[i][1] and trace[i - 1][1]]
    assert len(rises) == 3                                                  # 2500 passed 3× in 3 s (60/min)
    for r in rises:
        assert 2500 <= trace[r][0] <= 2500 + 2 * CONVEYOR / QC_PER_MU + 1   # within 1-2 ms of passing 2500
    for r, f in zip(rises, falls, strict=False):
        assert f - r == pytest.approx(300, abs=2)                           # dries for 300 ms
    for m, _, out2 in trace:
        if 1510 < m < 2490:
            assert out2 == 1
        elif m > 2510 or m < 1490:
            assert out2 == 0
