"""CAM control in the kernel: SETCURVE, CURVEPOS, DEFMCPOS, CMASTERCPOS, SYNCC n, SYNCCSTART/STOP (kernel-spec g)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.camcurve import Curve, FixPoint, StartStopPair, encode, interpolation_points, profile
from motiontool.controller.embedded import EmbeddedLink
from motiontool.kernel.cam import decode_curve_array
from motiontool.kernel.master import MasterConfig
from tests.kernel.helpers import start

LOOP = "WHILE 1 DO\nENDWHILE\n"
# CR 693-712: the CURVEPOS sample's fix points (master, slave)
CR_POINTS = (FixPoint(0, 0), FixPoint(500, 500), FixPoint(700, 300), FixPoint(1000, 1200))
ONE_TO_ONE = {"SYNCFACTM": 1, "SYNCFACTS": 1, "FFVEL": 1000, "DFLTVEL": 100, "DFLTACC": 100}


def cr_curve(**kw) -> Curve:
    """Fix points only (MCO ≥ 5.00, CR 3955-3958: "no interpolation points are used anymore")."""
    return Curve("cr", 1000, CR_POINTS, interpolation=False, **kw)


def setcurve(curve: Curve) -> str:
    """The program lines that select a curve: DIM name[size] and SETCURVE name (DG 1474-1480)."""
    return f"DIM {curve.name}[{len(encode(curve))}]\nSETCURVE {curve.name}\n"


def run_with(source: str, curves, settings=None, master=None, ms: int = 0):
    link = EmbeddedLink(master=master or MasterConfig())
    link.call("restore_arrays", arrays=[{"name": c.name if isinstance(c, Curve) else "raw",
                                         "values": encode(c) if isinstance(c, Curve) else c} for c in curves])
    run = start(source, settings={**ONE_TO_ONE, **(settings or {})}, link=link)
    if ms:
        run.advance(ms)
    return run


def test_curvepos_at_fix_points_equals_their_slave_values_and_ignores_the_slave():
    """CR 666-712: CURVEPOS "returns the slave value which corresponds to the actual curve master position" and
    "is independent of the slave position" (Case 1 slave 200 / Case 2 slave 700 give the same value); a fix-point
    curve is evaluated with the CAM editor's spline (camcurve.spline)."""
    f = profile(cr_curve())
    lines = [setcurve(cr_curve())]
    for m in (0, 500, 700, 1000, 800, 250):
        lines += [f"DEFMCPOS {m}", "PRINT CURVEPOS"]
    lines += ["DEFMCPOS 800", "POSA 200", "PRINT CURVEPOS", "POSA 700", "PRINT CURVEPOS"]
    run = run_with(lines[0] + "\n".join(lines[1:]) + "\n", [cr_curve()], ms=5000)
    assert not run.errors and run.state == "ended"
    values = [int(v) for v in run.prints]
    assert values[:4] == [0, 500, 300, 0]            # 1000 is the next cycle's 0 (slave length 1200 → 1200 − 1200)
    assert values[4] == round(f.slave(800)) and values[5] == round(f.slave(250))
    assert values[6] == values[7] == round(f.slave(800))


def test_curvepos_at_the_cycle_end_and_whole_cycles():
    """A fix point's master position gives its slave value; M + MasterCycleLen gives + SlaveCycleLen (issue 5)."""
    run = run_with(setcurve(cr_curve()) + "DEFMCPOS 999\nPRINT CURVEPOS\n",
                   [cr_curve()], ms=100)
    f = profile(cr_curve())
    assert int(run.prints[0]) == round(f.slave(999))
    assert f.slave(700 + 3 * 1000) == pytest.approx(300 + 3 * 1200)


@pytest.mark.parametrize("corrupt, where", [
    (lambda v: v[:-1], "DIM cr[{n}] (one element short)"),
    (lambda v: v + [0], "one element too many"),
    (lambda v: [v[0] + 1] + v[1:], "identification"),
    (lambda v: v[:15 + 14 + 2 + 5] + [9] + v[15 + 14 + 2 + 6:], "fix point type code"),
])
def test_setcurve_rejects_a_malformed_or_wrongly_sized_array_with_191(corrupt, where):
    """DG 11816-11830: "Illegal cam array" (191) for an invalid array or a DIM order mismatch; the message names
    the APOSS element (1-based) as docs/formats/cam-array.md specifies."""
    values = corrupt(encode(cr_curve()))
    run = run_with(f"DIM raw[{len(values)}]\nSETCURVE raw\nPRINT \"not reached\"\n", [values], ms=200)
    assert [e.number for e in run.errors] == [191], where
    assert not run.prints and run.state == "error"
    assert "raw[" in run.controller.error_history[-1].detail


