"""Synchronisation: master encoder, virtual master, exact gearing, SYNCV, SYNCP (kernel-spec a.3, f.0-f.4)."""

from __future__ import annotations

import math

import pytest

from motiontool.kernel.controller import Controller
from motiontool.kernel.master import Master, MasterConfig
from motiontool.kernel.sync import Gear
from tests.kernel.helpers import run_source, start

LOOP = "WHILE 1 DO\nENDWHILE\n"
FAST = {"FFVEL": 1000}  # velocity feed-forward: the slave follows with a small tracking error


def test_gear_has_no_drift_over_a_million_ticks():
    """DG 946: the gear must be exact, any rounding drifts. 55/2048 is the conveyor of DG 9344-9360."""
    master = Master(MasterConfig(velocity=1.37))
    gear = Gear(55, 2048, 0)
    last = master.raw
    for t in range(1, 1_000_001):
        master.tick(t)
        gear.advance(master.raw - last)
        last = master.raw
        if t % 250_000 == 0:
            assert gear.out == math.floor(master.raw * 55 / 2048) == (master.raw * 55) // 2048
    assert master.raw == 1_370_000
    assert gear.out == 1_370_000 * 55 // 2048


def test_gear_negative_factor_turns_the_direction():
    gear = Gear(3, -2, 0)
    assert gear.advance(5) == -8  # floor(-7.5)
    assert gear.advance(-5) == 0


def test_master_config_ramp_table_and_mavel():
    ramp = Master(MasterConfig(velocity=10.0, acceleration=0.01))
    for t in range(1, 2001):
        ramp.tick(t)
    assert ramp.velocity == 10.0
    assert ramp.mavel == 10_000  # qc/s over 20 ms (CR 2175-2195)
    table = Master(MasterConfig.from_mapping({"table": [(0, 0.0), (1000, 4.0), (2000, 4.0), (2500, -2.0)]}))
    speeds = []
    for t in range(1, 3001):
        table.tick(t)
        speeds.append(table.velocity)
    assert speeds[499] == pytest.approx(2.0) and speeds[1499] == 4.0 and speeds[2999] == -2.0
    with pytest.raises(ValueError):
        MasterConfig.from_mapping({"speed": 3})


def test_controller_takes_a_master_config_and_reports_mapos_mavel():
    ctl = Controller(master=MasterConfig(velocity=2.5))
    ctl.run_for(1000)
    assert ctl.master.mapos == 2500
    assert ctl.params.get(3452) == 2500          # 34-52 MAPOS
    assert ctl.params.get(3459) == 2500          # 34-59 MAVEL, qc/s
    assert Controller().master.mapos == 0        # default: the master stands still


def test_pulsvel_drives_the_master_and_pulsacc_applies_at_the_next_pulsvel():
    """CR 3552-3611: PULSVEL in Hz; one pulse = one encoder line = 4 qc (CR 3574-3611, kernel-spec p.7)."""
    run = run_source("PULSVEL 10000\nDELAY 1000\nPRINT MAPOS, \" \", MAVEL, \" \", SYSVAR[4105]\n"
                     "PULSACC 20000\nDELAY 500\nPRINT MAVEL\nPULSVEL 0\nDELAY 2500\nPRINT MAVEL\n"
                     "PULSACC 0\nPULSVEL 5000\nDEFMORIGIN\nDELAY 100\nPRINT MAPOS\n"
                     "SETMORIGIN 1000\nPRINT MAPOS\n", 8000)
    assert not run.errors
    mapos, mavel, sysvar = (int(x) for x in run.prints[0].split())
    assert abs(mapos - 40_000) <= 40 and mavel == 40_000 and sysvar == mapos
    assert run.prints[1] == "40000"          # PULSACC waits for the next PULSVEL
    assert run.prints[2] == "0"              # 80 qc/ms² … 40 qc/ms → 0 in 0.5 s: stopped after 2.5 s
    # PULSACC 0 + PULSVEL switches the virtual master off (the default external master stands still), DEFMORIGIN
    assert run.prints[3] == "0"
    assert int(run.prints[4]) == run.controller.master.raw - 1000 == 68_980  # SETMORIGIN 1000: counter 1000 is 0


