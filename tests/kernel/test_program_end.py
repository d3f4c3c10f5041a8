"""What a program's end does to the motion (decision K49): positioning runs to its target, CAM disengages with the
second start/stop pair, speed mode and SYNCV/SYNCP/SYNCM stop with DEC."""

from __future__ import annotations

import pytest

from motiontool.camcurve import StartStopPair
from motiontool.kernel.master import MasterConfig
from tests.kernel.helpers import start
from tests.kernel.test_cam import cr_curve, run_with, setcurve

FAST = {"FFVEL": 1000}


def _stops_with_dec(run, dec: int) -> None:
    """After the program's end the slave brakes at DEC (here ACC 100 / DEC `dec`) to standstill and holds."""
    ctl = run.controller
    while run.state == "running":
        run.advance(1)
    v0 = ctl.axis.profile.velocity
    assert v0 > 10 and ctl.axis.mode == "stopping"
    run.advance(100)
    assert v0 - ctl.axis.profile.velocity == pytest.approx(100 * ctl.axis.scaling.acceleration(dec), rel=0.02)
    run.advance(5000)
    assert ctl.axis.mode == "idle" and ctl.axis.profile.velocity == 0 and ctl.axis.sync is None
    assert ctl.master.velocity > 0 and not run.errors            # the master runs on; the slave stands


@pytest.mark.parametrize("command", ["SYNCV", "SYNCP", "SYNCM"])
def test_a_synchronisation_stops_with_dec_when_its_program_ends(command):
    """DG 1488: "Empty main loop so that program will not be terminated" — a synchronisation lives as long as the
    program that started it; at the end it stops like MOTOR STOP, "with programmed acceleration" (CR 2367-2375).
    Before issue 17 the slave followed the master on after the program had ended."""
    run = start(f"VEL 100\nACC 100\nDEC 50\n{command}\nDELAY 1500\n", settings=FAST, master=MasterConfig(velocity=20))
    messages = []
    run.link.subscribe(lambda e: messages.append(e.text) if e.kind == "message" else None)
    _stops_with_dec(run, 50)
    assert messages == ["the program ended: the synchronisation stops with DEC"]   # the user sees why


def test_speed_mode_stops_with_dec_when_its_program_ends():
    run = start("VEL 100\nACC 100\nDEC 20\nCVEL 30\nCSTART\nDELAY 1000\n", settings=FAST)
    ctl = run.controller
    while run.state == "running":
        run.advance(1)
    assert ctl.axis.mode == "stopping"
    run.advance(3000)
    assert ctl.axis.mode == "idle" and ctl.axis.profile.velocity == 0


def test_positioning_runs_to_its_target_after_the_program_ends():
    """CR 1340-1342: "The EXIT command ends a program where active positioning procedures are being carried out to
    the end"; the same when the program just runs out."""
    for end in ("EXIT\n", ""):
        run = start("NOWAIT ON\nVEL 50\nACC 100\nDEC 100\nPOSA 100000\n" + end + 'PRINT "never"\n' * bool(end))
        ctl = run.controller
        run.advance(50)
        assert run.state == "ended" and ctl.axis.mode == "positioning"
        run.advance(5000)
        assert ctl.axis.mode == "idle" and ctl.axis.cpos == 100000 and run.prints == []


def test_cam_disengages_with_the_second_pair_when_the_program_ends():
    """DG 4054: "If the program is closed without the explicit command SYNCCSTOP pnum slavepos, then the second point
    pair will always be used for disengaging"; the slave stops at the Slave Stop Position (DG 3754-3757). Before
    issue 17 the slave stayed on the curve after the program had ended."""
    pairs = (StartStopPair(0, 0), StartStopPair(100, 300), StartStopPair(600, 900))
    curve = cr_curve(start_stop_pairs=pairs, slave_stop_position=0)
    run = run_with(setcurve(curve) + "SYNCC 0\nSYNCCSTART 1\nDELAY 1200\n", [curve],
                   master=MasterConfig(velocity=1.0, start_position_qc=50))
    ctl = run.controller
    left = stopped = None
    for _ in range(3000):
        run.advance(1)
        if ctl.axis.mode == "cam" and ctl.axis.sync.state == "curve":
            assert run.state == "running"
        m = ctl.master.mapos
        if left is None and ctl.axis.mode == "cam" and ctl.axis.sync.state == "disengage":
            left = m
        if stopped is None and ctl.axis.mode != "cam":
            stopped = m
    assert run.state == "ended" and not run.errors
    assert 1600 <= left <= 1602 and 1899 <= stopped <= 1901       # the program ended at 1201: the next pair 2
    assert ctl.axis.mode == "idle" and round(ctl.axis.cpos) == 2400   # 0 of a slave cycle (1200 each)


def test_cam_without_a_second_pair_stops_at_the_slave_stop_position_when_the_program_ends():
    curve = cr_curve(slave_stop_position=100)
    run = run_with(setcurve(curve) + "SYNCC 0\nDELAY 300\n", [curve], master=MasterConfig(velocity=2.0))
    ctl = run.controller
    run.advance(1000)
    assert run.state == "ended" and ctl.axis.mode == "idle" and not run.errors
    stop = ctl.axis.cpos
    assert ctl.uu(round(stop)) % 1200 == 100
    run.advance(1000)
    assert ctl.axis.cpos == stop and ctl.master.velocity == 2.0
