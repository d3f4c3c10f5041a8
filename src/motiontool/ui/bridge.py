"""Qt side of a comms Link: link events arrive on the kernel thread; here they become Qt signals that are
delivered in the GUI thread (queued), and the controller status is polled for the status bar."""

from __future__ import annotations

from PySide6.QtCore import QObject, QTimer, Signal

from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError, LinkEvent, Status


class LinkBridge(QObject):
    printed = Signal(int, str, int)         # time_ms, text, controller ID
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
        self._event.connect(self._dispatch)  # emitted from the kernel thread → queued into the GUI thread
        self._timer = QTimer(self)
        self._timer.setInterval(poll_ms)
        self._poll_ms = poll_ms
        self._timer.timeout.connect(self.poll)
        self.last_status: Status | None = None

    @property
    def connected(self) -> bool:
        return self.link is not None

    def attach(self, link: Link, description: str, *, controller_id: int = 1) -> None:
        self.detach(close=False)
        self.link = link
        self.description = description
        self.controller_id = controller_id
        # Events are tagged with the controller they came from: after a switch, queued ones keep their ID.
        self._callback = lambda event, *, cid=controller_id: self._event.emit((cid, event))
        link.subscribe(self._callback)
        # a slow line (FC at 9600 baud) is asked for the status less often than the simulator
        self._timer.setInterval(max(self._poll_ms, int(1000 * link.status_interval_s)))
        self._timer.start()
        self.connection_changed.emit("connected")
        self.poll()

    def detach(self, *, close: bool = True) -> None:
        """Let go of the controller; with close=False its link stays open and its program keeps running."""
        if self.link is not None:
            self.link.unsubscribe(self._callback)
            if close:
                self.link.close()
            self.link = None
            self._timer.stop()
            self.connection_changed.emit("closed")

    def poll(self) -> None:
        if self.link is None:
            return
        try:
            status = self.link.status()
        except LinkError:
            self._timer.stop()
            self.link.unsubscribe(self._callback)
            self.link = None  # the next command that needs the controller reconnects (DG 2064-2066)
            self.connection_changed.emit("lost")
            return
        if status != self.last_status:
            self.last_status = status
            self.status_changed.emit(status)

    def _dispatch(self, tagged: tuple[int, LinkEvent]) -> None:
        cid, event = tagged
        if event.kind == "print":
            self.printed.emit(event.time_ms, event.text, cid)
        elif event.kind == "error":
            self.controller_error.emit(event.time_ms, event.number, event.text, event.line, cid)
        elif event.kind == "program":
            self.program_event.emit(event.time_ms, event.text, cid)
            if cid == self.controller_id:
                self.poll()
        elif event.kind == "samples":
            self.samples.emit(event.data)
        elif event.kind == "message":  # the controller side tells something: a link timeout, events it dropped
            self.program_event.emit(event.time_ms, event.text, cid)
