"""EmbeddedBus: several simulated controllers in this process, by node id, on one master signal.

The bus wraps a kernel `Simulation` (kernel/simulation.py: 1..32 controllers, lockstep, one virtual master or one
external master encoder shared by all) and gives every node its own `Link` carrying the ordinary requests and
events — like controllers "that all share the same network connection, (e.g. in a field bus)" (DG 2404). Time is
common: `advance` on any node's link (or on the bus) advances every node, tick by tick. Synchronous only: the
caller moves virtual time, as fast as Python goes and fully deterministic (like EmbeddedLink without a thread).
"""

from __future__ import annotations

import threading
from collections.abc import Iterable, Mapping
from typing import Any, Generic, Protocol, TypeVar

from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError, Request
from motiontool.controller.embedded import HostedService
from motiontool.controller.service import ControllerService
from motiontool.kernel.master import MasterConfig
from motiontool.kernel.plant import PlantConfig
from motiontool.kernel.simulation import Simulation


class SharedClock(Protocol):
    """What a NodeLink needs of its bus (EmbeddedBus, apc_bus.ApcLineBus): one clock, one request at a time."""

    closed: bool
    lock: threading.RLock

    def advance(self, ms: int) -> None: ...


ServiceT = TypeVar("ServiceT", bound=HostedService)


class NodeLink(Link, Generic[ServiceT]):
    """The link to one node of an EmbeddedBus (or a CTSync line); `service` is the node's."""

    kind = "embedded"

    def __init__(self, bus: SharedClock, node: int, service: ServiceT):
        super().__init__()
        self.bus = bus
        self.node = node
        self.service = service
        service.listeners.append(self._publish)

    @property
    def alive(self) -> bool:
        return not self.bus.closed

    @property
    def virtual_time(self) -> bool:
        return True

    def request(self, request: Request) -> Any:
        if self.bus.closed:
            raise LinkError("Lost connection: the simulated controllers have stopped")
        with self.bus.lock:  # one request in the simulation at a time, whichever thread asks
            if request.op == "advance":  # one clock for the whole bus
                self.bus.advance(int(request.args.get("ms", 0)))
                return None
            return self.service.handle(request).result()


class EmbeddedBus:
    def __init__(self, nodes: Iterable[int] | Mapping[int, PlantConfig | None] = (1,), *,
                 master_node: int | None = None, master: MasterConfig | None = None):
        self.simulation = Simulation(nodes, master_node=master_node, master=master)
        self.lock = threading.RLock()
        self.closed = False
        self.links: dict[int, NodeLink[ControllerService]] = {}
        for node in self.simulation.nodes:
            link = NodeLink(self, node, ControllerService(self.simulation[node]))
            self.simulation.set_ticker(node, link.service.tick, link.service.adds_nothing)
            self.links[node] = link

    @property
    def nodes(self) -> list[int]:
        return self.simulation.nodes

    def link(self, node: int) -> NodeLink[ControllerService]:
        self.simulation[node]  # ValueError naming an unknown node
        return self.links[node]

    def advance(self, ms: int) -> None:
        with self.lock:
            self.simulation.run_for(ms)

    def close(self) -> None:
        self.closed = True
