"""Real-time factor of the simulated APC (Unidrive SP + SM-Applications).

* `apc_rtf_axis_1ms`: one axis at a 1 ms POS period indexing back and forth with the Position reference (profile
  generator, position loop, output channel, plant), a POS0 task choosing the next set point. Goal ≥ 100×.
* `apc_rtf_ctsync8_cam`: eight drives on a CTSync line at 1 ms; the master builds a 700 rpm virtual master with
  MULDIVRM (§8.4) and broadcasts it; every node reads it in POS0 into its user-program reference source and runs
  the §4.7.2 CAM (Square1 / Linear / Square2). Goal ≥ 20×.

Prints `name: value unit` lines, the best of three runs, and the machine's load average. The machine is shared,
so each factor is given twice: from the process's CPU time (what an idle machine would show) and from the wall
clock (what the load left us).
"""

import os
import time

from motiontool.apc import ApcDrive, CTSyncLine
from motiontool.apc.intmath import MULDIVRM, UnsignedBottomWord, UnsignedTopWord

SIMULATED_MS = 10_000
IN, OUT1, CODES = [109227, 218454, 54613], [109227, 436908, 54613], [2, 0, 3]


def timed(run) -> tuple[float, float]:
    """Real-time factors (CPU time, wall clock) of `run`, which simulates SIMULATED_MS."""
    cpu, wall = time.process_time(), time.perf_counter()
    run()
    cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    return SIMULATED_MS / (cpu * 1000), SIMULATED_MS / (wall * 1000)


def enable(d: ApcDrive) -> None:
    d.APCSetupOutputChannel(2, 0, 0)
    d.APCEnableOutputChannel()
    d.APCSetRunMode(2)


def axis_rtf() -> tuple[float, float]:
    d = ApcDrive()
    enable(d)
    targets = [0, 5 * 65536]

    def pos0():
        if d.pg.at_target():
            targets.reverse()
            d.APCSetPositionSetPoint(targets[0])
    d.pos0 = pos0
    d.APCSelectReference(1)
    d.run_ms(500)
    elapsed = timed(lambda: d.run_ms(SIMULATED_MS))
    assert not d.trip and abs(d.read(130)) < 2000
    return elapsed


def ctsync_cam_rtf() -> tuple[float, float]:
    drives = [ApcDrive() for _ in range(8)]
    master = drives[0]
    master.params["81.06"] = 25
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
        enable(d)
    line = CTSyncLine(drives)
    line.run_ms(10)
    for d in drives:
        d.APCSelectReference(3)
    line.run_ms(500)
    elapsed = timed(lambda: line.run_ms(SIMULATED_MS))
    assert all(d.read(100) == 3 and not d.trip for d in drives)
    assert len({d.read(117) - drives[0].read(117) for d in drives}) == 1   # every node on the same CAM point
    return elapsed


def main() -> None:
    axis = [axis_rtf() for _ in range(3)]
    cpu, wall = max(a[0] for a in axis), max(a[1] for a in axis)
    print(f"apc_rtf_axis_1ms: {cpu:.0f} x")
    print(f"apc_rtf_axis_1ms_wall: {wall:.0f} x")
    print(f"apc_tick_axis_1ms: {1000 / cpu:.1f} us")
    line = [ctsync_cam_rtf() for _ in range(3)]
    cpu, wall = max(a[0] for a in line), max(a[1] for a in line)
    print(f"apc_rtf_ctsync8_cam: {cpu:.1f} x")
    print(f"apc_rtf_ctsync8_cam_wall: {wall:.1f} x")
    print(f"apc_tick_ctsync8_cam_per_drive: {1000 / cpu / 8:.1f} us")
    print(f"load_average_1min: {os.getloadavg()[0]:.2f} (2 cores, shared)")


if __name__ == "__main__":
    main()
