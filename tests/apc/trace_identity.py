"""Runs for test_trace_identity.py: the simulated APC fingerprinted every ms (issue 30 item 1, APC part).

A run's fingerprint is one sha256 per simulated second of its rows; a row holds, for every drive of the run, the
time, every read parameter [0]-[189] (as APCReadPar reads it), the plant's position, speed and encoder word, the
generators' fractional state, the CAM and digital lock internals, the output pipeline, the CTSync data, the drive
parameters and, with a DPL program, its variables. Floats by repr, so a change in the last bit shows. Errors and
trips the drives report, with their sample, go into one more sha256.
`python -m tests.apc.trace_identity` writes the golden file from the APC as it is.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable, Iterator
from pathlib import Path

from motiontool.apc import ApcDrive, CTSyncLine, PlantConfig
from motiontool.apc.intmath import MULDIVRM, UnsignedBottomWord, UnsignedTopWord
from motiontool.dpl.driver import check_source
from motiontool.dpl.runtime import DplRuntime
from tests.apc.helpers import VirtualMaster, enabled_drive
from tests.dpl.manual import PROGRAMS
from tests.trace_hash import SecondHashes, text_hash

GOLDEN = Path(__file__).parent / "golden" / "trace_identity.json"

# benchmarks/apc_rtf.py's CAM: Table 4-10's three segments (Square1 / Linear / Square2, §4.7.2)
IN, OUT1, CODES = [109227, 218454, 54613], [109227, 436908, 54613], [2, 0, 3]


def row(d: ApcDrive, memory=None) -> tuple:
    pg, opg, cam, dl, plant = d.pg, d.opg, d.cam, d.dl, d.plant
    readers = d._readers
    return (d.time_ns, tuple(readers[n]() for n in sorted(readers)),
            plant.position, plant.speed, plant.word, d.ref.word, d.fb.word,
            pg.offset, pg.speed, pg.acceleration, pg.prev_speed, pg.mode, pg._cruise,
            opg.offset, opg.speed, opg.mode, cam._done_here, cam.active_start, cam.active_size, cam.ratio.remainder,
            dl.target, dl.ratio.remainder, d._active, d._demand3, d._demand2, d._demand1, d.channel.sent, d._held,
            d.trip, d.error_id, d.ctsync_received, tuple(d.ctsync_counts), d.ctsync_out,
            sorted(d.params.values.items()), sorted(memory.variables.items()) if memory is not None else None)


class Fingerprint:
    def __init__(self, drives: list[ApcDrive]) -> None:
        self.events: list[str] = []
        self._rows = SecondHashes()
        for i, d in enumerate(drives):
            d.listeners.append(lambda kind, details, i=i, d=d: self.events.append(
                f"{i} {d.time_ns} {kind} {sorted(details.items())}"))

    def add(self, rows: list[tuple]) -> None:
        self._rows.add(rows)

    def result(self) -> dict:
        return {**self._rows.finish(), "events": text_hash(self.events), "event_count": len(self.events)}


# --- benchmarks/apc_rtf.py ------------------------------------------------------------------------------------------
def ctsync_cam_line(nodes: int = 8) -> CTSyncLine:
    """The benchmark's line: node 0 builds a 700 rpm virtual master with MULDIVRM (§8.4) and broadcasts it; every node
    follows the received reference with the §4.7.2 CAM, selected after 10 ms."""
    drives = [ApcDrive() for _ in range(nodes)]
    drives[0].params["81.06"] = 25
    state = {"counter": 0, "rem": 0}

    def node(d: ApcDrive, is_master: bool):
        def pos0():
            ref1, _, _, _ = d.CTSyncGetSlaveReferences()
            d.APCSetReferencePosition(UnsignedTopWord(ref1), UnsignedBottomWord(ref1), 0)
            if is_master:
                step, rem = MULDIVRM(700, 65536, 60000)
                state["rem"] += rem
                if state["rem"] >= 60000:
                    state["rem"] -= 60000
                    step += 1
                state["counter"] += step
                d.CTSyncSetMasterReferences(state["counter"], 0, 1)
        return pos0

    for i, d in enumerate(drives):
        if i:
            d.params["81.06"] = 26
        d.APCSetReferenceSource(4)
        d.APCCamInitialise2(IN, OUT1, CODES)
        d.APCSetCAMInterpolationMode(-1)
        d.APCSetCAMSize(3)
        d.pos0 = node(d, i == 0)
        d.APCSetupOutputChannel(2, 0, 0)
        d.APCEnableOutputChannel()
        d.APCSetRunMode(2)
    return CTSyncLine(drives)


def trace(tick: Callable[[], object], drives: list[ApcDrive], ms: int,
          at: dict[int, Callable[[], object]] | None = None, memories: list | None = None) -> dict:
    """`ms` ticks, fingerprinting every drive after each; at[k] runs before tick k (0-based)."""
    fp, at = Fingerprint(drives), at or {}
    pairs = list(zip(drives, memories or [None] * len(drives), strict=True))
    for k in range(ms):
        if k in at:
            at[k]()
        tick()
        fp.add([row(d, m) for d, m in pairs])
    return fp.result()


def run_ctsync_cam(nodes: int, ms: int, faults: dict[int, str] | None = None) -> dict:
    line = ctsync_cam_line(nodes)
    for sample, fault in (faults or {}).items():
        line.inject(sample, fault)

    def select():
        for d in line.drives:
            d.APCSelectReference(3)
    return trace(line.tick, line.drives, ms, {10: select})


def run_axis(ms: int) -> dict:
    """The benchmark's single axis: Position reference indexing 0 ↔ 5 revolutions, POS0 choosing the set point."""
    d = ApcDrive()
    d.APCSetupOutputChannel(2, 0, 0)
    d.APCEnableOutputChannel()
    d.APCSetRunMode(2)
    targets = [0, 5 * 65536]

    def pos0():
        if d.pg.at_target():
            targets.reverse()
            d.APCSetPositionSetPoint(targets[0])
    d.pos0 = pos0
    d.APCSelectReference(1)
    return trace(d.tick, [d], ms)


