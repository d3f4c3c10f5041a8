"""EmbeddedLink: the simulated controller inside this process.

Two ways to run (docs/decisions.md, "EmbeddedLink threading"):
- synchronous (default for the CLI and tests): virtual time moves only when the caller asks (`advance`),
  as fast as Python goes; fully deterministic;
- threaded (the IDE): a kernel thread (pacing.PacedClock) paces virtual time at real time × factor. Requests
  are queued to that thread, so the kernel is only ever touched by one thread. A thread, not a process: the kernel's
  tick is short and the GUI needs the same requests either way; a process would add serialisation on
  every streamed sample for no gain at 1× real time.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable
from typing import Any, Protocol

from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError, LinkEvent, Request, Response
from motiontool.controller.pacing import PacedClock
from motiontool.controller.service import ControllerService
from motiontool.kernel.controller import Controller
from motiontool.kernel.master import MasterConfig
from motiontool.kernel.plant import PlantConfig

# The threaded link (the IDE's) takes the controller's PRINT output as a serial link would, about one line per ms
# (115 200 baud): a PRINT flood then makes the program wait for its output buffer instead of stalling real time,
# Break and the IDE (decisions K82). The synchronous link (the command line) takes all of it every ms.
PRINT_LINES_PER_MS = 1


class Clocked(Protocol):
    @property
    def time_ms(self) -> float: ...


class HostedService(Protocol):
    """What a host puts behind a Link (EmbeddedLink, a bus's NodeLink): the MCO 305's ControllerService or an
    ApcService."""

    listeners: list[Callable[[LinkEvent], object]]

    @property
    def controller(self) -> Clocked: ...

    def handle(self, request: Request) -> Response: ...

    def tick(self) -> None:
        """One ms of the controller."""


class EmbeddedLink(Link):
    kind = "embedded"

    def __init__(self, plant: PlantConfig | None = None, realtime_factor: float | None = None,
                 master: MasterConfig | None = None, *, service: HostedService | None = None):
        """`service` replaces the MCO 305 (e.g. controller.apc_service.ApcService for an APC)."""
        super().__init__()
        self.service: HostedService = service or ControllerService(Controller(plant, master=master))
        self.service.listeners.append(self._publish)
        self.realtime_factor = realtime_factor
        self._requests: queue.Queue = queue.Queue()
        self._closed = threading.Event()
        self._clock: PacedClock | None = None
        self._event_queue: list[LinkEvent] = []
        self._lock = threading.RLock()   # synchronous: one request in the kernel at a time, whichever thread asks
        if realtime_factor is not None:
            if isinstance(self.service, ControllerService):   # the MCO 305's PRINT output (an APC prints none)
                self.service.controller.output_per_tick = PRINT_LINES_PER_MS
            # a paced link catches up on every tick (no max_lag): its time is the wall's × factor, always
            self._clock = PacedClock("mco305-kernel", realtime_factor, self._advance, idle=self._idle)
            self._clock.start()

    @property
    def alive(self) -> bool:
        return not self._closed.is_set() and (self._clock is None or self._clock.running)

    @property
    def virtual_time(self) -> bool:
        return self._clock is None

    def request(self, request: Request) -> Any:
        if not self.alive:
            raise LinkError("Lost connection: the simulated controller has stopped")
        if self._clock is None:
            with self._lock:
                response = self.service.handle(request)
        else:
            done: queue.Queue = queue.Queue(maxsize=1)
            self._requests.put((request, done))
            try:
                response = done.get(timeout=10.0)
            except queue.Empty:
                raise LinkError("Timeout: no reply from controller") from None
        return response.result()

    # --- kernel thread (the clock's) ------------------------------------------------------------------
    def _advance(self, ticks: int) -> None:
        """One round of the clock: the queued requests, then `ticks` ms of the controller."""
        while True:
            try:
                request, done = self._requests.get_nowait()
            except queue.Empty:
                break
            done.put(self.service.handle(request))
        try:
            for _ in range(ticks):
                self.service.tick()
        except Exception as exc:  # noqa: BLE001 - report it, keep the controller reachable
            self._publish(LinkEvent("message", int(self.service.controller.time_ms),
                                    f"internal simulator fault: {type(exc).__name__}: {exc}"))

    def _idle(self) -> None:
        """Until the next tick is due, but a request is answered at once (UI latency)."""
        try:
            request, done = self._requests.get(timeout=0.002)
        except queue.Empty:
            return
        done.put(self.service.handle(request))

    def close(self) -> None:
        self._closed.set()
        if self._clock is not None:
            self._clock.stop(timeout=2.0)
