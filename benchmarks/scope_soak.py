"""Free Run soak (issue 8: "A 10-minute soak shows no crash and < 50 MB growth"). The set-up of
benchmarks/scope_stream.py: 4 embedded controllers, threaded at real time, each streaming one group of 4
signals at 1 kHz into one oscilloscope window that redraws at 20 Hz; for `--seconds N` (default 600).

Prints
- soak_rss_growth: resident memory at the end minus after the warm-up (the curves' FIFOs are allocated
  lazily and fill in `default_samples` ms, so the warm-up is 30 s, or half the run if that is shorter); also
  soak_rss_growth_total from before streaming started,
- soak_drops: samples missing between consecutive packets plus packets the groups refused (goal 0),
- soak_crash: exceptions raised while feeding packets or drawing frames, plus controllers whose kernel thread
  died (goal 0; a crash of the process itself prints nothing),
- soak_samples / soak_frames: what was streamed and drawn, so a stalled run is visible.
Progress (time, RSS) goes to stderr every 30 s."""

import argparse
import os
import sys
import time
import traceback

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
sys.path.insert(0, os.path.dirname(__file__))

from PySide6.QtCore import QTimer  # noqa: E402

from scope_stream import build, rss_mb  # noqa: E402

GROUPS = 4
CAPACITY = 20_000       # samples per curve, as scope_stream.py


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=600.0)
    args = parser.parse_args()
    app, scope, window, links, runs, relay = build(GROUPS, CAPACITY)
    last_time = {}
    counts = {"gaps": 0, "crash": 0, "samples": 0, "frames": 0}

    def failed(where: str) -> None:
        counts["crash"] += 1
        if counts["crash"] <= 3:
            print(f"soak: exception in {where}:\n{traceback.format_exc()}", file=sys.stderr)

    def on_packet(k, data):
        try:
            t = data["time_ms"]
            if k in last_time:
                counts["gaps"] += max(0, t[0] - last_time[k] - 1)
            last_time[k] = t[-1]
            counts["samples"] += len(t)
            runs[k].feed(data)
        except Exception:  # noqa: BLE001 - counted: the soak's point is that there are none
            failed("packet")

    relay.packet.connect(on_packet)
    rss_start = rss_mb()
    for run in runs:
        run.start()
    started = time.monotonic()
    warmup = min(30.0, args.seconds / 2)
    rss = {"warm": None, "next_report": 30.0}
    window.list.rebuild()
    window.chart.live = True

    def frame():
        try:
            window.run.tick()
            window.chart.grab()   # paint what a visible window paints: the chart and the list
            window.list.viewport().grab()
            counts["frames"] += 1
        except Exception:  # noqa: BLE001
            failed("frame")
        elapsed = time.monotonic() - started
        if rss["warm"] is None and elapsed >= warmup:
            rss["warm"] = rss_mb()
        if elapsed >= rss["next_report"]:
            rss["next_report"] += 30.0
            print(f"soak: {elapsed:.0f} s  rss {rss_mb():.1f} MB  samples {counts['samples']}", file=sys.stderr)
        if elapsed > args.seconds:
            app.quit()

    timer = QTimer()
    timer.timeout.connect(frame)
    timer.start(50)
    app.exec()
    dead = sum(not link.alive for link in links)
    for run in runs:
        try:
            run.stop()
        except Exception:  # noqa: BLE001
            failed("stop")
    for link in links:
        link.close()
    end = rss_mb()
    print(f"soak_seconds: {time.monotonic() - started:.0f} s")
    print(f"soak_rss_growth: {end - (rss['warm'] or rss_start):.1f} MB")
    print(f"soak_rss_growth_total: {end - rss_start:.1f} MB")
    print(f"soak_drops: {counts['gaps'] + sum(r.dropped for r in runs)}")
    print(f"soak_crash: {counts['crash'] + dead}")
    print(f"soak_samples: {counts['samples']}  (expected about {GROUPS * 1000 * args.seconds:.0f})")
    print(f"soak_frames: {counts['frames']}  (expected about {20 * args.seconds:.0f})")


if __name__ == "__main__":
    main()