# --- the manual's DPL programs (tests/dpl/test_manual_programs.py's settings) --------------------------------------
def _runtime(name: str, drive: ApcDrive) -> DplRuntime:
    checked = check_source(path=PROGRAMS / f"{name}.dpl")
    assert checked.ok
    runtime = DplRuntime(drive, checked)
    runtime.start()
    return runtime


def run_dpl(name: str, ms: int, writes: dict[int, dict[tuple[int, int], int]],
            plant: PlantConfig | None = None) -> dict:
    drive = ApcDrive(plant)
    runtime = _runtime(name, drive)
    at = {k: lambda w=w: [drive.params.write(key, value) for key, value in w.items()] for k, w in writes.items()}
    return trace(lambda: runtime.advance(1), [drive], ms, at, [runtime.memory])


def run_dpl_ctsync(ms: int) -> dict:
    """§7.5 master and §7.6 slave on one line, rigid digital lock on the broadcast virtual master."""
    master, slave = ApcDrive(), ApcDrive()
    programs = [_runtime("s7_5_ctsync_master", master), _runtime("s7_6_ctsync_slave", slave)]
    line = CTSyncLine([master, slave])

    def tick():
        for r in programs:
            r.slice()
        line.tick()
    at = {50: lambda: master.params.write((18, 32), 1), 4000: lambda: master.params.write((18, 32), 0)}
    return trace(tick, [master, slave], ms, at, [r.memory for r in programs])


# --- freeze, profile and offsets on one drive (tests/apc/test_freeze.py, test_profile.py) ---------------------------
def run_freeze_cam(single_shot: bool) -> dict:
    """A CAM selected by a reference freeze between samples; single shot with re-arm cuts once per mark."""
    d = enabled_drive()
    VirtualMaster(d, 1000)
    d.APCEnableReferenceFreeze()
    d.APCResetRefSourceFreezeFlag()
    d.APCCamInitialise2([20_000, 15_000], [5_000, -2_000], [1, 4])
    d.APCSetCAMInterpolationMode(-1)
    d.APCSetCAMSize(2)
    if single_shot:
        d.APCEnableCAMSingleShot()
        d.APCEnableCAMFreezeRearm()
    d.APCSelectActionOnFreeze(2)
    t0 = d.time_ns / 1000
    for m in range(6):
        d.schedule("reference", "freeze", t0 + 45_000 * m + 100 + 37 * m)
    return trace(d.tick, [d], 300)


def run_freeze_diglock(rigid: bool) -> dict:
    d = enabled_drive()
    vm = VirtualMaster(d, 800)
    d.APCEnableReferenceFreeze()
    d.APCResetRefSourceFreezeFlag()
    if rigid:
        d.APCEnableRigidLock()
    d.APCSetDigLockRatioNumerator(3)
    d.APCSetDigLockRatioDenominator(7)
    d.APCSelectActionOnFreeze(1)
    d.schedule("reference", "freeze", d.time_ns / 1000 + 5250)

    def faster():
        vm.per_sample = 1900
    return trace(d.tick, [d], 1500, {700: faster})


