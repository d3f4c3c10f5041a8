"""Qt side of a comms Link: link events arrive on the kernel thread (or a wire link's event poller); here they
become Qt signals that are delivered in the GUI thread (queued), and the controller status is polled for the status
bar on a worker thread (ui/status_worker.py), so the window never waits for a slow line to answer it.

The bridge is also what a tool window (oscilloscope, CAM editor, Array Editor) is given of its APOSS window's
session: the link, the controller ID, its signals, `waiting`, `connect_default` and the window's `prompts` - not
the main window (issue 27 item 5)."""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Callable

from PySide6.QtCore import QObject, Signal

from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkEvent, Status
from motiontool.session.prompts import Prompts
from motiontool.ui.link_jobs import waiting
from motiontool.ui.status_worker import StatusWorker


class LinkBridge(QObject):
    printed = Signal(int, str, int)         # time_ms, text, controller ID
    printed_lines = Signal(int, object)     # controller ID, [text, ...]: consecutive PRINT lines in one go
    controller_error = Signal(int, int, str, object, int)  # time_ms, number, text, line, controller ID
    program_event = Signal(int, str, int)   # time_ms, text, controller ID
    samples = Signal(object)                # {"signals", "time_ms", "values"}
    status_changed = Signal(object)         # Status
    connection_changed = Signal(str)        # "connected" | "lost" | "closed"
    _event = Signal(object)

    def __init__(self, parent: QObject | None = None, poll_ms: int = 200):
        super().__init__(parent)
        self.link: Link | None = None
        self.description = ""
        self.controller_id = 1
        self._callback = None
        # Events of the kernel thread wait here; one queued signal wakes the GUI thread for all that came meanwhile,
        # so a burst of PRINT lines costs one wake-up and one append, not one each (decisions K82).
        self._pending: deque = deque()
        self._lock = threading.Lock()
        self._woken = False
        self._event.connect(self._dispatch)  # emitted from the kernel thread → queued into the GUI thread
        self._poll_ms = poll_ms
        self.status_worker = StatusWorker(self)
        self.status_worker.polled.connect(self._polled)
        self.status_worker.failed.connect(self._lost)
        self.last_status: Status | None = None
        self.prompts: Prompts | None = None
        self._connect: Callable[[], bool] | None = None

    @property
    def connected(self) -> bool:
        return self.link is not None

    def serve(self, connect: Callable[[], bool], prompts: Prompts) -> None:
        """Be the Qt face of the window's session (set by ui/connection.py): `connect` connects it as the
        window's commands do; `prompts` is the window's."""
        self._connect, self.prompts = connect, prompts

    def connect_default(self) -> bool:
        """A tool window that needs a controller connects its APOSS window first (DG 2054-2062, 5265-5273)."""
        return self.connected or (self._connect is not None and self._connect())

    def attach(self, link: Link, description: str, *, controller_id: int = 1) -> None:
        self.detach(close=False)
        self.link = link
        self.description = description
        self.controller_id = controller_id
        self.last_status = None                 # the new controller's first answer is news
        # Events are tagged with the controller they came from: after a switch, queued ones keep their ID.
        self._callback = lambda event, *, cid=controller_id: self._queue(cid, event)
        link.subscribe(self._callback)
        self.connection_changed.emit("connected")
        # at once, then periodically; a slow line (FC at 9600 baud) less often than the simulator
        self.status_worker.follow(link, max(self._poll_ms / 1000, link.status_interval_s))

    def detach(self, *, close: bool = True) -> None:
        """Let go of the controller; with close=False its link stays open and its program keeps running."""
        if self.link is not None:
            self.status_worker.stop()
            self.link.unsubscribe(self._callback)
            if close:
                self.link.close()
            self.link = None
            self.connection_changed.emit("closed")

    @staticmethod
    def waiting(window, text: str, work):
        """link_jobs.waiting for the windows outside ui/ (CAM and Array editors): they get the bridge, and the
        layers keep them from importing ui/ (decision I34)."""
        return waiting(window, text, work)

    def poll(self) -> None:
        """Ask for the status now (after a command, on a program event): it arrives as `status_changed` when it
        differs from the last one, without the window waiting for it."""
        self.status_worker.poll_now()

    def _polled(self, status: Status) -> None:
        if self.link is not None and status != self.last_status:
            self.last_status = status
            self.status_changed.emit(status)

    def _lost(self, _text: str) -> None:
        if self.link is None:
            return
        self.status_worker.stop()
        self.link.unsubscribe(self._callback)
        self.link = None  # the next command that needs the controller reconnects (DG 2064-2066)
        self.connection_changed.emit("lost")

    def _queue(self, cid: int, event: LinkEvent) -> None:
        with self._lock:
            self._pending.append((cid, event))
            if self._woken:
                return
            self._woken = True
        self._event.emit(None)

    def _dispatch(self, _wake) -> None:
        with self._lock:
            batch = list(self._pending)
            self._pending.clear()
            self._woken = False
        lines: list[str] = []
        lines_of = None
        for cid, event in batch:
            if event.kind == "print":
                if lines and cid != lines_of:
                    self.printed_lines.emit(lines_of, lines)
                    lines = []
                lines_of = cid
                lines.append(event.text)
                self.printed.emit(event.time_ms, event.text, cid)
                continue
            if lines:
                self.printed_lines.emit(lines_of, lines)
                lines = []
            self._handle(cid, event)
        if lines:
            self.printed_lines.emit(lines_of, lines)

    def _handle(self, cid: int, event: LinkEvent) -> None:
        if event.kind == "error":
            self.controller_error.emit(event.time_ms, event.number, event.text, event.line, cid)
        elif event.kind == "program":
            self.program_event.emit(event.time_ms, event.text, cid)
            if cid == self.controller_id:
                self.poll()
        elif event.kind == "samples":
            self.samples.emit(event.data)
        elif event.kind == "connection":
            # the link saw the loss itself (a CANopen heartbeat that stopped, a failed event poll): say so now rather
            # than when a status request times out; a queued event of a link left since is judged by the current one
            if cid == self.controller_id and self.link is not None and not getattr(self.link, "alive", True):
                self._lost(event.text)
        elif event.kind == "message":  # the controller side tells something: a link timeout, events it dropped
            self.program_event.emit(event.time_ms, event.text, cid)