def test_setcurve_rejects_more_than_2000_elements():
    """CR 3949-3952: "For that reason the maximum array size is 2000"."""
    run = run_with("DIM big[2001]\nSETCURVE big\n", [[0] * 2001], ms=100)
    assert [e.number for e in run.errors] == [191]


def test_syncc_without_setcurve_is_191():
    """CR 3913-3917: SETCURVE "has to be used, before the commands CURVEPOS, SYNCCxx … can be used"."""
    run = start("SYNCC 0\n")
    run.advance(100)
    assert [e.number for e in run.errors] == [191]


def test_cmastercpos_is_computed_from_mapos_and_moved_by_defmcpos_and_movesyncorigin():
    """CR 3928-3947: SETCURVE outside SYNCC computes CMASTERCPOS (SYSVAR 4230) from MAPOS; DEFMCPOS p makes the
    current master position p (CR 827-843); MOVESYNCORIGIN acts on it at once. 1 MU = SYNCFACTM/SYNCFACTS qc."""
    src = (setcurve(cr_curve()) + "PRINT SYSVAR[4230]\nDEFMCPOS 100\nPRINT SYSVAR[4230]\nDELAY 100\n"
           "PRINT SYSVAR[4230]\nMOVESYNCORIGIN 200\nPRINT SYSVAR[4230]\n")
    run = run_with(src, [cr_curve()], settings={"SYNCFACTM": 2, "SYNCFACTS": 1},
                   master=MasterConfig(velocity=4.0, start_position_qc=5000), ms=1000)
    assert not run.errors
    first, defined, later, moved = (int(v) for v in run.prints)
    mapos_mu = (5000 + 4) // 2                      # the program's first tick: MAPOS 5004 qc = 2502 MU
    assert first == mapos_mu % 1000
    assert defined == 100 and later == 100 + 200    # 100 ms at 4 qc/ms = 400 qc = 200 MU
    assert moved == later + 100                     # 200 master qc = 100 MU


def test_syncc_follows_whole_cycles_and_stops_at_the_slave_stop_position_after_n_cycles():
    """DG 7261: SYNCC num = "number of curves to be processed"; DG 3754-3760: the Slave Stop Position "will also be
    used if SYNCC starts with a specific number of cycles and does not use a SYNCCSTOP command". The first cycle
    is the one SYNCC starts in; without a second pair the slave positions to the stop position after the n-th."""
    curve = cr_curve(slave_stop_position=100)
    src = setcurve(curve) + "SYNCC 2\n" + LOOP
    run = run_with(src, [curve], master=MasterConfig(velocity=2.0))
    ctl = run.controller
    run.advance(300)
    motion = ctl.axis.sync
    assert ctl.axis.mode == "cam" and motion.state == "curve"
    f = profile(curve)
    assert ctl.axis.cpos == pytest.approx(f.slave(motion.cam.master_position()))
    run.advance(800)                               # master at 2200 MU: the 2nd cycle (1000-2000) is done
    assert ctl.axis.mode in ("positioning", "idle")
    run.advance(3000)
    assert ctl.axis.mode == "idle" and not run.errors
    assert ctl.uu(round(ctl.axis.cpos)) == 2400 + 100   # two slave cycles (1200 each) + Slave Stop Position


def test_syncc_n_disengages_with_the_second_pair_in_the_last_cycle():
    """DG 4054: "the second point pair will always be used for disengaging" when no SYNCCSTOP is given; the
    disengage path leaves the curve at Start (600) and is at rest at the stop position at Stop (900)."""
    pairs = (StartStopPair(0, 0), StartStopPair(100, 300), StartStopPair(600, 900))
    curve = cr_curve(start_stop_pairs=pairs, slave_stop_position=0)
    run = run_with(setcurve(curve) + "SYNCC 1\n" + LOOP, [curve],
                   master=MasterConfig(velocity=1.0, start_position_qc=50))
    ctl = run.controller
    left = stopped = None
    for _ in range(2000):
        run.advance(1)
        m = ctl.master.mapos
        if left is None and ctl.axis.mode == "cam" and ctl.axis.sync.state == "disengage":
            left = m
        if stopped is None and ctl.axis.mode != "cam":
            stopped = m
    assert 600 <= left <= 602 and 899 <= stopped <= 901
    assert ctl.axis.mode == "idle" and round(ctl.axis.cpos) == 1200   # 0 of the next slave cycle, nearest
    assert not run.errors


