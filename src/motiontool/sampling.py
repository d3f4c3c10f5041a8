"""The one sampler of every scope mode (issue 27 item 4): signal readers, an interval and a sink. Free Run on the MCO
and the APC (controller/sampling.py's packet sink), Single Shot (controller/scope_recording.py) and the program's
TESTSETP recorder (kernel/recorder.py) use it. Its owner calls `tick(now)` once per millisecond where that mode
samples (decision S33, S34), so it knows no controller: it sits below the kernel and the APC (no Qt, no I/O).

Two clocks, as the modes had them: a stream samples the milliseconds that are a multiple of its interval (so
packets from two nodes line up); a recording samples the first millisecond after its start, then every interval
(TESTSETP, DG 7121-7135; Single Shot records "in a TESTSETP array", DG 4668).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from typing import Any, Protocol

Reader = Callable[[], Any]


class Sink(Protocol):
    def full(self) -> bool: ...

    def add(self, now: int, row: list) -> None: ...


class BoundedStore:
    """At most `limit` sample sets with their times: cyclic drops the oldest, else the store is full. With a user
    array the sets also occupy it, interleaved as TESTSETP stores them (decision K4), rounded to integers unless the
    readers give `integers` already (SYSVARs: rounding them cost an armed TESTSETP a tenth of its tick)."""

    def __init__(self, limit: int, cyclic: bool, array: Any = None, *, integers: bool = False):
        self.limit = limit
        self.cyclic = cyclic
        self.array = array
        self.integers = integers
        self.samples: deque = deque(maxlen=limit)
        self.times: deque = deque(maxlen=limit)
        self.taken = 0

    def full(self) -> bool:
        return len(self.samples) >= self.limit and not self.cyclic  # stop when full (DG 5308)

    def add(self, now: int, row: list) -> None:
        self.samples.append(row)
        self.times.append(now)
        if self.array is not None:  # cyclic recordings overwrite the oldest set in the array
            k = len(row)
            slot = (self.taken % self.limit) * k
            self.array.data[slot:slot + k] = row if self.integers else [int(round(v)) for v in row]
        self.taken += 1


class Sampler:
    """Reads `readers` every `interval_ms` into `sink`; `aligned`: on multiples of the interval (a stream), else
    from the first tick on (a recording). A full sink stops the sampler: the new set is not read."""

    def __init__(self, readers: list[Reader], interval_ms: int, sink: Sink, *, aligned: bool):
        self.readers = list(readers)
        self.interval_ms = max(1, int(interval_ms))
        self.sink = sink
        self.aligned = aligned
        self.running = True
        self.countdown = 0

    def tick(self, now: int) -> None:
        """Called once per millisecond with the controller's clock."""
        if not self.running:
            return
        if self.aligned:
            if now % self.interval_ms:
                return
        elif self.countdown > 0:
            self.countdown -= 1
            return
        else:
            self.countdown = self.interval_ms - 1
        if self.sink.full():
            self.running = False
            return
        self.sink.add(now, [read() for read in self.readers])
