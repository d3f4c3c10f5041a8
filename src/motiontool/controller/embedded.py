"""EmbeddedLink: the simulated controller inside this process.

Two ways to run (docs/decisions.md, "EmbeddedLink threading"):
- synchronous (default for the CLI and tests): virtual time moves only when the caller asks (`advance`),
  as fast as Python goes; fully deterministic;
- threaded (the IDE): a kernel thread paces virtual time at real time × factor. Requests are queued to
  that thread, so the kernel is only ever touched by one thread. A thread, not a process: the kernel's
  tick is short and the GUI needs the same requests either way; a process would add serialisation on
  every streamed sample for no gain at 1× real time.
"""

from __future__ import annotations

import queue
import sys
import threading
import time
from collections.abc import Callable
from typing import Any, Protocol

from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError, LinkEvent, Request, Response
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
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._event_queue: list[LinkEvent] = []
        self._lock = threading.RLock()   # synchronous: one request in the kernel at a time, whichever thread asks
        if realtime_factor is not None:
            # The kernel thread computes bursts of ticks while holding the GIL; with Python's default 5 ms
            # switch interval every request from the UI thread would wait that long (262 parameter reads of
            # the Array Editor: 0.5 s instead of 0.1 s at 50x real time).
            sys.setswitchinterval(min(sys.getswitchinterval(), 0.0005))
            self._thread = threading.Thread(target=self._run, name="mco305-kernel", daemon=True)
            self._thread.start()

    @property
    def alive(self) -> bool:
        return not self._stop.is_set() and (self._thread is None or self._thread.is_alive())

    @property
    def virtual_time(self) -> bool:
        return self._thread is None

    def request(self, request: Request) -> Any:
        if not self.alive:
            raise LinkError("Lost connection: the simulated controller has stopped")
        if self._thread is None:
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

    # --- kernel thread ---------------------------------------------------------------------------------
    def _run(self) -> None:
        factor = self.realtime_factor
        assert factor is not None  # the kernel thread runs only for a paced link
        start = time.monotonic()
        ticks = 0
        if isinstance(self.service, ControllerService):   # the MCO 305's PRINT output (an APC prints none)
            self.service.controller.output_per_tick = PRINT_LINES_PER_MS
        while not self._stop.is_set():
            while True:
                try:
                    request, done = self._requests.get_nowait()
                except queue.Empty:
                    break
                done.put(self.service.handle(request))
            due = int((time.monotonic() - start) * 1000 * factor)
            burst = min(due - ticks, 200)
            try:
                for _ in range(burst):
                    self.service.tick()
            except Exception as exc:  # noqa: BLE001 - report it, keep the controller reachable
                self._publish(LinkEvent("message", int(self.service.controller.time_ms),
                                        f"internal simulator fault: {type(exc).__name__}: {exc}"))
            ticks += burst
            if burst < 200:  # idle until the next tick is due, but answer a request at once (UI latency)
                try:
                    request, done = self._requests.get(timeout=0.002)
                except queue.Empty:
                    continue
                done.put(self.service.handle(request))

    def close(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
