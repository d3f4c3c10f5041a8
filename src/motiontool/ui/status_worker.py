"""The periodic status poll of a window's controller, on a worker thread (decision F28).

On a slow line a status exchange takes a while (about 0.26 s at 9600 baud, a second at 2400): asked on the GUI
thread, the window would stand still that long at every poll. A `StatusWorker` asks from its own thread — through
the Link, as everything in the UI does — and hands each answer to the GUI thread as a queued Qt signal. One thread
per followed link: `stop()` (the window detaches, its interface closes) ends it without waiting for the wire, and
an answer of a link the window has left is never delivered. Events need no worker here: an embedded link publishes
them from its kernel thread, a wire link from its own event poller (comms/remote.py).
"""

from __future__ import annotations

import threading

from PySide6.QtCore import QObject, Qt, Signal, Slot

from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError


class StatusWorker(QObject):
    """`follow(link, interval_s)` polls `link.status()` every `interval_s` (from the end of the last answer) and at
    once on `poll_now()`; answers arrive in the GUI thread as `polled(Status)`, a refusal as `failed(text)` — after
    which the link is not asked again (the window reconnects with a new link)."""

    polled = Signal(object)        # Status
    failed = Signal(str)           # the LinkError's text

    def __init__(self, parent: QObject | None = None):
        super().__init__(parent)
        self._poll: _Poll | None = None
        self._generation = 0
        # the window may be deleted without a stop(): its threads then end after their current exchange
        self._gone = threading.Event()
        self.destroyed.connect(lambda *_, gone=self._gone: gone.set())

    @property
    def following(self) -> bool:
        return self._poll is not None

    @property
    def worker(self) -> threading.Thread | None:
        """The thread asking now (None when stopped)."""
        return self._poll

    def follow(self, link: Link, interval_s: float) -> None:
        """Ask `link` for its status at once and then every `interval_s` seconds (after `stop()` of the last)."""
        self.stop()
        self._generation += 1
        relay = _Relay()           # the worker's sender: it lives as long as the thread, not as long as the window
        relay.answer.connect(self._deliver, Qt.ConnectionType.QueuedConnection)
        self._poll = _Poll(link, interval_s, self._generation, relay, self._gone)
        self._poll.start()

    def poll_now(self) -> None:
        """Ask for the status now (after a command, on a program event). A request made while an answer is on its
        way is asked again after it: the answer on its way may predate the command."""
        if self._poll is not None:
            self._poll.wake.set()

    def stop(self) -> None:
        """Stop polling; an answer still on its way is dropped (its thread ends after it, without waiting here)."""
        if self._poll is not None:
            self._poll.stopped.set()
            self._poll.wake.set()
            self._poll = None
            self._generation += 1

    @Slot(int, object)
    def _deliver(self, generation: int, answer) -> None:
        if generation != self._generation:
            return                 # from a link this window has left
        if isinstance(answer, Exception):
            self.stop()
            self.failed.emit(str(answer))
        else:
            self.polled.emit(answer)


class _Relay(QObject):
    """Emits from the worker thread. Created in the GUI thread without a parent and deleted (deleteLater, in the GUI
    thread) when the worker ends, so no emit ever meets a deleted window; Qt drops the connection when the
    receiving StatusWorker is deleted first."""

    answer = Signal(int, object)   # (generation, Status | exception)


class _Poll(threading.Thread):
    def __init__(self, link: Link, interval_s: float, generation: int, relay: _Relay,
                 gone: threading.Event) -> None:
        super().__init__(name="status-poll", daemon=True)
        self.link = link
        self.interval_s = interval_s
        self.generation = generation
        self.relay = relay
        self.gone = gone
        self.wake = threading.Event()
        self.stopped = threading.Event()

    def _ended(self) -> bool:
        return self.stopped.is_set() or self.gone.is_set()

    def run(self) -> None:
        try:
            while not self._ended():
                self.wake.clear()  # a poll_now() from here on asks again after this answer
                try:
                    result = self.link.status()
                except LinkError as exc:
                    result = exc
                except Exception as exc:  # noqa: BLE001 - a failing link must not leave the status frozen silently
                    result = LinkError(f"status request failed: {type(exc).__name__}: {exc}")
                if self._ended():
                    return
                self.relay.answer.emit(self.generation, result)
                if isinstance(result, LinkError):
                    return
                self.wake.wait(self.interval_s)
        finally:
            self.relay.deleteLater()
