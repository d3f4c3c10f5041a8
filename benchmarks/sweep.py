"""Runs per second of `motiontool sweep` (issue 30 item 2): a 4 x 4 grid of 32-60 KPROP x 32-61 KDER, each point a
fresh simulated MCO 305 moving 50 revolutions (POSA 204800) for 5 s of virtual time, measured by
max(abs(TRACKERR)) and settle_time(APOS, 204800, 10), on 1 and on 2 local processes (the pool's start-up
included, as a user waits for it).

Prints `sweep_runs_per_s_jobs1: X runs/s` and `sweep_runs_per_s_jobs2: X runs/s` (wall clock, the best of three),
their ratio, and the machine's load average (the machine is shared: a busy second core halves jobs2).
"""

import os
import sys
import tempfile
import time
from pathlib import Path

from motiontool.sweep.points import grid, parse_vary
from motiontool.sweep.runner import run_points
from motiontool.sweep.setup import prepare

PROGRAM = "POSA 204800\n"
MEASURES = ["max(abs(TRACKERR))", "settle_time(APOS, 204800, 10)"]


def rate(job, points, jobs: int) -> float:
    best = 0.0
    for _ in range(3):
        done: dict = {}
        started = time.perf_counter()
        run_points(job, points, done, lambda k, row: None, jobs=jobs)
        best = max(best, len(done) / (time.perf_counter() - started))
    return best


if __name__ == "__main__":
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "move.m"
        path.write_text(PROGRAM, encoding="utf-8")
        points = grid([parse_vary("32-60=20:80:20"), parse_vary("32-61=0:300:100", 2)])
        job = prepare(path, ["32-60", "32-61"], MEASURES, [], 5.0, [], sys.stderr)
    one, two = rate(job, points, 1), rate(job, points, 2)
    print(f"sweep_runs_per_s_jobs1: {one:.1f} runs/s")
    print(f"sweep_runs_per_s_jobs2: {two:.1f} runs/s")
    print(f"sweep_speedup_jobs2: {two / one:.2f} x")
    print(f"load_average_1min: {os.getloadavg()[0]:.2f}")
