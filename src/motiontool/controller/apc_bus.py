"""ApcLineBus: a CTSync line of simulated APC drives in this process, one Link per node (nodes 1..N).

Like `EmbeddedBus` for the MCO 305: time is common — `advance` on any node's link (or on the bus) runs the whole
line, sample by sample, so every node's CTSyncGetSlaveReferences sees the master's data of the sample before
(apc/ctsync.py). Synchronous only, deterministic.
"""

from __future__ import annotations

import threading
from collections.abc import Iterable

from motiontool.apc.clock import PosClock
from motiontool.apc.ctsync import CTSyncLine
from motiontool.apc.drive import ApcDrive
from motiontool.controller.apc_service import ApcService
from motiontool.controller.bus import NodeLink


class ApcLineBus:
    def __init__(self, drives: Iterable[ApcDrive], *, four_wire: bool = False):
        self.line = CTSyncLine(drives, four_wire=four_wire)
        self.lock = threading.RLock()   # NodeLink: one request on the line at a time, whichever thread asks
        self.closed = False
        self._clock = PosClock()
        self.links: dict[int, NodeLink[ApcService]] = {}
        for node, drive in enumerate(self.line.drives, start=1):
            # the bus, not the node, runs the POS samples and time slices: a node's service keeps its clock and
            # streams
            self.links[node] = NodeLink(self, node, ApcService(drive, runs_samples=False))

    @property
    def nodes(self) -> list[int]:
        return list(self.links)

    def link(self, node: int) -> NodeLink[ApcService]:
        if node not in self.links:
            raise ValueError(f"node {node} is not on the line (nodes {self.nodes})")
        return self.links[node]

    def advance(self, ms: int) -> None:
        """`ms` milliseconds of the line: its samples, the line's period read before each (apc/clock.py), every
        node's Initial/Background slice before each sample."""
        services = [link.service for link in self.links.values()]

        def time_slice() -> None:
            for service in services:
                service.slice()
        for _ in range(int(ms)):
            now = (services[0].time_ms + 1) * 1_000_000
            self._clock.run_until(now, self.line, time_slice, self.line.tick)
            for service in services:
                service.tick()

    def close(self) -> None:
        self.closed = True
