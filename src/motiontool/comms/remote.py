"""RemoteLink: a Link to a controller behind any transport that can exchange messages (comms/wire.py).

A transport is one function, ``exchange(message: bytes) -> bytes``: the FC link chunks the message into
telegrams (comms/fc/), a CANopen link can write it to an SDO domain object and read the answer back. Everything
else is here: request ids and the session, decoding answers, and fetching events.

Events are polled (a bus master is never called back): while anything subscribes, a poller thread asks for the
events after the last one it saw, every `poll_interval_s` or at once while the controller says more are waiting;
while the connection is lost it keeps trying, and `alive` comes back with the first answer. With `patience_s`
(`motiontool run --timeout`) a request waits that long for a lost connection to come back (`patiently`).
`flush_events()` fetches what is waiting now (the CLI calls it before it reads the status, so output keeps its
order). Events are published in sequence order, never twice; events the controller had to drop are reported
as a ``message`` event. A link sees the events of its own session only: its first request (or subscription)
asks the controller where its numbering stands now (``events {now}``) and starts there, so another master's
backlog (an earlier run's tail, a program the drive started by itself) is neither printed nor counted as lost
(decision F29).
"""

from __future__ import annotations

import contextlib
import random
import threading
import time
from collections.abc import Callable
from typing import Any

from motiontool.comms.client import Identity
from motiontool.comms.link import Link
from motiontool.comms.protocol import ConnectionLost, LinkError, LinkEvent, Request
from motiontool.comms.wire import DAMAGED_REQUEST, WireError, decode_response, encode_request

POLL_INTERVAL_S = 0.05
DAMAGED_REPEATS = 3      # a request whose request or answer arrived damaged is sent again this often
LOST_RETRY_S = 0.25      # while the connection is lost, the poller tries again this often


