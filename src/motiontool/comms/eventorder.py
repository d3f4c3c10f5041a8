"""The events of several nodes' links in controller-time order.

Each link delivers its own node's events in order, but the links are polled one after another (and by their own
poller threads), so two nodes' PRINT lines of the same millisecond can arrive either way round. The embedded bus
prints them in (time, node) order; a run over a wire must print exactly the same. Events are held here and
released up to a time that every link is known to have delivered (the drive's clock read before the links were
flushed), in (time, node, arrival) order.
"""

from __future__ import annotations

import heapq
import itertools
import math
import threading
from collections.abc import Callable

from motiontool.comms.protocol import LinkEvent


class TimeOrder:
    def __init__(self, deliver: Callable[[int, LinkEvent], None]):
        self._deliver = deliver
        self._lock = threading.Lock()
        self._pending: list[tuple[int, int, int, LinkEvent]] = []
        self._arrival = itertools.count()

    def add(self, node: int, event: LinkEvent) -> None:
        """Called from any thread (a link's poller or the run loop's flush)."""
        with self._lock:
            heapq.heappush(self._pending, (event.time_ms, node, next(self._arrival), event))

    def release(self, until: float = math.inf) -> None:
        """Deliver every held event of time <= `until` (all of them by default), earliest first; a node's own
        events keep their order (the arrival number breaks ties)."""
        with self._lock:
            ready = []
            while self._pending and self._pending[0][0] <= until:
                ready.append(heapq.heappop(self._pending))
        for _, node, _, event in ready:
            self._deliver(node, event)
