"""Free Run streaming (issue 8): 4 controllers (embedded, threaded at real time), each streaming one group of
4 signals at 1 kHz into one oscilloscope window that redraws at 20 Hz. Prints
- scope_stream_drops: samples missing between consecutive packets (goal 0),
- scope_stream_latency_p95 / _max: how far the newest drawn sample is behind the controller clock when a
  frame is painted (goal < 100 ms),
- scope_stream_rss_growth: resident memory growth over the run,
- and, to tell design from load on a shared machine: scope_stream_data_age_p95 (how old the newest sample is
  when a frame starts: packets, queue, relay), scope_stream_frame_cpu_p95 (the GUI thread's CPU time for a
  frame) and scope_stream_frame_wall_p95 (the same frame on the wall clock: CPU plus waiting for a core and
  for the GIL held by the 4 kernel threads).
`--seconds N` (default 60) sets the duration."""

import argparse
import os
import resource
import sys
import time

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import numpy as np  # noqa: E402
from PySide6.QtCore import QObject, QTimer, Signal  # noqa: E402
from PySide6.QtWidgets import QApplication  # noqa: E402

from motiontool.aposs.driver import compile_source  # noqa: E402
from motiontool.controller.embedded import EmbeddedLink  # noqa: E402
from motiontool.scope.acquisition import FreeRun, new_curve  # noqa: E402
from motiontool.scope.curves import Group, Scope  # noqa: E402
from motiontool.scope.ui.window import ScopeWindow  # noqa: E402
from motiontool.ui import gui_gc  # noqa: E402

PROGRAM = "VEL 50\nACC 50\nDEC 50\nWHILE 1 DO\nPOSA 200000\nPOSA 0\nENDWHILE\n"
SIGNALS = ("APOS", "CPOS", "TRACKERR", "AVEL")


class Relay(QObject):
    packet = Signal(int, object)


def rss_mb() -> float:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize() / 2**20


def build(groups: int = 4, capacity: int = 20_000):
    """The set-up the stream benchmarks share (scope_soak.py too): one oscilloscope window and `groups`
    embedded controllers at real time, each running PROGRAM and streaming one Free Run group of SIGNALS; their
    packets reach the GUI thread through `relay` (connect to relay.packet, then start the runs)."""
    app = QApplication.instance() or QApplication(sys.argv)
    gui_gc.install(app)   # garbage collected on the GUI thread, as in the IDE (ui/app.py): never by a worker
    scope = Scope("free_run")
    scope.settings.default_samples = capacity
    window = ScopeWindow(None, "free_run", scope=scope, ask=False)
    window.resize(1280, 720)
    image = compile_source(PROGRAM, "move.m").image.to_bytes()
    relay = Relay()
    links, runs = [], []
    for k in range(groups):
        group = scope.add_group(Group(f"Group {k + 1}", controller=k + 1))
        for s in SIGNALS:
            new_curve(scope, s, group.name, "free_run", name=f"{k + 1}: {s}")
        link = EmbeddedLink(realtime_factor=1.0)
        link.download(image)
        link.start()
        links.append(link)
        runs.append(FreeRun(scope, link, group.name))
        link.subscribe(lambda e, k=k: relay.packet.emit(k, e.data) if e.kind == "samples" else None)
    return app, scope, window, links, runs, relay


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=60.0)
    args = parser.parse_args()
    app, scope, window, links, runs, relay = build()
    last_time = {}
    gaps = [0]

    def on_packet(k, data):
        t = data["time_ms"]
        if k in last_time:
            gaps[0] += max(0, t[0] - last_time[k] - 1)
        last_time[k] = t[-1]
        runs[k].feed(data)

    relay.packet.connect(on_packet)
    for run in runs:
        run.start()
    started = time.monotonic()
    window.list.rebuild()
    window.chart.live = True
    latencies, ages, frame_cpu, frame_wall = [], [], [], []
    rss0 = rss_mb()

    def frame():
        cpu0, wall0 = time.thread_time(), time.monotonic()
        for k, link in enumerate(links):
            newest = scope.curve(f"{k + 1}: APOS").raw()[0]
            if newest.size:
                ages.append(link.service.controller.time_ms - newest[-1])
        window.run.tick()
        window.chart.grab()   # what changes in a frame: the chart and (every 4th frame) the list
        window.list.viewport().grab()
        now = time.monotonic()
        frame_cpu.append((time.thread_time() - cpu0) * 1000)
        frame_wall.append((now - wall0) * 1000)
        for k, link in enumerate(links):
            newest = scope.curve(f"{k + 1}: APOS").raw()[0]
            if newest.size:
                # the controller clock runs at real time from its start: newest sample vs "now" on that clock
                clock = link.service.controller.time_ms
                latencies.append(clock - newest[-1] + (time.monotonic() - now) * 1000)
        if now - started > args.seconds:
            app.quit()

    timer = QTimer()
    timer.timeout.connect(frame)
    timer.start(50)
    app.exec()
    for run in runs:
        run.stop()
    for link in links:
        link.close()
    lat = np.array(latencies[20:] or [0.0])
    print(f"scope_stream_drops: {gaps[0] + sum(r.dropped for r in runs)} samples")
    print(f"scope_stream_latency_p95: {np.percentile(lat, 95):.0f} ms")
    print(f"scope_stream_latency_max: {lat.max():.0f} ms")
    print(f"scope_stream_rss_growth: {rss_mb() - rss0:.1f} MB")
    for name, values in (("data_age", ages[80:]), ("frame_cpu", frame_cpu[20:]), ("frame_wall", frame_wall[20:])):
        print(f"scope_stream_{name}_p95: {np.percentile(np.array(values or [0.0]), 95):.0f} ms")


if __name__ == "__main__":
    main()
