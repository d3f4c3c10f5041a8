"""The APC manual's programs (tests/dpl/programs, seed 004 §6.4 and §7.1-§7.6) running on the simulated APC with
the behaviour the manual describes."""

from __future__ import annotations

from motiontool.apc import ApcDrive, CTSyncLine, PlantConfig
from motiontool.dpl.driver import check_source
from motiontool.dpl.runtime import DplRuntime
from tests.dpl.manual import PROGRAMS

REV = 65536
PROFILE_MAX = 16106127                  # MULDIV(2^30, 1000 * 90, 60000 * 100): 900 rpm (§7 Notes)
FLAGS = {124: "accelerating", 125: "decelerating", 126: "constant +speed", 120: "at target"}


def load(name: str, drive: ApcDrive | None = None, text: str | None = None) -> DplRuntime:
    checked = check_source(text, PROGRAMS / f"{name}.dpl") if text else check_source(path=PROGRAMS / f"{name}.dpl")
    assert checked.ok
    runtime = DplRuntime(drive or ApcDrive(), checked)
    runtime.listeners.append(lambda kind, value: kind != "error" or (_ for _ in ()).throw(AssertionError(value)))
    return runtime


def flag_phases(samples: list[int]) -> list[str]:
    """The [186] words of a move as the sequence of its phases (each run of equal flags once)."""
    phases: list[str] = []
    for word in samples:
        names = [FLAGS[n] for n in (124, 126, 125, 120) if word >> (n - 120) & 1]
        profiling = bool(word >> 9 & 1)
        phase = " + ".join(names) + (" (profiling)" if profiling else "")
        if not phases or phases[-1] != phase:
            phases.append(phase)
    return phases


def test_s7_1_lands_exactly_on_the_set_point_with_the_documented_flag_sequence():
    """§7.1: set point in 0.1 rev from #18.11, 900 rpm profile, 2 s acceleration and 1 s deceleration (L5067-5073);
    the flags of a position profile (L854-912): accelerating, constant speed, decelerating, at target."""
    drive = ApcDrive()
    runtime = load("s7_1_position", drive)
    runtime.start()
    runtime.advance(20)
    assert drive.read("APC_FB_POS") == 0
    drive.params.write((18, 11), 500)                       # 50 revolutions
    words, speeds = [], []
    for _ in range(6000):
        runtime.advance(1)
        words.append(drive.read("APC_COMBINED_PROF_FLAGS"))
        speeds.append(drive.read("APC_PROF_OUT_SPD"))
    assert drive.read("APC_PROF_OUT_POS") == 50 * REV == 3276800
    assert abs(drive.read("APC_FB_POS") - 50 * REV) <= 2          # the drive follows within its loop error
    assert drive.params.read((18, 12)) == 500                       # "#18.12 actual position in 0.1 rev"
    assert max(speeds) == PROFILE_MAX
    assert flag_phases(words) == ["accelerating (profiling)", "constant +speed (profiling)",
                                  "decelerating (profiling)", "at target"]
    accel = sum(1 for w in words if w >> 4 & 1)
    decel = sum(1 for w in words if w >> 5 & 1)
    assert 1998 <= accel <= 2002 and 998 <= decel <= 1002           # ms: 2 s and 1 s ramps to/from 900 rpm


def test_s7_2_rigid_digital_lock_recovers_the_lost_position_then_returns_to_datum():
    """§7.2: #18.32 = 1 engages rigid digital lock to the 700 rpm virtual master: the slave ramps to line speed,
    overspeeds to recover the position lost while accelerating, then locks (L5240-5252); #18.32 = 0 returns the
    axis to the datum #18.11 with the Position reference."""
    drive = ApcDrive()
    runtime = load("s7_2_flying_shear", drive)
    runtime.start()
    runtime.advance(100)
    gap = drive.read("APC_PROF_OUT_POS") - drive.read("APC_RF_POS")    # when digital lock is selected
    drive.params.write((18, 32), 1)
    peak = 0
    for _ in range(6000):
        runtime.advance(1)
        peak = max(peak, drive.read("APC_PROF_OUT_SPD"))
        if drive.read("APC_DIGLCK_MODE") == 1:
            break
    assert drive.read("APC_DIGLCK_MODE") == 1                       # locked
    assert peak > drive.read("APC_RFSRC_SPD")                       # it overspeeds to win the position back
    runtime.advance(500)
    assert drive.read("APC_PROF_OUT_POS") - drive.read("APC_RF_POS") == gap   # no net position lost
    assert drive.read("APC_PROF_OUT_SPD") == drive.read("APC_RFSRC_SPD")
    drive.params.write((18, 32), 0)
    runtime.advance(8000)
    assert drive.read("APC_REF_SELECT") == 1 and drive.read("APC_PROF_OUT_POS") == 0
    assert abs(drive.read("APC_FB_POS")) <= 2


