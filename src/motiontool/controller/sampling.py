"""One sampler for the scope modes the controller's side serves (issue 27 item 4): signal readers, an interval and
a sink. The MCO's and the APC's Free Run stream (`PacketSink`) and the Single Shot recording (`BoundedStore`,
controller/scope_recording.py) use it; the services call `tick(now)` once per millisecond after the controller's
tick, so every mode samples the state that millisecond ends with.

Two clocks, as the modes had them: a stream samples the milliseconds that are a multiple of its interval (so
packets from two nodes line up); a recording samples the first millisecond after its start, then every interval,
as the TESTSETP recorder does (Single Shot records "in a TESTSETP array", DG 4668). The program's own TESTSETP
recorder stays in kernel/recorder.py: it samples inside the kernel's tick (before the CAN and the program slice)
and the kernel never imports the controller's side.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from typing import Any, Protocol

Reader = Callable[[], Any]


class Sink(Protocol):
    def full(self) -> bool: ...

    def add(self, now: int, row: list) -> None: ...


class PacketSink:
    """A stream's samples, sent as one "samples" packet every ~20 ms (docs/link-protocol.md)."""

    def __init__(self, names: list[str], interval_ms: int, publish: Callable[[dict], object]):
        self.names = list(names)
        self.size = max(1, 20 // interval_ms)
        self.publish = publish
        self.times: list[int] = []
        self.values: list[list] = []

    def full(self) -> bool:
        return False  # a stream never ends by itself: the packets go out

    def add(self, now: int, row: list) -> None:
        self.times.append(now)
        self.values.append(row)
        if len(self.times) >= self.size:
            self.flush()

    def flush(self) -> None:
        if self.times:
            data = {"signals": list(self.names), "time_ms": self.times, "values": self.values}
            self.times, self.values = [], []
            self.publish(data)


class BoundedStore:
    """At most `limit` sample sets with their times: cyclic drops the oldest, else the store is full. With a user
    array the sets also occupy it, interleaved as a TESTSETP recording (kernel/recorder.py), rounded to integers."""

    def __init__(self, limit: int, cyclic: bool, array: Any = None):
        self.limit = limit
        self.cyclic = cyclic
        self.array = array
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
            self.array.data[slot:slot + k] = [int(round(v)) for v in row]
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


def stream(names: list[str], readers: list[Reader], interval_ms: int,
           publish: Callable[[dict], object]) -> tuple[Sampler, PacketSink]:
    """A Free Run stream: the sampler and its packet sink (to flush when the stream changes)."""
    interval = max(1, int(interval_ms))
    sink = PacketSink(names, interval, publish)
    return Sampler(readers, interval, sink, aligned=True), sink
