"""Real-time factor of the APC manual's DPL programs on the simulated APC (the DPL runtime plus the kernel).

* `dpl_rtf_s7_1_position`: §7.1 moving 50 revolutions (POS0 interlock and set point, the background loop).
* `dpl_rtf_s7_3_cam`: §7.3 running its CAM (POS0 virtual master, CAM reference).
* `dpl_rtf_s7_5_s7_6_ctsync`: §7.5 master and §7.6 slave on one CTSync line, both in rigid digital lock.

Prints `name: value unit` lines, the best of three runs of 10 s of virtual time, from the process's CPU time and
from the wall clock, and the machine's load average (the machine is shared).
"""

import os
import time
from pathlib import Path

from motiontool.apc import ApcDrive, CTSyncLine
from motiontool.dpl.driver import check_source
from motiontool.dpl.runtime import DplRuntime

PROGRAMS = Path(__file__).resolve().parents[1] / "tests" / "dpl" / "programs"
SIMULATED_MS = 10_000


def runtime(name: str, drive: ApcDrive) -> DplRuntime:
    r = DplRuntime(drive, check_source(path=PROGRAMS / f"{name}.dpl"))
    r.start()
    return r


def position() -> None:
    drive = ApcDrive()
    r = runtime("s7_1_position", drive)
    drive.params.write((18, 11), 500)
    r.advance(SIMULATED_MS)


def cam() -> None:
    drive = ApcDrive()
    r = runtime("s7_3_cam", drive)
    drive.params.write((18, 32), 1)
    r.advance(SIMULATED_MS)


def ctsync() -> None:
    master, slave = ApcDrive(), ApcDrive()
    programs = [runtime("s7_5_ctsync_master", master), runtime("s7_6_ctsync_slave", slave)]
    line = CTSyncLine([master, slave])
    master.params.write((18, 32), 1)
    for _ in range(SIMULATED_MS):
        for r in programs:
            r.slice()
        line.tick()


def best(run) -> tuple[float, float]:
    factors = []
    for _ in range(3):
        cpu, wall = time.process_time(), time.perf_counter()
        run()
        cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
        factors.append((SIMULATED_MS / (cpu * 1000), SIMULATED_MS / (wall * 1000)))
    return max(f[0] for f in factors), max(f[1] for f in factors)


if __name__ == "__main__":
    for name, run in (("s7_1_position", position), ("s7_3_cam", cam), ("s7_5_s7_6_ctsync", ctsync)):
        cpu, wall = best(run)
        print(f"dpl_rtf_{name}_cpu: {cpu:.1f} x")
        print(f"dpl_rtf_{name}_wall: {wall:.1f} x")
    print(f"load_average_1min: {os.getloadavg()[0]:.2f}")
