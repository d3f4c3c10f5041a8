"""Real-time factor of the simulated controller.

* one axis running a program that moves continuously: `kernel_rtf_<ramp>: <factor> x` (virtual ms per wall ms)
  and the cost of one tick. Goal ≥ 100×.
* a multi-axis project (DG 254: the virtual master "serves as a common master signal for synchronization of up-to
  32 axes"): 8 controllers on one EmbeddedBus (kernel/simulation.py), node 1's PULSVEL is the virtual master of all
  of them and each axis runs the stamping CAM curve of DG 1435-1494 (fix points, MCO ≥ 5.00) with SYNCC 0 /
  SYNCCSTART 0, its program then waiting (WAITI on an input that never comes), like benchmarks/cam_rtf.py.
  `kernel_rtf_cam8: <factor> x` is virtual ms per wall ms for all 8 axes together, `kernel_tick_cam8` the cost of
  one tick of all 8. The bus advances 2000 ms at once, so the steady line runs in stretches of ticks
  (kernel/steady_line.py, decisions K129).
* the same line with 32 controllers, all the virtual master serves (issue 30): `kernel_rtf_cam32: <factor> x`. Goals
  on an idle two-core machine (issue 30): 32 CAM axes ≥ 20×, 8 CAM axes ≥ 80×, one axis ≥ 500×.
* beside each CAM figure the bare loop of the same shape (`bare_rtf_cam<N>`): a plain pure-Python 1 ms loop that
  does per axis what a CAM axis must do at the least (the master increment, the curve master position, the curve
  piece by Horner's rule, the target, the position law, the motor's lag, the encoder count, the tracking error
  check) and nothing else: what the language allows, the kernel's ceiling.

Each factor is printed twice: from the wall clock (`kernel_rtf_…`, what the load left us) and from the process's CPU
time (`kernel_rtf_…_cpu`, close to what an idle machine shows), then the load average: the machine may be shared.
"""

import bisect
import math
import os
import sys
import time

from cam_rtf import start_cam_axis
from motiontool.aposs.driver import compile_source
from motiontool.camcurve import Curve, FixPoint, encode
from motiontool.controller.bus import EmbeddedBus
from motiontool.controller.embedded import EmbeddedLink

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
CAM32_AXES = 32  # DG 254: "synchronization of up-to 32 axes"
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


class BareAxis:
    """One axis of the bare loop: the state the least CAM axis has to carry from tick to tick."""

    def __init__(self, pieces: list[tuple], length: float, slave_length: float):
        self.pieces, self.length, self.slave_length = pieces, length, slave_length
        self.piece = pieces[0]
        self.cpos = self.velocity = self.position = self.motor_velocity = 0.0
        self.apos = 0


def bare_fleet(axes: int) -> tuple[list[BareAxis], list[float]]:
    """The bare loop's axes on the stamping curve's spline pieces (lo, hi, start, coefficients) and its breaks."""
    from motiontool.camcurve.spline import profile
    pp = profile(Curve("stamping", 4000, CAM_POINTS, interpolation=False, intervals=40)).ppoly
    breaks = [float(b) for b in pp.x]
    pieces = [(breaks[j], breaks[j + 1], breaks[j], *(float(c) for c in pp.c[:, j])) for j in range(len(breaks) - 1)]
    return [BareAxis(pieces, 4000.0, 3600.0) for _ in range(axes)], breaks


def bare_loop(fleet: list[BareAxis], breaks: list[float], ms: int) -> None:
    """`ms` ticks of the fleet's CAM axes on one virtual master as plainly as Python allows (module docstring)."""
    mu_per_qc, k, alpha, master = 55 / 2048, 25 / 9, 1.0 - math.exp(-1.0 / 5.0), 0.0
    for _ in range(ms):
        master += 37.236
        raw = math.floor(master)
        for a in fleet:
            m = 1000.0 + raw * mu_per_qc
            cycle = math.floor(m / a.length)
            x = m - cycle * a.length
            lo, hi, start, c0, c1, c2, c3, c4, c5 = a.piece
            if not lo <= x < hi:
                lo, hi, start, c0, c1, c2, c3, c4, c5 = a.piece = a.pieces[bisect.bisect_right(breaks, x) - 1]
            dx = x - start
            t = (((((c0 * dx + c1) * dx + c2) * dx + c3) * dx + c4) * dx + c5 + cycle * a.slave_length) * k
            a.velocity, a.cpos = t - a.cpos, t
            reference = 0.03 * (t - a.apos) + a.velocity
            a.motor_velocity = v = a.motor_velocity + (reference - a.motor_velocity) * alpha
            a.position += v
            a.apos = math.floor(a.position)
            if abs(a.cpos - a.apos) > 20000:
                raise AssertionError("tracking error")


def bare_factors(axes: int) -> tuple[float, float]:
    runs = []
    for _ in range(3):
        fleet, breaks = bare_fleet(axes)
        runs.append(timed(lambda: bare_loop(fleet, breaks, CAM_MS), CAM_MS))  # noqa: B023 - called at once
    return max(r[0] for r in runs), max(r[1] for r in runs)


def report_cam(axes: int, repeats: int) -> None:
    runs = [measure_cam_axes(axes) for _ in range(repeats)]  # best of short runs: the machine may be shared
    wall, cpu = max(r[0] for r in runs), max(r[1] for r in runs)
    bare_wall, bare_cpu = bare_factors(axes)
    print(f"kernel_rtf_cam{axes}: {wall:.1f} x")
    print(f"kernel_rtf_cam{axes}_cpu: {cpu:.1f} x")
    print(f"kernel_tick_cam{axes}: {1000.0 / cpu:.1f} us")
    print(f"bare_rtf_cam{axes}: {bare_wall:.1f} x")
    print(f"bare_rtf_cam{axes}_cpu: {bare_cpu:.1f} x")


def main() -> None:
    if sys.argv[1:] == ["cam32"]:  # the 32-axis line alone (profiling: python -m cProfile kernel_rtf.py cam32)
        report_cam(CAM32_AXES, 1)
        return
    for ramp_type, name in ((0, "trapezoid"), (2, "limited_jerk")):
        runs = [measure(ramp_type) for _ in range(3)]
        wall, cpu = max(r[0] for r in runs), max(r[1] for r in runs)
        print(f"kernel_rtf_{name}: {wall:.0f} x")
        print(f"kernel_rtf_{name}_cpu: {cpu:.0f} x")
        print(f"kernel_tick_{name}: {1000.0 / cpu:.1f} us")
    report_cam(1, 5)
    report_cam(CAM_AXES, 5)
    report_cam(CAM32_AXES, 3)
    print(f"load_average_1min: {os.getloadavg()[0]:.2f} (2 cores, shared)")


if __name__ == "__main__":
    main()
