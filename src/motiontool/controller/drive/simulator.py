"""The virtual drive's controllers: a kernel `Simulation` (1..32 nodes in lockstep on one master signal) on its own
thread, paced at real time, every node reachable as a `DriveNode` by any number of listener threads.

Thread safety: one lock guards the simulation. The clock thread takes it for every 1 ms tick and requests take it
for their own short work, so a request waits at most one tick of every node and the kernel is never touched by two
threads at once. With ``clock="virtual"`` there is no clock thread: time moves only when a master sends
``advance`` (as in the synchronous embedded link), which makes a run over the wire reproducible to the tick.

Link timeout (FC 300 8-03/8-04, "control word timeout" — the drive watches its bus master): when `timeout_s` is
set and a master that has talked to a node falls silent for that long while the node's program runs, the node
reacts as configured — ``stop`` breaks the program (the axis stops with the maximum deceleration, like [Esc]) —
and queues a message event saying so, which the master reads when it comes back.
"""

from __future__ import annotations

import random
import threading
import time

from motiontool.aposs.image import ProgramImage
from motiontool.comms.protocol import LinkEvent
from motiontool.controller.drive.node import DriveNode
from motiontool.controller.pacing import BURST, PacedClock
from motiontool.controller.service import ControllerService
from motiontool.kernel.master import MasterConfig
from motiontool.kernel.simulation import Simulation

CLOCKS = ("realtime", "virtual")
REACTIONS = ("none", "stop")
MAX_ADVANCE_MS = 60_000   # one `advance` request; `run --link` asks 50 ms at a time
ADVANCE_SLICE_MS = 50     # advanced under the lock at a time


class VirtualDrive:
    def __init__(self, nodes, *, master_node: int | None = None, master: MasterConfig | None = None,
                 clock: str = "realtime", speed: float = 1.0, timeout_s: float | None = None,
                 timeout_reaction: str = "stop"):
        if clock not in CLOCKS:
            raise ValueError(f"clock {clock!r}: choose {' or '.join(CLOCKS)}")
        if timeout_reaction not in REACTIONS:
            raise ValueError(f"timeout reaction {timeout_reaction!r}: choose {' or '.join(REACTIONS)}")
        if not speed > 0:
            raise ValueError(f"speed {speed}: must be above 0")
        self.simulation = Simulation(nodes, master_node=master_node, master=master)
        self.lock = threading.RLock()
        self.clock = clock
        self.speed = speed
        self.timeout_s = timeout_s
        self.timeout_reaction = timeout_reaction
        self.boot_id = random.getrandbits(31)
        self.nodes: dict[int, DriveNode] = {}
        for n in self.simulation.nodes:
            service = ControllerService(self.simulation[n])
            self.simulation.set_ticker(n, service.tick, service.adds_nothing)
            self.nodes[n] = DriveNode(n, service, self)
        self._clock: PacedClock | None = None
        self._timed_out: set[int] = set()

    # --- set-up ---------------------------------------------------------------------------------------
    def node(self, node: int) -> DriveNode:
        if node not in self.nodes:
            raise ValueError(f"no node {node} on this drive (nodes {sorted(self.nodes)})")
        return self.nodes[node]

    def install_program(self, node: int, image: ProgramImage, number: int = 0) -> None:
        """`--node ID:PROGRAM.m`: the program saved as `number` and started once, as Execute would (an Autostart
        program would be executed again and again, DG 2768-2772)."""
        service = self.node(node).service
        with self.lock:
            service.store.save(number, image)
            service.op_start(number)

    def identity(self, node: int) -> dict:
        return {"node": node, "clock": self.clock, "drive": "motiontool virtual drive", "boot": self.boot_id}

    # --- time ------------------------------------------------------------------------------------------
    def advance(self, ms: int) -> None:
        """Virtual clock: `ms` ticks on every node now. A real-time drive refuses: its clock is the wall's."""
        if self.clock != "virtual":
            raise ValueError("advance: this drive runs in real time (start it with --clock virtual to step it)")
        if not 0 <= ms <= MAX_ADVANCE_MS:
            raise ValueError(f"advance: {ms} ms; one request advances 0..{MAX_ADVANCE_MS} ms")
        done = 0
        while done < ms:   # in slices, the lock let go between them: other masters are served meanwhile
            n = min(ADVANCE_SLICE_MS, ms - done)
            with self.lock:
                self.simulation.run_for(n)
            done += n
            self._reset_nodes()

    def start(self) -> None:
        if self.clock == "realtime" and self._clock is None:
            # far behind (a suspended process): the drive drops the missed ticks instead of racing to catch up
            self._clock = PacedClock("virtual-drive-clock", self.speed, self._advance, max_lag=10 * BURST)
            self._clock.start()

    def stop(self) -> None:
        if self._clock is not None:
            self._clock.stop(timeout=2.0)
            self._clock = None

    def _advance(self, ticks: int) -> None:
        """One round of the clock: `ticks` ms of every node, the lock taken per tick (a request waits at most one
        tick), then the link timeout and the nodes' resets."""
        simulation = self.simulation
        for _ in range(ticks):
            with self.lock:
                try:
                    simulation.tick()
                except Exception as exc:  # noqa: BLE001 - report it, keep the drive reachable
                    self._fault(exc)
        self._watch_timeout()
        self._reset_nodes()

    def _reset_nodes(self) -> None:
        """A node that received NMT Reset Node is switched off and on, as Controller ▸ Restart does (N51)."""
        for node in self.nodes.values():
            can = node.service.controller.can
            if can.reset_node_pending:
                with self.lock:
                    can.reset_node_pending = False
                    node.service.op_power_on()

    def _fault(self, exc: Exception) -> None:
        for node in self.nodes.values():
            node.events.put(LinkEvent("message", self.simulation.time_ms,
                                      f"internal simulator fault: {type(exc).__name__}: {exc}"))

    def _watch_timeout(self) -> None:
        if self.timeout_s is None:
            return
        now = time.monotonic()
        for n, node in self.nodes.items():
            silent = now - node.last_contact > self.timeout_s
            if not silent or not node.sessions:
                self._timed_out.discard(n)
                continue
            if n in self._timed_out:
                continue
            self._timed_out.add(n)
            with self.lock:
                controller = node.service.controller
                if controller.program_state != "running":
                    continue
                text = f"link timeout: no request from the master for {self.timeout_s:g} s"
                if self.timeout_reaction == "stop":
                    controller.break_program()
                    text += "; the program was stopped (timeout reaction: stop)"
                else:
                    text += "; the program keeps running (timeout reaction: none)"
                node.events.put(LinkEvent("message", controller.time_ms, text))
