"""Real-time factor of the simulated controller.

* one axis running a program that moves continuously: `kernel_rtf_<ramp>: <factor> x` (virtual ms per wall ms)
  and the cost of one tick. Goal ≥ 100×.
* a multi-axis project (DG 254: the virtual master "serves as a common master signal for synchronization of up-to
  32 axes"): 8 controllers on one EmbeddedBus (kernel/simulation.py), node 1's PULSVEL is the virtual master of all
  of them and each axis runs the stamping CAM curve of DG 1435-1494 (fix points, MCO ≥ 5.00) with SYNCC 0 /
  SYNCCSTART 0, its program then waiting (WAITI on an input that never comes), like benchmarks/cam_rtf.py.
  `kernel_rtf_cam8: <factor> x` is virtual ms per wall ms for all 8 axes together, `kernel_tick_cam8` the cost of
  one tick of all 8. Goal ≥ 20×.

Each factor is printed twice: from the wall clock (`kernel_rtf_…`, what the load left us) and from the process's CPU
time (`kernel_rtf_…_cpu`, close to what an idle machine shows), then the load average: the machine may be shared.
"""

import os
import time

from cam_rtf import start_cam_axis
from motiontool.aposs.driver import compile_source
from motiontool.camcurve import Curve, FixPoint, encode
from motiontool.comms.bus import EmbeddedBus
from motiontool.comms.embedded import EmbeddedLink

PROGRAM = """
VEL 100
ACC 100
DEC 100
main:
POSA 204800
POSA 0
GOTO main
"""
SIMULATED_MS = 20_000

CAM_AXES = 8
CAM_MS = 2_000
CAM_POINTS = (FixPoint(0, 0), FixPoint(1500, 1200, "T"), FixPoint(2500, 2400, "T"), FixPoint(4000, 3600))
CAM_SETTINGS = {"SYNCFACTM": 2048, "SYNCFACTS": 55, "POSFACT_Z": 25, "POSFACT_N": 9, "ENCODER": 500,
                "FFVEL": 1000, "DFLTVEL": 100, "DFLTACC": 100}
# 60 boxes/min: 4000 MU/s = 4000 · 2048/55 qc/s = 37236 Hz of 4-qc pulses (one pulse = 4 qc, CR 3574-3611)
VIRTUAL_MASTER = "PULSACC 100000\nPULSVEL 37236\n"


def timed(run, simulated_ms: int) -> tuple[float, float]:
    """Real-time factors (wall clock, CPU time) of `run`, which simulates `simulated_ms`."""
    cpu, wall = time.process_time(), time.perf_counter()
    run()
    cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    return simulated_ms / (wall * 1000.0), simulated_ms / (cpu * 1000.0)


def measure(ramp_type: int) -> tuple[float, float]:
    result = compile_source(PROGRAM, "rtf.m")
    assert result.ok
    link = EmbeddedLink()
    link.write_parameter("RAMPTYPE", ramp_type)
    link.download(result.image.to_bytes())
    link.start()
    factors = timed(lambda: link.advance(SIMULATED_MS), SIMULATED_MS)
    assert link.status().program_state == "running"
    return factors


def cam_program(size: int, master: bool) -> str:
    return (f"DIM stamping[{size}]\nSETCURVE stamping\nDEFMCPOS 1000\nPOSA CURVEPOS\n"
            f"{VIRTUAL_MASTER if master else ''}SYNCC 0\nSYNCCSTART 0\nWAITI 8 ON\n")


def measure_cam_axes(axes: int = CAM_AXES) -> tuple[float, float]:
    values = encode(Curve("stamping", 4000, CAM_POINTS, interpolation=False, intervals=40))
    bus = EmbeddedBus(range(1, axes + 1), master_node=1)
    for node in bus.nodes:
        start_cam_axis(bus.link(node), values, cam_program(len(values), node == 1), CAM_SETTINGS)
    bus.advance(2000)  # engaged and up to speed
    controllers = [bus.simulation[n] for n in bus.nodes]
    assert all(c.axis.mode == "cam" for c in controllers), [c.axis.mode for c in controllers]
    factors = timed(lambda: bus.link(1).advance(CAM_MS), CAM_MS)
    mapos = controllers[0].master.mapos
    assert mapos > 0 and all(c.master.mapos == mapos for c in controllers)
    assert all(c.program_state == "running" and c.axis.mode == "cam" and not c.error for c in controllers)
    return factors


def main() -> None:
    for ramp_type, name in ((0, "trapezoid"), (2, "limited_jerk")):
        runs = [measure(ramp_type) for _ in range(3)]
        wall, cpu = max(r[0] for r in runs), max(r[1] for r in runs)
        print(f"kernel_rtf_{name}: {wall:.0f} x")
        print(f"kernel_rtf_{name}_cpu: {cpu:.0f} x")
        print(f"kernel_tick_{name}: {1000.0 / cpu:.1f} us")
    runs = [measure_cam_axes() for _ in range(5)]  # best of 5 short runs: the machine may be shared
    wall, cpu = max(r[0] for r in runs), max(r[1] for r in runs)
    print(f"kernel_rtf_cam{CAM_AXES}: {wall:.1f} x")
    print(f"kernel_rtf_cam{CAM_AXES}_cpu: {cpu:.1f} x")
    print(f"kernel_tick_cam{CAM_AXES}: {1000.0 / cpu:.1f} us")
    print(f"load_average_1min: {os.getloadavg()[0]:.2f} (2 cores, shared)")


if __name__ == "__main__":
    main()