def test_synccstart_waits_for_the_start_point_then_engages_along_the_path():
    """DG 4040-4046: forward, synchronisation "begins at the Start point and end at the Stop point"; the engage
    path starts at the slave stop position at rest and meets the curve at Stop (DG 3916-3930)."""
    pairs = (StartStopPair(0, 0), StartStopPair(200, 500))
    curve = cr_curve(start_stop_pairs=pairs)
    run = run_with(setcurve(curve) + "SYNCC 0\nSYNCCSTART 1\n" + LOOP, [curve],
                   master=MasterConfig(velocity=1.0))
    ctl = run.controller
    f = profile(curve)
    trace = []
    for _ in range(700):
        run.advance(1)
        trace.append((ctl.master.mapos, ctl.axis.cpos, ctl.syncstat()))
    assert all(c == 0 and not st & 1 for m, c, st in trace if m <= 200)     # waits at the stop position
    moving = [(m, c) for m, c, _ in trace if 200 < m < 500]
    assert all(0 < c < f.slave(m) + 1e-9 for m, c in moving[5:])            # on the way to the curve
    assert all(c == pytest.approx(f.slave(m)) for m, c, _ in trace if m >= 501)
    assert all(st & 1 for m, _, st in trace if m >= 510)                    # READY on the curve
    velocities = [b[1] - a[1] for a, b in zip(trace, trace[1:], strict=False)]
    assert max(abs(b - a) for a, b in zip(velocities, velocities[1:], strict=False)) < 0.05  # no velocity jump


def test_synccstop_with_start_equal_stop_pair_zero_stops_at_the_position_with_vel_and_dec():
    """DG 4050: Start = Stop → "with the set maximum velocity (i.e. without a curve)"; SYNCCSTOP pnum slavepos
    stops at slavepos; SYNCSTAT is no longer READY and SYNCERR 0 afterwards."""
    curve = cr_curve()
    src = setcurve(curve) + "SYNCC 0\nDELAY 300\nSYNCCSTOP 0 50\nWAITAX\nPRINT CPOS, \" \", SYNCSTAT\n"
    run = run_with(src, [curve], master=MasterConfig(velocity=1.0), ms=3000)
    assert not run.errors
    cpos, syncstat = (int(v) for v in run.prints[0].split())
    assert cpos == 50 and syncstat & 1 == 0
    assert run.controller.axis.mode == "idle" and run.controller.syncerr() == 0


def test_motor_stop_ends_the_cam_synchronisation():
    """CR 2367-2375: MOTOR STOP stops a synchronisation with DEC; CONTINUE does not resume it (CR 574)."""
    src = setcurve(cr_curve()) + "SYNCC 0\nDELAY 300\nMOTOR STOP\nCONTINUE\nPRINT AXEND\n"
    run = run_with(src, [cr_curve()], master=MasterConfig(velocity=2.0), ms=2000)
    ctl = run.controller
    assert ctl.axis.mode == "idle" and ctl.axis.sync is None and ctl.syncstat() == 0
    assert not run.errors


def test_defsyncorigin_with_a_curve_follows_the_command_reference_example():
    """CR 913-945: line (0,0)-(2000,4000), gears 1:1, slave at 11000 qc, master at 15000 qc. A plain SETCURVE/SYNCC
    finds master curve position 1000, csstart 8000 and drives the slave to 10000; after DEFSYNCORIGIN 500 100000
    "csstart will be set to 10000" and the slave "just follow[s] the curve" (stays at 11000)."""
    line = Curve("line", 2000, (FixPoint(0, 0), FixPoint(500, 1000), FixPoint(1000, 2000), FixPoint(2000, 4000)),
                 interpolation=False)
    n = len(encode(line))
    for origin, expected in (("", 10000), ("DEFSYNCORIGIN 500 100000\n", 11000)):
        src = f"DIM line[{n}]\nPOSA 11000\nSETCURVE line\n{origin}SYNCC 0\nDELAY 2000\nPRINT CPOS, \" \", CURVEPOS\n"
        run = run_with(src, [line], master=MasterConfig(start_position_qc=15000), ms=8000)
        assert not run.errors
        cpos, curvepos = (int(v) for v in run.prints[0].split())
        assert cpos == expected and curvepos == expected


