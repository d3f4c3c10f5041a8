"""Real mouse events on a pyqtgraph plot (QMouseEvents sent to its viewport, so pyqtgraph's own hover, drag and
click logic runs), as a user drags in the oscilloscope's chart."""

from __future__ import annotations

from PySide6.QtCore import QEvent, QPoint, QPointF, Qt
from PySide6.QtGui import QMouseEvent
from PySide6.QtWidgets import QApplication

NONE = Qt.MouseButton.NoButton


def to_pixel(plot, view, x: float, y: float) -> QPoint:
    """The viewport pixel of view coordinates (x, y) in `view`, a view box of the PlotWidget `plot`."""
    return plot.mapFromScene(view.mapViewToScene(QPointF(x, y)))


def _send(plot, kind, pos: QPoint, button, buttons) -> None:
    viewport = plot.viewport()
    event = QMouseEvent(kind, QPointF(pos), QPointF(viewport.mapToGlobal(pos)), button, buttons,
                        Qt.KeyboardModifier.NoModifier)
    QApplication.sendEvent(viewport, event)


def drag(qtbot, plot, start: QPoint, end: QPoint, button=Qt.MouseButton.LeftButton, steps: int = 6) -> None:
    _send(plot, QEvent.Type.MouseMove, start, NONE, NONE)
    qtbot.wait(30)  # pyqtgraph drops mouse moves closer than its rate limit
    _send(plot, QEvent.Type.MouseButtonPress, start, button, button)
    for k in range(1, steps + 1):
        qtbot.wait(30)
        _send(plot, QEvent.Type.MouseMove, start + (end - start) * (k / steps), NONE, button)
    qtbot.wait(30)
    _send(plot, QEvent.Type.MouseButtonRelease, end, button, NONE)
    qtbot.wait(30)