def test_syncv_slave_velocity_is_master_velocity_times_the_gear():
    """DG 9318-9324: slave velocity = master velocity · SYNCFACTS / SYNCFACTM, reached with ACC (DG 796-798)."""
    run = start("VEL 100\nACC 100\nSYNCV\n" + LOOP, settings={"SYNCFACTS": 55, "SYNCFACTM": 32, **FAST},
                master=MasterConfig(velocity=20.0))
    ctl = run.controller
    run.advance(100)
    assert 0 < ctl.axis.profile.velocity < 20.0 * 55 / 32  # still on the ACC ramp
    run.advance(1900)
    assert ctl.axis.mode == "sync"
    assert ctl.axis.profile.velocity == pytest.approx(20.0 * 55 / 32)
    assert abs(ctl.avel() - 34_375) < 50                 # AVEL in UU/s
    assert not run.errors


def test_syncv_is_limited_by_vel():
    run = start("VEL 10\nACC 100\nSYNCV\n" + LOOP, settings=FAST, master=MasterConfig(velocity=50.0))
    run.advance(2000)
    assert run.controller.axis.profile.velocity == pytest.approx(run.controller.axis.scaling.velocity(10))


def test_syncp_catches_up_then_cpos_follows_mapos_exactly():
    """DG 944-1140: CPOS = MAPOS · gear + offset from the relation at the start (K17); a slave standing while the master
    runs lags behind first and catches up within VEL/ACC (K18), then it is locked: CPOS follows exactly."""
    settings = {"SYNCFACTS": 55, "SYNCFACTM": 32, "SYNCPOSOFFS": 1000, **FAST}
    run = start("VEL 100\nACC 100\nDEC 100\nm0 = MAPOS\nSYNCP\nPRINT m0\n"
                "WHILE 1 DO\n  IF (SYNCSTAT & 4) THEN\n    OUT 1 1\n  ELSE\n    OUT 1 0\n  ENDIF\nENDWHILE\n",
                settings=settings, master=MasterConfig(velocity=20.0, start_position_qc=20000))
    ctl = run.controller
    run.advance(200)
    assert not ctl.axis.sync.locked and ctl.io.outputs.get(1, 0) == 0  # still catching up
    m0 = int(run.prints[0])
    peak = 0.0
    for _ in range(30):
        run.advance(100)
        peak = max(peak, abs(ctl.axis.profile.velocity))
    assert peak <= ctl.axis.scaling.velocity(100) + 1e-9
    assert ctl.axis.sync.locked
    for _ in range(50):
        run.advance(7)
        assert ctl.uu(ctl.axis.cpos) == (ctl.master.mapos - m0 + 1000) * 55 // 32
    assert abs(ctl.syncerr()) < 100
    assert ctl.syncstat() & 4 and ctl.params.get(3460) & 4
    assert ctl.io.outputs.get(1) == 1                                  # DG 1055: IF (SYNCSTAT & 4)
    assert not run.errors


def test_syncp_locks_the_slave_to_the_master_where_they_stand():
    """DG 948: "When starting position synchronizing the actual slave position will be locked to the actual master
    position, it is thus necessary to bring the slave into the right physical position with respect to the physical
    position of the master." With the master at 233 512 qc the slave used to chase MAPOS × gear from absolute 0 at
    full speed; now it stays where it is until the master moves and then follows it (K17)."""
    master = MasterConfig(table=((0, 0.0), (1000, 0.0), (1500, 10.0)), start_position_qc=233_512)
    run = start("VEL 100\nACC 100\nDEC 100\nPOSA 5000\nSYNCP\n" + LOOP,
                settings={"SYNCFACTS": 3, "SYNCFACTM": 2, **FAST}, master=master)
    ctl = run.controller
    run.advance(900)
    assert ctl.axis.mode == "sync" and ctl.axis.sync.locked and ctl.axis.cpos == 5000
    assert ctl.syncstat() & 4 and ctl.syncerr() <= 2
    fastest = 0.0
    for _ in range(2100):
        run.advance(1)
        fastest = max(fastest, ctl.axis.profile.velocity)
        assert ctl.uu(ctl.axis.cpos) == 5000 + (ctl.master.mapos - 233_512) * 3 // 2
    assert fastest == pytest.approx(15.0)    # master 10 qc/ms × 3/2: never more
    assert not run.errors


