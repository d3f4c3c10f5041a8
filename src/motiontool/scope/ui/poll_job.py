"""A link request of the oscilloscope on a thread of its own (issue 27 item 2: the window never waits for the
wire). One at a time: asked again while one is on the line, the new one is left out, which is what a poll wants
(the next comes a poll interval later with fresher values); the answer, or the exception it raised, reaches
`done` in the GUI thread. `wait(window, text, request)` is for Start/Stop, which need the answer before they go
on: the request runs on such a thread while the window paints, says `text` and shows a busy cursor; user input
waits meanwhile, so Start or Stop cannot begin twice."""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QEventLoop, QObject, Qt, Signal
from PySide6.QtWidgets import QApplication


class PollJob(QObject):
    answered = Signal(object, object)     # (done, result or exception), from the worker thread

    def __init__(self, parent: QObject | None = None, name: str = "scope-poll"):
        super().__init__(parent)
        self.name = name
        self.busy = False
        self.answered.connect(self._deliver)

    def run(self, work: Callable[[], Any], done: Callable[[Any], None]) -> bool:
        """Start `work` unless one is still under way (then False)."""
        if self.busy:
            return False
        self.busy = True
        threading.Thread(target=self._work, args=(work, done), name=self.name, daemon=True).start()
        return True

    def _work(self, work: Callable[[], Any], done: Callable[[Any], None]) -> None:
        try:
            result = work()
        except Exception as exc:  # noqa: BLE001 - a refused or lost request is said by `done`, not lost on a thread
            result = exc
        with contextlib.suppress(RuntimeError):   # the window was closed meanwhile
            self.answered.emit(done, result)

    def _deliver(self, done: Callable[[Any], None], result: Any) -> None:
        self.busy = False
        done(result)


def wait(window, text: str, request: Callable[[], Any]) -> Any:
    """`request()` on a thread; returns its answer or raises what it raised."""
    box: list[Any] = []
    loop = QEventLoop()
    job = PollJob(name="scope-wait")
    job.run(request, lambda result: (box.append(result), loop.quit()))
    window.statusBar().showMessage(text)
    QApplication.setOverrideCursor(Qt.CursorShape.BusyCursor)
    try:
        while not box:   # the answer may come before exec(): then the loop ends at its first pass
            loop.exec(QEventLoop.ProcessEventsFlag.ExcludeUserInputEvents)
    finally:
        QApplication.restoreOverrideCursor()
        if window.statusBar().currentMessage() == text:
            window.statusBar().clearMessage()
        job.deleteLater()
    if isinstance(box[0], BaseException):
        raise box[0]
    return box[0]
