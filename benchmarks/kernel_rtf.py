"""Real-time factor of the simulated controller: one axis running a program that moves continuously.

Prints `kernel_rtf: <factor> x` (virtual ms per wall ms) and the cost of one tick. Goal ≥ 100×.
"""

import time

from motiontool.aposs.driver import compile_source
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


def measure(ramp_type: int) -> float:
    result = compile_source(PROGRAM, "rtf.m")
    assert result.ok
    link = EmbeddedLink()
    link.write_parameter("RAMPTYPE", ramp_type)
    link.download(result.image.to_bytes())
    link.start()
    start = time.perf_counter()
    link.advance(SIMULATED_MS)
    elapsed = time.perf_counter() - start
    assert link.status().program_state == "running"
    return SIMULATED_MS / (elapsed * 1000.0)


def main() -> None:
    for ramp_type, name in ((0, "trapezoid"), (2, "limited_jerk")):
        best = max(measure(ramp_type) for _ in range(3))
        print(f"kernel_rtf_{name}: {best:.0f} x")
        print(f"kernel_tick_{name}: {1000.0 / best:.1f} us")


if __name__ == "__main__":
    main()
