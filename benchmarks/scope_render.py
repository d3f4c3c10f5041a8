"""Oscilloscope drawing speed (issue 8), offscreen at 1280×720, each frame a full repaint (`grab()`):

- scope_live_fps: 8 curves × 10 000 points, every frame new samples appended and the chart redrawn as during
  a Free Run (goal ≥ 30 fps);
- scope_browse_fps: 8 curves × 10 M samples, panning and zooming (cached min/max pyramid; goal ≥ 30 fps;
  plain pyqtgraph ≈ 8 fps at 8 × 1 M, peers.md 2.9).
Prints `name: value unit` lines."""

import os
import sys
import time

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import numpy as np  # noqa: E402
from PySide6.QtWidgets import QApplication  # noqa: E402

from motiontool.scope.curves import Curve, Scope  # noqa: E402
from motiontool.scope.ui.window import ScopeWindow  # noqa: E402


def make_window(n: int, curves: int = 8) -> ScopeWindow:
    scope = Scope("free_run")
    scope.settings.default_samples = n
    for k in range(curves):
        c = scope.add_curve(Curve(f"c{k}"))
        c.buffer.set_capacity(n)
    w = ScopeWindow(None, "free_run", scope=scope, ask=False)
    w.resize(1280, 720)  # not shown: each frame is painted exactly once, by grab()
    return w


def live(app) -> float:
    n = 10_000
    w = make_window(n)
    t0 = 0
    rng = np.random.default_rng(1)
    for c in w.scope.curves:  # a full buffer, as after 10 s of a 1 kHz stream
        t = np.arange(n, dtype=float)
        c.buffer.extend(t, np.sin(t / 300 + rng.random()) * 1000 + rng.normal(0, 5, n))
    t0 = n
    w.chart.live = True
    frames, start = 0, time.perf_counter()
    while time.perf_counter() - start < 3.0:
        t = np.arange(t0, t0 + 20, dtype=float)   # 20 ms of new samples per frame
        for c in w.scope.curves:
            c.buffer.extend(t, np.sin(t / 300) * 1000)
        t0 += 20
        w.run.tick()
        w.grab()
        frames += 1
    return frames / (time.perf_counter() - start)


def browse(app) -> tuple[float, float]:
    n = 10_000_000
    w = make_window(n)
    t = np.arange(n, dtype=float)
    for k, c in enumerate(w.scope.curves):
        c.buffer.extend(t, np.sin(t / (1e4 * (k + 1))) * 1000 + (t % 977) * 0.1)
    start = time.perf_counter()
    w.zoom_reset()   # builds the pyramids once
    build = time.perf_counter() - start
    view = w.chart.view
    frames, start = 0, time.perf_counter()
    while time.perf_counter() - start < 3.0:
        phase = frames % 60
        width = n / (1 + phase)              # zoom in and out …
        x0 = (n - width) * ((frames * 7919) % 1000) / 1000   # … while panning
        view.setXRange(x0, x0 + width, padding=0)
        w.chart.refresh(navigation=False)
        w.grab()
        frames += 1
    return frames / (time.perf_counter() - start), build


def main() -> None:
    app = QApplication.instance() or QApplication(sys.argv)
    print(f"scope_live_fps: {live(app):.1f} fps")
    fps, build = browse(app)
    print(f"scope_browse_fps: {fps:.1f} fps")
    print(f"scope_browse_first_draw: {build:.2f} s")


if __name__ == "__main__":
    main()
