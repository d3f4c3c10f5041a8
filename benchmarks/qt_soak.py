"""The Qt stack's soak (tests/ui/soak_plot.py): 8 live pyqtgraph curves offscreen for `--seconds N` (default 60) in
a process of their own. The test suite runs the same plot for 15 s (tests/ui/test_soak.py); this is the long run.

Prints
- qt_soak_frames_per_s: frames drawn per second the machine let the plot run (the timer asks for 50),
- qt_soak_rss_growth: resident memory, median of the last third of the run minus median of the middle third,
- qt_soak_crash: 1 when the plot process died (the PySide6 6.12.0 refcount abort, say), else 0."""

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

PLOT = Path(__file__).resolve().parents[1] / "tests" / "ui" / "soak_plot.py"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0)
    seconds = parser.parse_args().seconds
    proc = subprocess.run([sys.executable, str(PLOT), str(seconds)], capture_output=True, text=True,
                          env={**os.environ, "QT_QPA_PLATFORM": "offscreen"})
    if proc.returncode != 0:
        print(proc.stderr[-2000:], file=sys.stderr)
        print("qt_soak_crash: 1")
        sys.exit(1)
    report = json.loads(proc.stdout.strip().splitlines()[-1])
    runnable = report["seconds"] - (report["waited_s"] or 0.0)
    rss = report["rss_kib"]
    third = len(rss) // 3
    middle, last = sorted(rss[third:2 * third]), sorted(rss[2 * third:])
    print(f"qt_soak_frames_per_s: {report['frames'] / runnable:.1f} /s")
    print(f"qt_soak_rss_growth: {last[len(last) // 2] - middle[len(middle) // 2]} KiB")
    print("qt_soak_crash: 0")


if __name__ == "__main__":
    main()