def test_on_mcpos_fires_once_per_cycle_when_the_curve_master_passes():
    """DG 1758-1760: ON MCPOS "call up a subprogram whenever a defined master position has been passed";
    the curve master position restarts every cycle (CAM box)."""
    src = (setcurve(cr_curve()) + "n = 0\nON MCPOS 250 GOSUB hit\nWHILE n < 3 DO\nENDWHILE\nPRINT TIME\n"
           "SUBMAINPROG\nSUBPROG hit\n  n = n + 1\n  PRINT SYSVAR[4230]\nRETURN\nENDPROG\n")
    run = run_with(src, [cr_curve()], master=MasterConfig(velocity=2.0), ms=3000)
    assert not run.errors and run.state == "ended"
    hits = [int(v) for v in run.prints[:3]]
    assert all(250 <= h <= 252 for h in hits)
    assert 1125 <= int(run.prints[3]) <= 1130      # one hit per 500 ms cycle: at 125, 625 and 1125 ms


def test_on_mcpos_at_the_cycle_start_fires_when_the_curve_restarts_and_setout_works_backwards():
    """CR 2883-2984: a position interrupt fires when the position is passed in the given direction; the curve
    master position 0 is passed at every curve restart (MasterCycleLen → 0), forward and (ON -MCPOS) backward."""
    src = (setcurve(cr_curve()) + "n = 0\nON MCPOS 0 GOSUB hit\nON -MCPOS 900 SETOUT 3\nWHILE n < 2 DO\nENDWHILE\n"
           "PRINT TIME\nSUBMAINPROG\nSUBPROG hit\n  n = n + 1\nRETURN\nENDPROG\n")
    run = run_with(src, [cr_curve()], master=MasterConfig(velocity=4.0), ms=1000)
    assert not run.errors and run.state == "ended"
    assert 500 <= int(run.prints[0]) <= 503                      # restarts at 250 ms and 500 ms (4 MU/ms)
    assert run.controller.io.outputs.get(3, 0) == 0              # never passed 900 backwards
    run = run_with(setcurve(cr_curve()) + "ON -MCPOS 900 SETOUT 3\n" + LOOP, [cr_curve()],
                   master=MasterConfig(velocity=-4.0, start_position_qc=1000), ms=100)
    assert run.controller.io.outputs.get(3) == 1                 # 0 → 999 (restart backwards) → 900 passed


def test_setcurve_and_defmcpos_during_syncc_take_effect_at_the_next_curve_restart():
    """CR 3936-3944: "If SETCURVE is used while SYNCC is active, the CMASTERCPOS will not be changed … all
    Curve-Array information will be updated, after the next restart of the curve"; DEFMCPOS "is executed with next
    restart of curve". The slave's target stays continuous across the switch."""
    flat = Curve("flat", 1000, (FixPoint(0, 0), FixPoint(250, 500), FixPoint(500, 1000), FixPoint(1000, 2000)),
                 interpolation=False)
    src = (f"DIM cr[{len(encode(cr_curve()))}]\nDIM flat[{len(encode(flat))}]\nSETCURVE cr\nSYNCC 0\nDELAY 100\n"
           "SETCURVE flat\nDEFMCPOS 100\nPRINT SYSVAR[4230]\n" + LOOP)
    run = run_with(src, [cr_curve(), flat], master=MasterConfig(velocity=2.0))
    ctl = run.controller
    run.advance(150)
    motion = ctl.axis.sync
    assert 200 <= int(run.prints[0]) <= 204 and motion.cam.curve.decoded.name == "cr"  # unchanged until restart
    targets = []
    for _ in range(600):
        run.advance(1)
        targets.append(motion.target)
    assert motion.cam.curve.decoded.name == "flat"
    assert 0 <= ctl.read_pseudo(0, 4230) - (100 + 2 * (ctl.time_ms - 500)) <= 2   # restart at 500 ms → 100
    steps = [b - a for a, b in zip(targets, targets[1:], strict=False)]
    assert max(abs(x) for x in steps) < 10                                  # no jump at the switch
    assert steps[-1] == pytest.approx(2 * 2.0)                              # slope 2 UU/MU at 2 MU/ms, gear 1:1
    assert not run.errors