class RemoteLink(Link):
    kind = "remote"

    def __init__(self, exchange: Callable[[bytes], bytes], description: str = "",
                 poll_interval_s: float = POLL_INTERVAL_S):
        super().__init__()
        self._exchange = exchange
        self.description = description
        self.poll_interval_s = poll_interval_s
        self.session = random.getrandbits(31) + 1
        self._next_id = random.getrandbits(20)      # ids differ between links of one session's lifetime too
        self._bus = threading.RLock()               # one request on the wire at a time
        self._events_lock = threading.RLock()       # one event poll at a time: events are published in order
        self._last_event = 0
        self._epoch: int | None = None
        self._closed = threading.Event()
        self._lost = False
        self._lost_since: float | None = None
        self.patience_s = 0.0                       # how long a lost connection may last before requests fail
        self._poller: threading.Thread | None = None
        self._identity: Identity | None = None

    # --- requests -------------------------------------------------------------------------------------
    @property
    def alive(self) -> bool:
        return not self._closed.is_set() and not self._lost

    def request(self, request: Request) -> Any:
        if self._closed.is_set():
            raise ConnectionLost("the link is closed")
        if self._epoch is None and request.op != "events":
            self._mark_session()
        message = encode_request(request, self.session)   # a repeat is the same (session, id): never applied twice

        def exchange():
            with self._bus:
                return self._exchange(message)
        damage = ""
        for _ in range(DAMAGED_REPEATS + 1):
            # a damaged answer, or the controller's word that our request arrived damaged, is asked again under
            # the same (session, id): the controller applies it once and answers a repeat from its cache
            try:
                response = decode_response(self.patiently(exchange))
            except WireError as exc:
                damage = f"a damaged answer ({exc})"
                continue
            if not response.ok and response.id == 0 and response.error.startswith(DAMAGED_REQUEST):
                damage = response.error
                continue
            if response.id != request.id and response.ok:
                raise LinkError(f"answer to request {response.id} where {request.id} was expected")
            return response.result()
        raise LinkError(f"{request.op}: {DAMAGED_REPEATS + 1} tries on {self.description}, the last gave {damage}")

    def patiently(self, action: Callable[[], Any]) -> Any:
        """Run `action` (one exchange with the controller); a lost connection marks the link lost and, with
        `patience_s`, is a pause: the same action is tried again until it gets through or the link has been lost
        that long (one deadline for every thread), then ConnectionLost. A transport's own retries see short
        gaps; this sees a drive that stalls for seconds (decision F30)."""
        while True:
            try:
                result = action()
            except ConnectionLost as exc:
                self._set_connection(lost=True, text=self.lost_text(str(exc)))
                since = self._lost_since or time.monotonic()
                left = since + self.patience_s - time.monotonic()
                if left <= 0 or self._closed.is_set():
                    if self.patience_s > 0:
                        raise ConnectionLost(f"{self.description} did not come back within {self.patience_s:g} s: "
                                             f"{exc}") from None
                    raise
                self._closed.wait(min(LOST_RETRY_S, left))
                continue
            self._set_connection(lost=False)
            return result

    def lost_text(self, reason: str) -> str:
        if self.patience_s > 0:
            return f"lost connection to {self.description}, waiting up to {self.patience_s:g} s ({reason})"
        return f"Lost connection: {reason}"

    def restored_text(self, why: str = "") -> str:
        if self.patience_s > 0:
            return f"connection to {self.description} restored"
        return f"Connection restored ({why})" if why else "Connection restored"

    def _set_connection(self, *, lost: bool, text: str = "") -> None:
        """Mark the link lost or restored; a `connection` event says so once per change. A transport whose line
        comes back by itself (a heartbeat that resumes) calls it with lost=False."""
        if lost == self._lost:
            return
        self._lost = lost
        self._lost_since = time.monotonic() if lost else None
        self._publish(LinkEvent("connection", 0, text or (self.lost_text("no answer") if lost
                                                          else self.restored_text())))

    def identify(self) -> Identity:
        """Asked every time: the name changes (Parameters ▸ Name, here or by another master); the last answer
        is kept for what cannot change while the link is open (the clock)."""
        self._identity = super().identify()
        return self._identity

    @property
    def virtual_time(self) -> bool:
        """True when the controller's clock moves only on `advance` (a virtual drive started with a virtual
        clock)."""
        identity = self._identity or self.identify()
        return identity.clock == "virtual"

    # --- events ---------------------------------------------------------------------------------------
    def subscribe(self, callback: Callable[[LinkEvent], None]) -> None:
        super().subscribe(callback)
        if self._epoch is None:
            with contextlib.suppress(LinkError):   # a lost line: the first poll that gets through marks it
                self.poll_events()
        if self._poller is None and self.alive:
            self._poller = threading.Thread(target=self._poll_loop, name=f"{self.kind}-events", daemon=True)
            self._poller.start()

    def poll_events(self) -> bool:
        """Fetch one batch of events and publish them; True when more are waiting."""
        with self._events_lock:
            if self._epoch is None:
                self._mark_session()
                return False
            # the epoch names the numbering `after` belongs to: a restarted controller answers from its first event
            value = self.call("events", after=self._last_event, epoch=self._epoch)
            if self._epoch is not None and value.get("epoch") != self._epoch:
                self._publish(LinkEvent("message", 0, "the controller restarted: its event numbers begin again"))
                self._last_event = 0
            self._epoch = value.get("epoch")
            if value.get("lost"):
                self._publish(LinkEvent("message", 0, f"{value['lost']} controller events were lost "
                                                      "(they were not fetched in time)"))
            for seq, data in value.get("events", []):
                if seq <= self._last_event:
                    continue
                if not self._publish(LinkEvent(**data)):
                    # nobody listens (the IDE let go of a lost link): not acknowledged, so the drive keeps it for
                    # the link that resumes this session (Reconnect) instead of it being fetched into the void
                    return False
                self._last_event = seq
            self._last_event = max(self._last_event, int(value.get("last", self._last_event)))
            return bool(value.get("more"))

    def resume(self, previous: Link) -> None:
        """This link replaces `previous`, lost, to the same controller for the same master (the IDE's Reconnect):
        the session goes on where the lost link's events stopped, so what the controller said while the line was
        down (a link timeout's reaction, a program error) is shown now instead of being taken for another
        master's past. A controller restarted meanwhile is found by the epoch, as on any poll."""
        if isinstance(previous, RemoteLink) and previous._epoch is not None:
            with self._events_lock:
                if self._epoch is None:
                    self._epoch, self._last_event = previous._epoch, previous._last_event

    def _mark_session(self) -> None:
        """This session starts now: the events before it belong to other masters (or to nobody)."""
        with self._events_lock:
            if self._epoch is None:
                mark = self.call("events", now=True)
                self._epoch, self._last_event = mark.get("epoch"), int(mark.get("last", 0))

    def flush_events(self) -> None:
        while self.poll_events():
            pass

    def _poll_loop(self) -> None:
        while not self._closed.is_set():
            if self._subscribers:
                try:
                    if self.poll_events():
                        continue
                except ConnectionLost:
                    pass            # said once by request(); keep trying: the line may come back
                except LinkError as exc:  # a refused poll (e.g. a damaged answer): try again next time
                    self._publish(LinkEvent("message", 0, f"event poll failed: {exc}"))
            self._closed.wait(max(self.poll_interval_s, LOST_RETRY_S) if self._lost else self.poll_interval_s)

    def close(self) -> None:
        self._closed.set()
        if self._poller is not None and self._poller is not threading.current_thread():
            self._poller.join(timeout=2.0)
