"""Several simulated MCO 305 sharing one master signal: the multi-axis projects of the manual (issue 5).

"Virtual master is an encoder simulation which serves as a common master signal for synchronization of up-to
32 axes" (DG 254); "a multi-axis system where multiple slaves are following the velocity or position of a
common master signal" (DG 796); the wiring: "One encoder is connected to multiple MCO 305" or "The virtual
master output of one MCO 305 is connected to multiple MCO 305" (DG 8520-8521).

A `Simulation` holds 1..32 controllers by node id (the controller ID of the bus), each with its own parameters,
arrays, program and plant, and advances them in lockstep, one 1 ms tick at a time. The shared master signal is
either

* the virtual master of one node (`master_node`): its PULSVEL/PULSACC output (kernel/master.py) is wired to the
  master input of every other node; the master node sees its own signal as master input as always (CR
  3564-3565); or
* one simulated external master encoder (`master`, a MasterConfig; the default when no `master_node` is
  given), wired to the master input of every node.

What travels on the wire is the signal — this tick's increment in master qc — not a position: every node keeps
its own master counter, so MAPOS, MAVEL, DEFMORIGIN/SETMORIGIN and SYSVAR[4105] stay per node, and two nodes
that start together count the same MAPOS. A node that runs PULSVEL itself feeds its own virtual master back to
its own input and stops following the wire until PULSACC 0 + PULSVEL switches it off (docs/decisions.md).

Tick order: the shared encoder (or the master node) first, then the other nodes in ascending node id, so a slave
sees in tick t the master increment of tick t, as on a single controller. While every node is in a CAM line's
steady state, `run_for` runs stretches of ticks node by node (kernel/steady_line.py) with the same results.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping

from motiontool.kernel import steady_line
from motiontool.kernel.canbus import CanBus
from motiontool.kernel.canport import CANNR
from motiontool.kernel.controller import Controller
from motiontool.kernel.master import Master, MasterConfig
from motiontool.kernel.plant import PlantConfig

MAX_NODES = 32   # "common master signal for synchronization of up-to 32 axes" (DG 254)
NODE_IDS = range(1, MAX_NODES + 1)


def check_node_id(node) -> int:
    """A node id as an int in 1..32, else ValueError naming it."""
    if isinstance(node, bool) or not isinstance(node, int):
        raise ValueError(f"node id {node!r} is not a whole number 1..{MAX_NODES}")
    if node not in NODE_IDS:
        raise ValueError(f"node id {node} is outside 1..{MAX_NODES}")
    return node


def check_node_ids(nodes: Iterable) -> list[int]:
    """Validated node ids in the given order; duplicates and ids outside 1..32 are a ValueError naming the id."""
    seen: list[int] = []
    for node in nodes:
        check_node_id(node)
        if node in seen:
            raise ValueError(f"node id {node} is given twice")
        seen.append(node)
    if not seen:
        raise ValueError("a simulation needs at least one node id")
    return seen


class Simulation:
    """1..32 controllers by node id on one master signal, advanced in lockstep (module docstring)."""

    def __init__(self, nodes: Iterable[int] | Mapping[int, PlantConfig | None] = (1,), *,
                 master_node: int | None = None, master: MasterConfig | None = None):
        plants = dict(nodes) if isinstance(nodes, Mapping) else None
        ids = sorted(check_node_ids(list(nodes)))
        if master_node is not None:
            check_node_id(master_node)
            if master_node not in ids:
                raise ValueError(f"master node id {master_node} is not one of the nodes {ids}")
        self.master_node = master_node
        self.master_config = master or MasterConfig()
        self.time_ms = 0
        self.controllers: dict[int, Controller] = {
            n: Controller(plants.get(n) if plants else None, master=self.master_config) for n in ids}
        # the shared external master encoder: counts like every node's own counter, ticks before them
        self.encoder: Master | None = None
        if master_node is None:
            self.encoder = Master(self.master_config)
            for c in self.controllers.values():
                c.master.feed = self.encoder
        else:  # the master node's encoder output: its virtual master's increment while PULSVEL runs, else nothing
            source = self.controllers[master_node].master
            for n, c in self.controllers.items():
                if n != master_node:
                    c.master.feed, c.master.feed_virtual_only = source, True
        # one CAN bus for all (kernel/canbus.py); every controller's CAN node id (CANNR) is its node id (K101)
        self.can_bus = CanBus()
        for n, c in self.controllers.items():
            c.params.values[CANNR] = c.params.saved[CANNR] = n
            c.can.attach(self.can_bus)
        self.order = ([master_node] if master_node is not None else []) + [n for n in ids if n != master_node]
        self._tickers: dict[int, Callable[[], None]] = {n: self.controllers[n].tick for n in self.order}
        self._sequence = [self._tickers[n] for n in self.order]
        self._steady: dict[int, Callable[[], bool]] = {}  # a replaced ticker's: it adds nothing to the tick now

    # --- access ------------------------------------------------------------------------------------------
    @property
    def nodes(self) -> list[int]:
        return sorted(self.controllers)

    def __getitem__(self, node: int) -> Controller:
        try:
            return self.controllers[node]
        except KeyError:
            raise ValueError(f"node id {node!r} is not in this simulation (nodes {self.nodes})") from None

    def __len__(self) -> int:
        return len(self.controllers)

    def __iter__(self):
        return iter(self.nodes)

    def set_ticker(self, node: int, tick: Callable[[], None], steady: Callable[[], bool] | None = None) -> None:
        """Replace what advances one node by one tick (a comms ControllerService.tick that also streams and
        runs the Restart mechanism); it must tick that node's controller exactly once. `steady` tells when it
        adds nothing to the controller's tick (then stretches of ticks may run without it); without it, never."""
        self[node]  # ValueError naming an unknown node
        self._tickers[node] = tick
        self._steady[node] = steady or (lambda: False)
        self._sequence = [self._tickers[n] for n in self.order]

    def steady_tickers(self) -> list[Callable[[], bool]]:
        return list(self._steady.values())

    # --- time --------------------------------------------------------------------------------------------
    def tick(self) -> None:
        """One millisecond on every node: the shared master signal first, then the nodes (module docstring)."""
        self.time_ms += 1
        if self.encoder is not None:
            self.encoder.tick(self.time_ms)
        self.can_bus.deliver()
        for tick in self._sequence:
            tick()

    def run_for(self, ms: int, until: Callable[[], bool] | None = None) -> None:
        ms = int(ms)
        if until is None:
            self._run(ms)
            return
        for _ in range(ms):
            self.tick()
            if until():
                return

    def _run(self, ms: int) -> None:
        """`ms` ticks, in stretches where the line is steady; after a failed try the next waits 1, 2, 4 … 64 ticks
        (a line that is not steady pays for few tries)."""
        wait = 1
        while ms > 0:
            done = steady_line.run(self, ms) if ms >= steady_line.MIN_TICKS else 0
            if done:
                ms -= done
                wait = 1
                if ms and done < steady_line.MAX_TICKS:  # the stretch ended before a tick that runs generally
                    self.tick()
                    ms -= 1
                continue
            for _ in range(min(wait, ms)):
                self.tick()
            ms -= min(wait, ms)
            wait = min(2 * wait, 64)