def run_cam_overrun() -> dict:
    """A CAM whose master speeds up past the delta-segment limit: 90.49 = 2 and Stop (L3524-3546)."""
    d = enabled_drive()
    vm = VirtualMaster(d, 3000)
    d.APCCamInitialise1([20_000, 20_000], [8_000, 8_000])
    d.APCSetCAMSize(2)
    d.APCSetCAMDeltaSegLimit(1)
    d.APCSelectReference(3)

    def faster():
        vm.per_sample = 25_000
    return trace(d.tick, [d], 600, {200: faster})


def run_profiles() -> dict:
    """Position moves with jerk retargeted mid-move, a speed move, the offset generator, a linear stop."""
    d = enabled_drive()
    d.APCSetProfileJerk(40)
    d.APCSetPositionSetPoint(40 * 65536)
    d.APCSelectReference(1)
    steps = {
        300: lambda: d.APCSetPositionSetPoint(-20 * 65536),
        900: lambda: (d.APCSetSpeedSetPoint(17895 * 200), d.APCSelectReference(2)),
        1300: lambda: (d.APCSetSpeedOffset(17895 * 30), d.APCSelectOffset(2)),
        1700: lambda: (d.APCSetPositionOffset(3 * 65536), d.APCSelectOffset(1)),
        2100: lambda: (d.APCSetStopMode(2), d.APCSelectReference(0)),
        2600: lambda: (d.APCDisableProfile(), d.APCSetPositionSetPoint(65536), d.APCSelectReference(1)),
        2800: lambda: (d.APCSetStopMode(1), d.APCSelectReference(0)),
    }
    return trace(d.tick, [d], 3000, steps)


def runs() -> Iterator[tuple[str, Callable[[], dict]]]:
    yield "benchmark ctsync 8 drives cam", lambda: run_ctsync_cam(8, 3000)
    yield "benchmark axis 1 ms", lambda: run_axis(3000)
    yield "ctsync 3 drives cam, faulty line", lambda: run_ctsync_cam(
        3, 1500, {400: "short", 401: "checksum", 700: "missing", 1100: "long"})
    yield "dpl s7_1_position", lambda: run_dpl("s7_1_position", 4000, {20: {(18, 11): 500}})
    yield "dpl s7_2_flying_shear", lambda: run_dpl("s7_2_flying_shear", 6000,
                                                   {100: {(18, 32): 1}, 3500: {(18, 32): 0}})
    yield "dpl s7_3_cam", lambda: run_dpl("s7_3_cam", 9000, {10: {(18, 32): 1}, 3000: {(18, 33): 1},
                                                               6500: {(18, 32): 0}})
    yield "dpl s7_4_homing", lambda: run_dpl("s7_4_homing", 4000, {50: {(18, 32): 1}},
                                             PlantConfig(start_revolutions=3.25, marker_angle=0.5))
    yield "dpl s7_5_s7_6_ctsync", lambda: run_dpl_ctsync(6000)
    yield "dpl s6_4_position", lambda: run_dpl("s6_4_position", 3000, {0: {(18, 11): 25, (18, 31): 1}})
    yield "dpl s6_4_speed", lambda: run_dpl("s6_4_speed", 2000, {0: {(18, 13): 1000, (18, 32): 1}})
    yield "dpl s6_4_cam", lambda: run_dpl("s6_4_cam", 4000, {0: {(18, 16): 60, (18, 33): 1}})
    yield "dpl s6_4_diglock", lambda: run_dpl("s6_4_diglock", 3000, {0: {(18, 16): 100, (18, 35): 1}})
    yield "freeze cam cyclic", lambda: run_freeze_cam(False)
    yield "freeze cam single shot re-arm", lambda: run_freeze_cam(True)
    yield "freeze digital lock", lambda: run_freeze_diglock(False)
    yield "freeze digital lock rigid", lambda: run_freeze_diglock(True)
    yield "cam delta-segment limit", run_cam_overrun
    yield "profiles and offsets", run_profiles


def main() -> None:
    golden = {name: run() for name, run in runs()}
    GOLDEN.parent.mkdir(exist_ok=True)
    GOLDEN.write_text(json.dumps(golden, indent=0, sort_keys=True) + "\n", encoding="utf-8")
    print(f"wrote {GOLDEN} ({len(golden)} runs)", file=sys.stderr)


if __name__ == "__main__":
    main()
