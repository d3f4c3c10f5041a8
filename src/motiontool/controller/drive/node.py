"""One controller of the virtual drive as a wire link sees it: requests (thread-safe), an event queue with sequence
numbers, and the answers to recent requests kept so that a repeated request is answered, not applied twice.

Events: a wire master cannot be called back, so it polls. Every event gets the next sequence number; the wire-only
request ``events {after, max, epoch}`` returns the events after ``after`` (the last one the master saw) and forgets
the ones up to it. ``after`` counts in the numbering of ``epoch`` (the one the master saw last): the master of a
drive before its restart gets the new drive's events from the first. When more than `EVENT_LIMIT` are waiting the
oldest are dropped and the next answer says how many (``lost``), so a master that stopped polling costs bounded
memory (docs/link-protocol.md "Events on the wire"). ``events {now: true}`` (a master's first poll) answers no
events and the number to ask after: a master sees the events of its own session only, never another master's
backlog (decision F29).
"""

from __future__ import annotations

import itertools
import random
import threading
import time
from collections import OrderedDict, deque
from typing import Any

from motiontool.comms.protocol import LinkEvent, Request, Response
from motiontool.comms.wire import DAMAGED_REQUEST, WireError, decode_request, encode_response
from motiontool.controller.service import ControllerService

EVENT_LIMIT = 4096       # events kept for a master that does not poll
EVENTS_PER_ANSWER = 64   # at most this many in one `events` answer (the master asks again when `more`)
ANSWER_CACHE = 16        # answers kept per node for repeated requests


class EventQueue:
    """Events with sequence numbers 1, 2, …, fetched by a polling master (thread-safe)."""

    def __init__(self, limit: int = EVENT_LIMIT):
        self._lock = threading.Lock()
        self._events: deque[tuple[int, LinkEvent]] = deque()
        self.limit = limit
        self.seq = 0
        self.epoch = random.getrandbits(31)  # a new queue (a restarted drive) starts again at 1

    def put(self, event: LinkEvent) -> None:
        with self._lock:
            self.seq += 1
            self._events.append((self.seq, event))
            if len(self._events) > self.limit:
                self._events.popleft()

    def now(self) -> dict[str, Any]:
        """Where a new master starts: nothing fetched, nothing lost, `last` the newest number."""
        with self._lock:
            return {"events": [], "last": self.seq, "lost": 0, "more": False, "epoch": self.epoch}

    def after(self, seq: int, count: int = EVENTS_PER_ANSWER) -> dict[str, Any]:
        """The events after `seq` (at most `count`): {"events": [[seq, event], …], "last": the sequence number to
        ask after next time, "lost": events dropped unseen, "more": whether more are waiting, "epoch"}."""
        with self._lock:
            if seq > self.seq:   # numbers from before this queue existed: a master of an earlier drive
                seq = 0
            events = self._events
            while events and events[0][0] <= seq:   # acknowledged: the master has seen them
                events.popleft()
            oldest = events[0][0] if events else self.seq + 1
            batch = [[n, e.to_dict()] for n, e in itertools.islice(events, count)]
            return {"events": batch, "last": batch[-1][0] if batch else self.seq, "lost": max(0, oldest - seq - 1),
                    "more": len(events) > count, "epoch": self.epoch}


class DriveNode:
    """A simulated controller behind a wire: `handle_message(bytes) -> bytes` for any transport."""

    def __init__(self, node: int, service: ControllerService, drive):
        self.node = node
        self.service = service
        self.drive = drive                    # the VirtualDrive: its lock, clock and identity
        self.events = EventQueue()
        service.listeners.append(self.events.put)
        self._answers: OrderedDict[tuple[int, int], bytes] = OrderedDict()
        self._answers_lock = threading.Lock()
        self.last_contact = time.monotonic()  # the drive's link timeout watches this
        self.sessions: set[int] = set()

    # --- requests ---------------------------------------------------------------------------------------
    def handle(self, request: Request) -> Response:
        self.last_contact = time.monotonic()
        op = request.op
        try:
            if op == "events":
                args = request.args
                if args.get("now"):
                    return Response(request.id, True, self.events.now())
                after = int(args.get("after", 0))
                if args.get("epoch") not in (None, self.events.epoch):  # numbers of the drive before a restart
                    after = 0
                return Response(request.id, True, self.events.after(after, int(args.get("max", EVENTS_PER_ANSWER))))
            if op == "advance":
                self.drive.advance(int(request.args.get("ms", 0)))
                return Response(request.id, True, None)
            with self.drive.lock:
                response = self.service.handle(request)
        except (ValueError, TypeError) as exc:
            return Response(request.id, False, error=str(exc))
        except Exception as exc:  # noqa: BLE001 - a malformed request is refused to its master only
            return Response(request.id, False, error=f"{op}: request refused ({type(exc).__name__}: {exc})")
        if op == "identify" and response.ok:
            response.value = {**response.value, **self.drive.identity(self.node)}
        return response

    def handle_message(self, data: bytes) -> bytes:
        """A request message (comms/wire.py) → its answer; a repeated (session, id) gets the cached answer."""
        try:
            request, session = decode_request(data)
        except WireError as exc:
            return encode_response(Response(0, False, error=f"{DAMAGED_REQUEST}: {exc}"))
        key = (session, request.id)
        with self._answers_lock:
            cached = self._answers.get(key)
        if cached is not None:
            self.last_contact = time.monotonic()
            return cached
        self.sessions.add(session)
        answer = encode_response(self.handle(request))
        with self._answers_lock:
            self._answers[key] = answer
            while len(self._answers) > ANSWER_CACHE:
                self._answers.popitem(last=False)
        return answer