def test_backward_master_engages_at_stop_and_is_on_the_curve_at_start():
    """DG 4026-4046: "When the master moves backward, engaging is shown by the disengage path … When moving
    backward, it begins at the Stop point and ends at the Start point"."""
    pairs = (StartStopPair(0, 0), StartStopPair(200, 500))
    curve = cr_curve(start_stop_pairs=pairs)
    run = run_with(setcurve(curve) + "SYNCC 0\nSYNCCSTART 1\n" + LOOP, [curve],
                   master=MasterConfig(velocity=-1.0, start_position_qc=800))
    ctl = run.controller
    f = profile(curve)
    trace = []
    for _ in range(700):
        run.advance(1)
        trace.append((ctl.master.mapos, ctl.axis.cpos))
    assert all(c == 0 for m, c in trace if m >= 500)                       # waits until Stop is passed backward
    assert any(c != 0 for m, c in trace if 200 < m < 500)                  # engaging between Stop and Start
    on = [(m, c) for m, c in trace if m <= 199]
    assert on and all(c == pytest.approx(f.slave(m)) for m, c in on)       # on the curve from Start on
    assert not run.errors


def test_synccstart_0_catches_up_within_vel_and_acc_then_syncstat_is_ready_and_accurate():
    """DG 1485 "Engage roller immediately with the set maximum velocity"; kernel-spec f.0: during any
    synchronisation the slave is limited by VEL and ACC/DEC (DG 796-798). SYNCSTAT: 1 READY on the curve,
    4 ACCURACY inside SYNCACCURACY (j.5); SYNCERR = target − actual in UU."""
    run = run_with(setcurve(cr_curve()) + "VEL 20\nACC 20\nDEC 20\nDEFMCPOS 700\nSYNCC 0\nSYNCCSTART 0\n" + LOOP,
                   [cr_curve()], settings={"SYNCACCURACY": 50})
    ctl = run.controller
    vel, acc = ctl.axis.scaling.velocity(20), ctl.axis.scaling.acceleration(20)
    run.advance(20)
    assert ctl.syncstat() & 5 == 0 and ctl.syncerr() > 200                # 300 UU to go, not ready
    peak_v = peak_a = 0.0
    for _ in range(3000):
        run.advance(1)
        peak_v = max(peak_v, abs(ctl.axis.profile.velocity))
        peak_a = max(peak_a, abs(ctl.axis.profile.acceleration))
    assert peak_v <= vel + 1e-9 and peak_a <= acc + 1e-9
    assert ctl.axis.cpos == 300 and ctl.syncstat() & 5 == 5 and abs(ctl.syncerr()) <= 2


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(1, 300), min_size=3, max_size=6), st.lists(st.integers(-2000, 2000), min_size=7,
       max_size=7), st.sampled_from([0, 1, 2]), st.booleans())
def test_the_kernel_evaluates_fix_point_curves_with_the_editors_spline(steps, slaves, curve_type, interpolation):
    """One implementation (issue 5): the kernel's curve is camcurve.spline's piecewise polynomial for fix-point
    arrays, and the straight lines between the array's interpolation points otherwise (DG 1366). At most 1800
    intervals of 10 MU, so every curve fits the controller's 2000 elements (CR 3949-3952, tested above)."""
    masters = [0]
    for s in steps:
        masters.append(masters[-1] + 10 * s)
    points = tuple(FixPoint(m, slaves[i]) for i, m in enumerate(masters))
    curve = Curve("p", masters[-1], points, interpolation=interpolation, intervals=masters[-1] // 10,
                  curve_type=curve_type)
    fn = decode_curve_array("p", encode(curve))
    xs = np.linspace(0, masters[-1], 97)
    if interpolation:
        expected = np.interp(xs, np.arange(curve.intervals + 1) * 10.0, interpolation_points(curve))
    else:
        expected = profile(curve).slave(xs, periodic=False)
    got = np.array([fn(float(x)) for x in xs])
    assert np.allclose(got, expected, rtol=0, atol=1e-6 * (1 + np.max(np.abs(expected))))
    for p in points:
        assert fn.periodic(p.master + 3 * masters[-1]) == pytest.approx(p.slave + 3 * curve.slave_length, abs=1e-6)
