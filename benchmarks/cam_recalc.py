"""CAM editor: the time one mouse move takes while a fix point is dragged with Continuous Recalc on, for a
10 000-point curve and for the manual's 4-point stamping curve.  Goal: ≤ 16 ms per move (one frame at 60 Hz).

What one measured move covers, end to end, as a user sees it:

* a real ``QMouseEvent`` (MouseMove, left button held) is sent to the diagram's viewport, so pyqtgraph's scene,
  hover and drag handling run and the view box emits the drag like for a hand on the mouse;
* the editor's drag slot recomputes the moved curve, its spline profile, the diagram samples with the
  straight/curved colouring and the fix point markers; the Fix Points table row and, when it is the card in
  front (``_info`` lines), the Curve Info card follow the drag at up to 20 updates per second, so some moves
  include them and some do not (mean and p95 show both);
* ``QApplication.processEvents()`` then runs until Qt has painted everything that changed (diagram, table row,
  Curve Info card) into the window's backing store, i.e. until the screen shows the new state.

The timer covers sendEvent + processEvents of each move.  The window is 1400 × 900 (QT_QPA_PLATFORM=offscreen:
Qt's raster painting as on screen, without the final blit to a display) and the whole curve is in view (all
10 000 points and markers on screen) or, for the ``_zoomed`` lines, only the 100 fix points around the dragged
one (there the spline's change spreads over the whole view, so all of it is repainted on every move); the
cards show Curve Data (the default) or, for the ``_info`` lines, Curve Info.  pyqtgraph's mouse rate limit
(100 moves/s) is switched off so that every move is handled and timed.  The drag starts on fix point 5000 (the
nearest marker under it), warms up for 3 moves, is timed for STEPS moves (2 px up and -1..1 px sideways each),
and is released (the release, one undo step with the full refresh of tables and cards, is printed separately).

Prints ``name: value unit`` lines: mean and p95 per move, and the release.  Wall-clock times: on a machine
busy with other work they grow with the load.
"""

import os
import statistics
import sys
import time
import traceback

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import numpy as np  # noqa: E402
import pyqtgraph as pg  # noqa: E402
from pyqtgraph import debug as pg_debug  # noqa: E402
from PySide6.QtCore import QEvent, QPoint, QPointF, Qt  # noqa: E402
from PySide6.QtGui import QMouseEvent  # noqa: E402
from PySide6.QtWidgets import QApplication  # noqa: E402

from motiontool.camcurve import Curve, FixPoint, profile  # noqa: E402
from motiontool.cameditor.ui.window import CamEditor, Slot  # noqa: E402

POINTS = 10_000
STEPS = 60
WARM_UP = 3
LEFT, NONE = Qt.MouseButton.LeftButton, Qt.MouseButton.NoButton


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


def _send(editor: CamEditor, kind: QEvent.Type, pos: QPoint, button, buttons) -> None:
    viewport = editor.diagram.viewport()
    event = QMouseEvent(kind, QPointF(pos), QPointF(viewport.mapToGlobal(pos)), button, buttons,
                        Qt.KeyboardModifier.NoModifier)
    QApplication.sendEvent(viewport, event)


def _pixel(editor: CamEditor, master: float, slave: float) -> QPoint:
    return editor.diagram.mapFromScene(editor.diagram.box.mapViewToScene(QPointF(master, slave)))


def measure(app: QApplication, name: str, c: Curve, index: int, info: bool = False, zoomed: bool = False) -> None:
    sys.excepthook = _fail_on_slot_errors
    pg_debug.printExc = _fail_on_ignored_errors  # what pyqtgraph's warnOnException (paint) reports through
    editor = CamEditor()
    editor.confirm = False
    editor.resize(1400, 900)
    editor.show()
    editor.slots = [Slot(c.name, [], c)]
    editor.current = 0
    editor.refresh(zoom=True)
    p = c.fix_points[index]
    if zoomed:  # 50 fix points either side of the dragged one
        editor.options.boxes["auto_scale"].setChecked(False)
        near = c.fix_points[index - 50:index + 51]
        low, high = min(q.slave for q in near), max(q.slave for q in near)
        editor.diagram.box.setRange(xRange=(near[0].master, near[-1].master), yRange=(low - 50, high + 50))
    if info:
        editor.cards.setCurrentWidget(editor.curve_info)  # Curve Info follows the drag [DG L3646]
    for _ in range(3):
        app.processEvents()
    assert editor.options["continuous_recalc"]
    start = _pixel(editor, p.master, p.slave)
    _send(editor, QEvent.Type.MouseMove, start, NONE, NONE)  # hover: the hand cursor
    app.processEvents()
    _send(editor, QEvent.Type.MouseButtonPress, start, LEFT, LEFT)
    app.processEvents()
    times = []
    for k in range(WARM_UP + STEPS):
        pos = start + QPoint((k % 3) - 1, -2 * (k + 1))  # up and a little sideways
        t0 = time.perf_counter()
        _send(editor, QEvent.Type.MouseMove, pos, NONE, LEFT)
        app.processEvents()
        if k >= WARM_UP:
            times.append((time.perf_counter() - t0) * 1000)
    dragged = editor.diagram.box._dragging
    assert dragged is not None, "the press did not hit a fix point"
    # the last move was drawn in full (an exception in a slot would otherwise only be printed)
    shown = editor.diagram
    assert np.array_equal(shown.samples_y, profile(editor.curve()).slave(shown.samples_x, periodic=False))
    t0 = time.perf_counter()
    _send(editor, QEvent.Type.MouseButtonRelease, pos, LEFT, NONE)
    app.processEvents()
    release = (time.perf_counter() - t0) * 1000
    assert editor.slot().history.undo_label() == "Move point" and editor.curve() != c
    times.sort()
    name += ("_zoomed" if zoomed else "") + ("_info" if info else "")
    print(f"cam_recalc_drag_{name}_mean: {statistics.fmean(times):.1f} ms")
    print(f"cam_recalc_drag_{name}_p95: {times[int(np.ceil(0.95 * len(times))) - 1]:.1f} ms")
    print(f"cam_recalc_release_{name}: {release:.1f} ms")
    editor.modified = False
    editor.close()


def _fail_on_slot_errors(kind, value, tb) -> None:
    """An exception raised in a Qt slot or event handler is only printed by PySide (and one in a paint() by
    pyqtgraph); a benchmark that went on would time a broken drag."""
    sys.__excepthook__(kind, value, tb)
    os._exit(1)


def _fail_on_ignored_errors(msg: str = "", *args, **kwargs) -> None:
    traceback.print_exc()
    print(f"cam_recalc: {msg}", file=sys.stderr)
    os._exit(1)


def main() -> None:
    app = QApplication.instance() or QApplication(sys.argv)
    pg.setConfigOption("mouseRateLimit", 0)  # time every move (the editor itself keeps pyqtgraph's default)
    for info in (False, True):
        measure(app, "stamping", stamping(), 1, info)
        measure(app, "10000", curve(), POINTS // 2, info)
        measure(app, "10000", curve(), POINTS // 2, info, zoomed=True)


if __name__ == "__main__":
    main()
