"""Drive a pyqtgraph plot with 8 live curves offscreen and report memory; run as a separate process.

Prints one JSON line: {"frames": N, "rss_kib": [samples...], "seconds": wall time of the run, "waited_s":
seconds the plot was ready to run but waited for a CPU (Linux schedstat; null where unknown)}. A crash of Qt
(e.g. the PySide6 6.12.0 refcount bug) ends the process abnormally, which the soak test sees as a non-zero exit.
"""

import json
import os
import sys
import time

import numpy as np

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pyqtgraph as pg  # noqa: E402
from PySide6.QtCore import QTimer  # noqa: E402
from PySide6.QtWidgets import QApplication  # noqa: E402


def rss_kib() -> int:
    with open("/proc/self/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def run_queue_wait() -> float | None:
    """Seconds this thread has spent ready to run but waiting for a CPU, or None where the kernel does not say.
    /proc/thread-self/schedstat: time on a CPU, time waiting on a run queue (ns), timeslices."""
    try:
        with open("/proc/thread-self/schedstat", encoding="ascii") as schedstat:
            return int(schedstat.read().split()[1]) / 1e9
    except (OSError, IndexError, ValueError):
        return None


def main(seconds: float) -> None:
    app = QApplication(sys.argv[:1])
    plot = pg.PlotWidget()
    plot.resize(800, 500)
    plot.show()
    curves = [plot.plot(pen=pg.intColor(i, 8)) for i in range(8)]
    n = 2000
    t = np.arange(n) * 1e-3
    state = {"frames": 0, "phase": 0.0}
    samples: list[int] = []
    start = time.monotonic()
    waited_at_start = run_queue_wait()

    def update() -> None:
        state["phase"] += 0.05
        for i, curve in enumerate(curves):
            curve.setData(t, np.sin(2 * np.pi * (i + 1) * t + state["phase"]) + i)
        plot.repaint()
        state["frames"] += 1
        elapsed = time.monotonic() - start
        if state["frames"] % 25 == 0:
            samples.append(rss_kib())
        if elapsed >= seconds:
            app.quit()

    timer = QTimer()
    timer.timeout.connect(update)
    timer.start(20)
    app.exec()
    elapsed = time.monotonic() - start
    waited_at_end = run_queue_wait()
    waited = None if waited_at_start is None or waited_at_end is None else waited_at_end - waited_at_start
    print(json.dumps({"frames": state["frames"], "rss_kib": samples, "seconds": elapsed, "waited_s": waited}))


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 60.0)
