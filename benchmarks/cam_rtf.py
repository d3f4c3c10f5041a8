"""Real-time factor of the simulated controller while one axis runs a CAM curve (SYNCC) on the virtual master.

The stamping curve of DG 1435-1494 (4000 MU master cycle, tangent section at 1.2 UU/MU) is encoded with
camcurve.layout.encode and restored into the controller like a .zbc download; the program engages with SYNCC 0 /
SYNCCSTART 0 and then waits (WAITI on an input that never comes), so the measurement is the motion loop, not the
VM. Both array kinds are measured: with interpolation points (linear between them, firmware < 5.00) and fix
points only (spline, MCO ≥ 5.00). Prints `cam_rtf_<kind>: <factor> x` and the tick cost. Goal ≥ 100×.
"""

import time

from motiontool.aposs.driver import compile_source
from motiontool.camcurve import Curve, FixPoint, encode
from motiontool.controller.embedded import EmbeddedLink

POINTS = (FixPoint(0, 0), FixPoint(1500, 1200, "T"), FixPoint(2500, 2400, "T"), FixPoint(4000, 3600))
SETTINGS = {"SYNCFACTM": 2048, "SYNCFACTS": 55, "POSFACT_Z": 25, "POSFACT_N": 9, "ENCODER": 500, "FFVEL": 1000,
            "DFLTVEL": 100, "DFLTACC": 100}
SIMULATED_MS = 20_000


def program(size: int) -> str:
    # 60 boxes/min: 4000 MU/s = 4000 · 2048/55 qc/s = 37236 Hz of 4-qc pulses (one pulse = 4 qc, CR 3574-3611)
    return (f"DIM stamping[{size}]\nSETCURVE stamping\nDEFMCPOS 1000\nPOSA CURVEPOS\nPULSACC 100000\n"
            f"PULSVEL 37236\nSYNCC 0\nSYNCCSTART 0\nWAITI 8 ON\n")


def start_cam_axis(link, values: list[int], source: str, settings: dict) -> None:
    """Load the curve array `stamping`, the settings and the program into one controller and start it
    (kernel_rtf.py uses it for each of its 8 axes)."""
    result = compile_source(source, "cam_rtf.m")
    assert result.ok, [d.format() for d in result.diagnostics]
    link.call("restore_arrays", arrays=[{"name": "stamping", "values": values}])
    for key, value in settings.items():
        link.write_parameter(key, value)
    link.download(result.image.to_bytes())
    link.start()


def measure(interpolation: bool) -> float:
    values = encode(Curve("stamping", 4000, POINTS, interpolation=interpolation, intervals=40))
    link = EmbeddedLink()
    start_cam_axis(link, values, program(len(values)), SETTINGS)
    link.advance(2000)  # engaged and up to speed
    controller = link.service.controller
    assert controller.axis.mode == "cam", controller.axis.mode
    start = time.perf_counter()
    link.advance(SIMULATED_MS)
    elapsed = time.perf_counter() - start
    assert link.status().program_state == "running" and controller.axis.mode == "cam"
    assert not controller.error
    return SIMULATED_MS / (elapsed * 1000.0)


def main() -> None:
    for interpolation, name in ((True, "interpolated"), (False, "fixpoints")):
        best = max(measure(interpolation) for _ in range(3))
        print(f"cam_rtf_{name}: {best:.0f} x")
        print(f"cam_tick_{name}: {1000.0 / best:.1f} us")


if __name__ == "__main__":
    main()
