"""CAM editor: recompute + redraw time while a fix point of a 10 000-point curve is dragged (Continuous Recalc on).

Builds a curve of 10 000 C fix points (smooth random slave values, no interpolation grid), opens it in the
CamEditor offscreen and moves fix point 5000 step by step through the same code path a mouse drag uses
(CurveViewBox.point_dragged → CamEditor._dragged), each step followed by a synchronous repaint of the diagram.
Prints `cam_recalc_drag_10000: <median> ms` (and the worst step), and the same for the manual's 4-point
stamping curve.  Goal ≤ 16 ms.
"""

import os
import statistics
import sys
import time

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import numpy as np  # noqa: E402
from PySide6.QtWidgets import QApplication  # noqa: E402

from motiontool.camcurve import Curve, FixPoint  # noqa: E402
from motiontool.cameditor.ui.window import CamEditor, Slot  # noqa: E402

POINTS = 10_000
STEPS = 30


def curve() -> Curve:
    rng = np.random.default_rng(1)
    masters = np.arange(POINTS) * 10
    slaves = np.round(np.cumsum(rng.normal(0, 3, POINTS))).astype(int)
    slaves[0] = 0
    points = tuple(FixPoint(int(m), int(s)) for m, s in zip(masters, slaves, strict=True))
    return Curve("big", int(masters[-1]), points, interpolation=False, intervals=1000)


def stamping() -> Curve:
    """The manual's stamping curve (DG L1435-1465) for comparison."""
    points = (FixPoint(0, 0), FixPoint(1500, 1200, "T"), FixPoint(2500, 2400, "T"), FixPoint(4000, 3600))
    return Curve("stamping", 4000, points, intervals=40)


def measure(app, name: str, c: Curve, index: int) -> None:
    editor = CamEditor()
    editor.confirm = False
    editor.resize(1400, 900)
    editor.show()
    editor.slots = [Slot(c.name, [], c)]
    editor.current = 0
    editor.refresh(zoom=True)
    app.processEvents()
    p = editor.curve().fix_points[index]
    times = []
    for k in range(STEPS):
        t0 = time.perf_counter()
        editor._dragged(index, p.master + (k % 5) - 2, p.slave + 3 * k, False)
        editor.diagram.viewport().repaint()
        times.append((time.perf_counter() - t0) * 1000)
    editor._dragged(index, p.master, p.slave + 3 * STEPS, True)
    print(f"cam_recalc_drag_{name}: {statistics.median(times):.1f} ms")
    print(f"cam_recalc_drag_{name}_worst: {max(times):.1f} ms")
    editor.modified = False
    editor.close()


def main() -> None:
    app = QApplication.instance() or QApplication(sys.argv)
    measure(app, "stamping", stamping(), 1)
    measure(app, "10000", curve(), POINTS // 2)


if __name__ == "__main__":
    main()