def test_syncerr_is_signed_with_negative_syncaccuracy():
    """DG 9430-9460: SYNCACCURACY < 0 reports SYNCERR with its sign (target − actual: + = slave behind)."""
    for accuracy, sign in ((1000, 1), (-1000, 1)):
        run = start("VEL 100\nACC 100\nSYNCP\n" + LOOP, settings={"SYNCACCURACY": accuracy},
                    master=MasterConfig(velocity=20.0, start_position_qc=50000))
        run.advance(50)
        assert run.controller.syncerr() * sign > 0     # behind the target
    run = start("VEL 100\nACC 100\nSYNCP\n" + LOOP, settings={"SYNCACCURACY": -1000},
                master=MasterConfig(velocity=-20.0, start_position_qc=-50000))
    run.advance(50)
    assert run.controller.syncerr() < 0                # the target is below: signed negative
    run = start("VEL 100\nACC 100\nSYNCP\n" + LOOP, settings={"SYNCACCURACY": 1000},
                master=MasterConfig(velocity=-20.0, start_position_qc=-50000))
    run.advance(50)
    assert run.controller.syncerr() > 0                # absolute


def test_movesyncorigin_and_syncposoffs_shift_the_slave_within_the_limits():
    run = start("VEL 100\nACC 100\nDEC 100\nm0 = MAPOS\nSYNCP\nPRINT m0\nDELAY 500\nMOVESYNCORIGIN 4000\nDELAY 1500\n"
                "SET SYNCPOSOFFS -2000\n" + LOOP,
                settings={"SYNCFACTS": 3, "SYNCFACTM": 2, **FAST}, master=MasterConfig(velocity=10.0))
    ctl = run.controller
    run.advance(500)
    assert ctl.axis.sync.locked
    last_v = ctl.axis.profile.velocity
    amax = ctl.axis.scaling.acceleration(100)
    for _ in range(1500):
        run.advance(1)
        v = ctl.axis.profile.velocity
        assert abs(v - last_v) <= amax + 1e-9  # smooth: no jump of the commanded velocity
        last_v = v
    assert ctl.axis.sync.locked
    m0 = int(run.prints[0])
    assert ctl.uu(ctl.axis.cpos) == (ctl.master.mapos - m0 + 4000) * 3 // 2
    run.advance(1500)
    assert ctl.axis.sync.locked
    assert ctl.uu(ctl.axis.cpos) == (ctl.master.mapos - m0 + 4000 - 2000) * 3 // 2
    assert not run.errors


def test_defsyncorigin_relates_a_master_and_a_slave_position():
    """CR 891-975 sample: master 2000 qc ↔ slave 4000 qc, then master 3000 ↔ slave 5000 (gear 1:1)."""
    run = start("DEFSYNCORIGIN 2000 4000\nVEL 100\nACC 100\nSYNCP\n" + LOOP, settings=FAST,
                master=MasterConfig(velocity=1.0, start_position_qc=1999))
    ctl = run.controller
    run.advance(3000)
    assert ctl.axis.sync.locked
    assert ctl.uu(ctl.axis.cpos) == ctl.master.mapos + 2000


def test_motor_stop_leaves_sync_with_dec_and_continue_does_not_resume():
    run = start("VEL 100\nACC 100\nDEC 50\nSYNCV\nDELAY 1500\nMOTOR STOP\nPRINT AXEND\nCONTINUE\nDELAY 100\n"
                "PRINT AXEND\n" + LOOP, settings=FAST, master=MasterConfig(velocity=30.0))
    ctl = run.controller
    run.advance(1500)
    assert ctl.axis.mode == "sync"
    run.advance(1)
    v0 = ctl.axis.profile.velocity
    run.advance(100)
    assert ctl.axis.mode == "stopping"
    assert v0 - ctl.axis.profile.velocity == pytest.approx(100 * ctl.axis.scaling.acceleration(50), rel=0.02)
    run.advance(1000)
    assert ctl.axis.mode == "idle" and ctl.axis.sync is None
    assert ctl.axis.profile.velocity == 0.0 and run.prints == ["1", "1"]
    assert ctl.syncstat() == 0 and ctl.syncerr() == 0


def test_sync_needs_no_pending_error_and_esc_stops_the_virtual_master():
    run = start("PULSVEL 1000\nSYNCP\n" + LOOP)
    run.advance(500)
    run.controller.break_program()
    run.advance(500)
    assert run.controller.master.velocity == 0.0
    assert run.controller.axis.mode == "idle"


