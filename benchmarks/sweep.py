"""Runs per second of `motiontool sweep` (issue 30 item 2): an 8 x 8 grid of 32-60 KPROP x 32-61 KDER, each point a
fresh simulated MCO 305 moving 50 revolutions (POSA 204800) for 5 s of virtual time, measured by
max(abs(TRACKERR)) and settle_time(APOS, 204800, 10), on 1 and on 2 local processes (the pool's start-up
included, as a user waits for it; 64 points, so that it is a small part as in a real sweep).

Prints `sweep_runs_per_s_jobs1: X runs/s` and `sweep_runs_per_s_jobs2: X runs/s` (wall clock, the best of three),
their ratio, runs per CPU second with 1 job (close to an idle core's figure), and the machine's load average: the
machine is shared, and under load the workers get no more CPU than the one process would (measured at load 10:
0.027 s of CPU per run in a worker, 0.024 s in the process itself, but twice the wall time per run).
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


def rate(job, points, jobs: int) -> tuple[float, float]:
    """(runs per wall second, runs per CPU second of this process), each the best of three."""
    best, best_cpu = 0.0, 0.0
    for _ in range(3):
        done: dict = {}
        started, cpu = time.perf_counter(), time.process_time()
        run_points(job, points, done, lambda k, row: None, jobs=jobs)
        best = max(best, len(done) / (time.perf_counter() - started))
        best_cpu = max(best_cpu, len(done) / max(time.process_time() - cpu, 1e-9))
    return best, best_cpu


if __name__ == "__main__":
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "move.m"
        path.write_text(PROGRAM, encoding="utf-8")
        points = grid([parse_vary("32-60=20:90:10"), parse_vary("32-61=0:350:50", 2)])
        job = prepare(path, ["32-60", "32-61"], MEASURES, [], 5.0, [], sys.stderr)
    (one, one_cpu), (two, _) = rate(job, points, 1), rate(job, points, 2)
    print(f"sweep_runs_per_s_jobs1: {one:.1f} runs/s")
    print(f"sweep_runs_per_cpu_s_jobs1: {one_cpu:.1f} runs/s")  # what one idle core gives, whatever the load
    print(f"sweep_runs_per_s_jobs2: {two:.1f} runs/s")
    print(f"sweep_speedup_jobs2: {two / one:.2f} x")
    print(f"load_average_1min: {os.getloadavg()[0]:.2f}")