def until_wrap(runtime: DplRuntime, drive: ApcDrive, limit: int = 12_000) -> int:
    """Run to the next CAM wrap ([89], one sample) and return the slave reference there."""
    for _ in range(limit):
        runtime.advance(1)
        if drive.read("APC_CAM_WRAP_THIS_CYCLE"):
            return drive.read("APC_PROF_OUT_POS")
    raise AssertionError("no CAM wrap")


def test_s7_3_runs_its_cam_cycles_forwards_and_back():
    """§7.3: the six-segment CAM; #18.33 = 0 runs elements 0-2 (trapezoid forward with Square1/Linear/Square2),
    #18.33 = 1 elements 3-5 (the slave back with sine ramps); a new start index applies at the wrap (L3500-3522).
    One cycle moves the slave by ΣOut exactly (the virtual master is a few counts into the next segment at the
    wrap, where Square1 and Cosine1 have not moved a count yet)."""
    drive = ApcDrive()
    runtime = load("s7_3_cam", drive)
    cycle = 764587 + 3822935 + 1146880                               # ΣOut of one trapezoid (L5616-5624)
    runtime.start()
    runtime.advance(10)
    drive.params.write((18, 32), 1)
    start = drive.read("APC_PROF_OUT_POS")
    first = until_wrap(runtime, drive)
    drive.params.write((18, 33), 1)                                  # reverse, from the next wrap on
    second = until_wrap(runtime, drive)
    assert drive.read("APC_CAM_STRT_IDX") == 3
    third = until_wrap(runtime, drive)
    assert (first - start, second - first, third - second) == (cycle, cycle, -cycle)
    assert abs(drive.read("APC_FB_POS") - third) < 100               # the drive follows its reference


def test_s7_3_reselected_with_a_new_direction_walks_into_the_same_sample_pitfall():
    """§7.3 sets the start index in the POS0 pass that selects the CAM: stopped (#18.32 = 0), switched to reverse
    (#18.33 = 1) and started again, the CAM first runs the old forward elements 0-2 and reverses only from its
    wrap (L3505-3508 "the new CAM size and start index will not take effect until the CAM reaches the end and
    wraps over")."""
    drive = ApcDrive()
    runtime = load("s7_3_cam", drive)
    runtime.start()
    runtime.advance(10)
    drive.params.write((18, 32), 1)
    until_wrap(runtime, drive)
    drive.params.write((18, 32), 0)
    runtime.advance(3000)                                            # profiled to a stop
    drive.params.write((18, 33), 1)
    drive.params.write((18, 32), 1)
    segments = []
    for _ in range(2 * 12_000):
        runtime.advance(1)
        if not segments or segments[-1] != drive.read("APC_CAM_INDEX"):
            segments.append(drive.read("APC_CAM_INDEX"))
        if len(segments) == 5:
            break
    assert segments == [0, 1, 2, 3, 4] and drive.read("APC_CAM_STRT_IDX") == 3