def test_the_origin_of_synchronisation_belongs_to_each_syncp():
    """CR 2397-2415: MOVESYNCORIGIN "shifts the origin of synchronization … relates to the last one"; CR 903-906:
    DEFSYNCORIGIN's internal MOVESYNCORIGIN is done "at the moment, when the SYNC command is activated". So a
    MOVESYNCORIGIN before SYNCP shifts the relation that SYNCP locks (DG 948), a SYNCP given while one runs keeps the
    running relation, and after MOTOR STOP a new SYNCP locks afresh without the old relative shifts (K17). SYNCM
    starts "like position synchronization" (DG 1149)."""
    master = MasterConfig(table=((0, 0.0), (400, 0.0), (500, 4.0)), start_position_qc=100_000)
    run = start("VEL 100\nACC 100\nDEC 100\nMOVESYNCORIGIN 600\nSYNCP\nDELAY 1000\nPRINT CPOS - (MAPOS - 100000)\n"
                "MOVESYNCORIGIN -200\nDELAY 500\nSYNCP\nDELAY 500\nPRINT CPOS - (MAPOS - 100000)\n"
                "MOTOR STOP\nDELAY 200\nc = CPOS\nm = MAPOS\nSYNCM\nDELAY 500\nPRINT CPOS - c - (MAPOS - m)\n" + LOOP,
                settings=FAST, master=master)
    ctl = run.controller
    run.advance(300)
    assert ctl.axis.cpos == pytest.approx(600, abs=1e-9)        # the shift is realised at the start
    run.advance(3000)
    assert not run.errors
    first, kept, afresh = (int(p) for p in run.prints)
    assert first == 600                                            # the master has moved meanwhile
    assert kept == 400                                             # 600 − 200, the second SYNCP changed nothing
    assert afresh == 0                                             # no shift carried into the new SYNCM


def test_the_gear_changes_during_synchronisation():
    """DG 796: "Electronic synchronization is very flexible compared to a mechanical shaft … as the gear-ratio and
    position offset can be adjusted during operation"; 33-10/33-11 change during operation (DG 11209-11210 TRUE). A
    SET of SYNCFACTS during SYNCV changes the slave velocity (ramped with ACC) and during SYNCP the ratio from the
    target's current position on — without another SYNC command (K21; before, nothing changed until one)."""
    run = start("VEL 100\nACC 100\nDEC 100\nSYNCV\nDELAY 1000\nSET SYNCFACTS 2\n" + LOOP, settings=FAST,
                master=MasterConfig(velocity=20.0))
    run.advance(1000)
    assert run.controller.axis.profile.velocity == pytest.approx(20.0)
    run.advance(1000)
    assert run.controller.axis.profile.velocity == pytest.approx(40.0)      # 20 qc/ms × 2/1, ramped in 200 ms
    run = start("VEL 100\nACC 100\nDEC 100\nSYNCP\nDELAY 1000\nSET SYNCFACTS 3\n" + LOOP,
                settings={"SYNCFACTM": 2, **FAST}, master=MasterConfig(velocity=10.0))
    ctl = run.controller
    run.advance(1001)
    cpos, mapos = ctl.axis.cpos, ctl.master.mapos
    assert ctl.axis.profile.velocity == pytest.approx(5.0)                  # 10 × 1/2
    run.advance(1000)
    assert ctl.axis.sync.locked and ctl.axis.profile.velocity == pytest.approx(15.0)   # 10 × 3/2
    moved = ctl.axis.sync.target - cpos
    assert moved == pytest.approx((ctl.master.mapos - mapos) * 3 / 2, abs=2)     # the target went on from there


@pytest.mark.parametrize("sync", ["SYNCP", "SYNCV", "SYNCM"])
def test_deforigin_during_synchronisation(sync):
    """CR 863: "With the DEFORIGIN command the current position is set as the zero point" (the sample's output,
    CR 880: "Position after defining new origin 0"). During a synchronisation too: before commit db586ff the
    program stopped with error 199 (SyncMotion's attribute `shift` hid the method DEFORIGIN calls). The slave
    then follows the master on from the new zero: 500 Hz × 4 qc (decisions K15) = 400 qc in 200 ms."""
    run = run_source(f"VEL 100\nACC 100\nDEC 100\nPULSVEL 500\n{sync}\nDELAY 500\nDEFORIGIN\nPRINT APOS\n"
                     "DELAY 200\nPRINT APOS\n", 3000)
    assert [e.text for e in run.errors] == []
    assert run.prints[0] == "0"
    assert abs(int(run.prints[1]) - 400) <= 5
