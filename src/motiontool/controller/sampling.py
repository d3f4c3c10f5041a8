"""The controller's side of the common sampler (motiontool/sampling.py, issue 27 item 4): the Free Run stream's
packet sink for the MCO and the APC. The services call `tick(now)` once per millisecond after the controller's tick,
so Free Run and Single Shot sample the state that millisecond ends with (decision S33); the program's TESTSETP
recorder drives the same sampler from inside the kernel's tick (kernel/recorder.py, decision S34).
"""

from __future__ import annotations

from collections.abc import Callable

from motiontool.sampling import Reader, Sampler


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


def stream(names: list[str], readers: list[Reader], interval_ms: int,
           publish: Callable[[dict], object]) -> tuple[Sampler, PacketSink]:
    """A Free Run stream: the sampler and its packet sink (to flush when the stream changes)."""
    interval = max(1, int(interval_ms))
    sink = PacketSink(names, interval, publish)
    return Sampler(readers, interval, sink, aligned=True), sink