def test_s7_4_homes_on_the_marker_and_shows_the_43_versus_48_issue():
    """§7.4 homes on the feedback marker: 10 rpm until the marker, then a Position move to the captured position
    and Stop within ±20 counts. It compares the main position [48] with the *source* marker position [43]
    (spec §5): with the encoder not at zero when the APC starts, [43] and [48] differ by that offset and the
    axis stops beside the marker; the same program with [50] (APC_FB_MRKPOS) stops on it."""
    offset_revs = 3.25
    for marker_parameter, lands_on_marker in (("APC_FBSRC_MRKPOS", False), ("APC_FB_MRKPOS", True)):
        drive = ApcDrive(PlantConfig(start_revolutions=offset_revs, marker_angle=0.5))
        text = (PROGRAMS / "s7_4_homing.dpl").read_text(encoding="utf-8")
        runtime = load("s7_4_homing", drive, text.replace("APCReadPar(APC_FBSRC_MRKPOS)",
                                                          f"APCReadPar({marker_parameter})"))
        runtime.start()
        runtime.advance(50)
        drive.params.write((18, 32), 1)                              # a rising edge starts homing
        for _ in range(20_000):
            runtime.advance(1)
            if runtime.read_variable("Homing%") == 5:
                break
        assert runtime.read_variable("Homing%") == 5
        marker_main = drive.read("APC_FB_MRKPOS")                    # where the marker was, in [48] counts
        marker_source = drive.read("APC_FBSRC_MRKPOS")
        assert marker_source - marker_main == round(offset_revs * REV)
        runtime.advance(1000)
        position = drive.read("APC_FB_POS")
        if lands_on_marker:
            assert abs(position - marker_main) <= 20
        else:
            assert abs(position - marker_source) <= 20 and abs(position - marker_main) > REV


def test_s7_5_and_s7_6_ctsync_master_and_slave_follow_the_virtual_master():
    """§7.5/§7.6: the master builds a 700 rpm virtual master, broadcasts it with control bit 0 from #18.32, and
    every node (the master too) follows the data it receives one cycle later in rigid digital lock."""
    master, slave = ApcDrive(), ApcDrive()
    programs = [load("s7_5_ctsync_master", master), load("s7_6_ctsync_slave", slave)]
    line = CTSyncLine([master, slave])
    for runtime in programs:
        runtime.start()

    def advance(samples: int) -> None:
        for _ in range(samples):
            for runtime in programs:
                runtime.slice()
            line.tick()

    advance(50)
    assert master.params.read((81, 6)) == 25 and slave.params.read((81, 6)) == 26
    master.params.write((18, 32), 1)
    advance(6000)
    for drive in (master, slave):
        assert drive.read("APC_DIGLCK_MODE") == 1
        assert drive.read("APC_PROF_OUT_SPD") == drive.read("APC_RFSRC_SPD")
    assert master.read("APC_RF_POS") == slave.read("APC_RF_POS")     # both see the same broadcast
    assert master.read("APC_PROF_OUT_POS") == slave.read("APC_PROF_OUT_POS")
    master.params.write((18, 32), 0)
    advance(3000)
    assert master.read("APC_PROF_OUT_SPD") == slave.read("APC_PROF_OUT_SPD") == 0


def test_s6_4_building_blocks_position_speed_cam_and_digital_lock():
    """§6.4.6-§6.4.9 assembled as §6.5 says: each selects its reference with its #18 switch and moves."""
    drive = ApcDrive()
    position = load("s6_4_position", drive)
    drive.params.write((18, 11), 25)
    drive.params.write((18, 31), 1)
    position.start()
    position.advance(4000)
    assert drive.read("APC_FB_POS") in range(int(2.5 * REV) - 2, int(2.5 * REV) + 3)
    assert drive.params.read((18, 12)) == 25

    drive = ApcDrive()
    speed = load("s6_4_speed", drive)
    drive.params.write((18, 13), 1000)                               # 100.0 rpm
    drive.params.write((18, 32), 1)
    speed.start()
    speed.advance(2000)
    assert drive.read("APC_PROF_OUT_SPD") == 1073741824 * 100 // 60000

    drive = ApcDrive()
    cam = load("s6_4_cam", drive)
    drive.params.write((18, 16), 60)                                 # virtual master 60 rpm: 1 segment per s
    drive.params.write((18, 33), 1)
    cam.start()
    cam.advance(1500)
    assert drive.read("APC_CAM_INDEX") == 1 and drive.params.read((18, 15)) == 1
    peak = max(drive.read("APC_PROF_OUT_POS") for _ in range(1600) if cam.advance(1) is None)
    assert 3 * REV - 10 <= peak <= 3 * REV                           # +1 and +2 turns (cosine: rest at the ends)
    assert abs(until_wrap(cam, drive)) <= 1                          # -3 turns: back at the start each cycle

    drive = ApcDrive()
    lock = load("s6_4_diglock", drive)
    drive.params.write((18, 16), 100)
    drive.params.write((18, 35), 1)
    lock.start()
    lock.advance(3000)
    assert drive.read("APC_DIGLCK_MODE") == 1
    assert drive.read("APC_PROF_OUT_SPD") == drive.read("APC_RFSRC_SPD")
