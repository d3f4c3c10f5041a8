"""Python's cyclic garbage collection on the GUI thread only.

The collector runs in whichever thread passes an allocation threshold. The IDE has worker threads (the live
check, the status worker, the embedded link); a collection there destroys unreachable Qt widgets outside the GUI
thread, and if the GUI thread is inside a Qt call that released the GIL (`QApplication.topLevelWidgets()`), it
is left holding a dangling pointer: a segmentation fault. As pyqtgraph does for the same reason, automatic
collection is switched off and a GUI timer collects by the collector's own thresholds.
"""

from __future__ import annotations

import gc

from PySide6.QtCore import QObject, QTimer


class GuiThreadCollector(QObject):
    """Collect garbage cycles from a timer of the GUI thread instead of at random allocations."""

    def __init__(self, parent: QObject, *, interval_ms: int = 1000) -> None:
        super().__init__(parent)
        gc.disable()
        self.timer = QTimer(self)
        self.timer.timeout.connect(self.check)
        self.timer.start(interval_ms)

    def check(self) -> int:
        """Collect the oldest generation whose count passed its threshold; the number of objects freed."""
        counts = gc.get_count()
        thresholds = gc.get_threshold()
        for generation in (2, 1, 0):
            if counts[generation] > thresholds[generation]:
                return gc.collect(generation)
        return 0

    def stop(self) -> None:
        """Back to Python's automatic collection (the collector is done with)."""
        self.timer.stop()
        self.setParent(None)
        gc.enable()


def install(app: QObject) -> GuiThreadCollector:
    """One collector per application (a second call returns the first)."""
    collector = app.findChild(GuiThreadCollector)
    return collector if collector is not None else GuiThreadCollector(app)
