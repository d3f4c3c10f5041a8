"""Link requests a window makes on a worker thread (like the status poll, ui/status_worker.py): on a slow line
one exchange takes a quarter of a second or more, and the window must not stand still meanwhile.

`LinkJobs.run(work, done)` calls `work()` on the jobs' own thread, one job after another in the order asked, and
hands its result (or the LinkError/ValueError it raised) to `done` in the GUI thread. `PollJob.run(work, done)` is
one request at a time on a thread of its own: asked again while one is on the line, the new one is left out, which
is what a poll wants (the next comes a poll interval later with fresher values). `wait_off_gui(work)` is for a
command that needs the answer before it goes on (Execute's array check): the request runs on a thread while the
GUI thread keeps painting (user input waits, so the command is not started twice meanwhile); `waiting.waiting` is
wait_off_gui that says so.
"""

from __future__ import annotations

import contextlib
import queue
import threading
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QEventLoop, QObject, Qt, Signal, Slot

from motiontool.comms.protocol import LinkError

Done = Callable[[Any], None]


class _Relay(QObject):
    """Emits from a worker thread; lives as long as its job, not as long as the window (as in status_worker)."""

    answer = Signal(object, object)   # (done callback, result or exception)


class LinkJobs(QObject):
    def __init__(self, parent: QObject | None = None):
        super().__init__(parent)
        self._queue: queue.Queue = queue.Queue()
        self._thread: threading.Thread | None = None
        self._gone = threading.Event()
        self.destroyed.connect(lambda *_, gone=self._gone: gone.set())
        self.pending = 0                  # jobs asked and not yet delivered (tests wait for 0)

    def run(self, work: Callable[[], Any], done: Done) -> None:
        relay = _Relay()
        relay.answer.connect(self._deliver, Qt.ConnectionType.QueuedConnection)
        self.pending += 1
        self._queue.put((work, done, relay))
        if self._thread is None or not self._thread.is_alive():
            self._thread = threading.Thread(target=self._work, name="link-jobs", daemon=True)
            self._thread.start()

    def _work(self) -> None:
        while not self._gone.is_set():
            try:
                work, done, relay = self._queue.get(timeout=1.0)
            except queue.Empty:
                continue          # one thread for the window's life: it ends when the window is deleted
            result = _call(work)
            if not self._gone.is_set():
                relay.answer.emit(done, result)
            relay.deleteLater()

    @Slot(object, object)
    def _deliver(self, done: Done, result: Any) -> None:
        self.pending -= 1
        done(result)


class PollJob(QObject):
    answered = Signal(object, object)     # (done, result or exception), from the worker thread

    def __init__(self, parent: QObject | None = None, name: str = "scope-poll"):
        super().__init__(parent)
        self.name = name
        self.busy = False
        self.answered.connect(self._deliver)

    def run(self, work: Callable[[], Any], done: Done) -> bool:
        """Start `work` unless one is still under way (then False)."""
        if self.busy:
            return False
        self.busy = True
        threading.Thread(target=self._work, args=(work, done), name=self.name, daemon=True).start()
        return True

    def _work(self, work: Callable[[], Any], done: Done) -> None:
        try:
            result = work()
        except Exception as exc:  # noqa: BLE001 - a refused or lost request is said by `done`, not lost on a thread
            result = exc
        with contextlib.suppress(RuntimeError):   # the window was closed meanwhile
            self.answered.emit(done, result)

    def _deliver(self, done: Done, result: Any) -> None:
        self.busy = False
        done(result)


def _call(work: Callable[[], Any]) -> Any:
    try:
        return work()
    except (LinkError, ValueError) as exc:
        return exc
    except Exception as exc:  # noqa: BLE001 - a failing request is reported, never lost on a thread
        return LinkError(f"request failed: {type(exc).__name__}: {exc}")


def wait_off_gui(work: Callable[[], Any]) -> Any:
    """`work()` on a thread; the GUI thread paints while it waits. Raises what `work` raised."""
    box: list[Any] = []
    loop = QEventLoop()
    relay = _Relay()
    relay.answer.connect(lambda _done, _result: loop.quit(), Qt.ConnectionType.QueuedConnection)

    def body() -> None:
        box.append(_call(work))
        relay.answer.emit(None, None)

    thread = threading.Thread(target=body, name="link-wait", daemon=True)
    thread.start()
    while not box:  # the queued quit may come before exec(): then the loop ends at its first pass
        loop.exec(QEventLoop.ProcessEventsFlag.ExcludeUserInputEvents)
    # The answer is in the box before the thread emits: a quick answer is seen without a pass of the loop, and the
    # relay deleted then could be deleted while the thread still emits from it (a segfault under load).
    thread.join()
    relay.deleteLater()
    if isinstance(box[0], Exception):
        raise box[0]
    return box[0]
