"""PacedClock: the one loop that runs simulated controllers at real time × factor (issue 27 item 4).

A clock thread computes how many 1 ms ticks are due since it started and hands them to its host's `advance(n)`
in bursts of at most `burst`, so a host that fell behind catches up without holding its controllers for long.
Between bursts it idles (`idle`: a host may answer a request meanwhile). `max_lag`: when more ticks than that are
still due after a burst (the process was suspended, the machine starved it), the clock counts a stall and drops
them instead of racing; None catches up on everything. `stop()` ends the thread and waits for it.

The hosts: EmbeddedLink (the IDE's simulator, one controller or APC; catches up on everything, answers its queued
requests while it idles) and the virtual drive (`drive/simulator.py`, 1..32 nodes; drops what is more than
10 bursts behind). The buses (`bus.py`, `apc_bus.py`) step in virtual time and have no clock.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable

BURST = 200   # ticks computed at most in one go when the clock fell behind

# A paced host computes bursts of ticks holding the GIL; with Python's default 5 ms switch interval every request
# from another thread (the UI, a listener) would wait that long for it (262 parameter reads of the Array Editor:
# 0.5 s instead of 0.1 s at 50x real time). 0.5 ms lets a request in within half a tick. Set once per process,
# when the first paced clock starts; never raised (someone may have set it lower).
SWITCH_INTERVAL_S = 0.0005
_switch_interval_set = False


def hand_over_quickly() -> None:
    """The process's GIL switch interval at most SWITCH_INTERVAL_S (once per process)."""
    global _switch_interval_set
    if not _switch_interval_set:
        sys.setswitchinterval(min(sys.getswitchinterval(), SWITCH_INTERVAL_S))
        _switch_interval_set = True


class PacedClock:
    def __init__(self, name: str, factor: float, advance: Callable[[int], None], *,
                 idle: Callable[[], None] | None = None, burst: int = BURST, max_lag: int | None = None,
                 on_stall: Callable[[int], None] | None = None, clock: Callable[[], float] = time.monotonic):
        """`advance(n)` runs n ticks (n may be 0: a round without a due tick) and reports its own faults; it must
        not raise. `idle()` waits about a ms when the host is not behind (default: 1 ms, or until stopped).
        `on_stall(dropped)` hears of each stall; `clock` is the wall clock in seconds (tests replace it)."""
        if not factor > 0:
            raise ValueError(f"realtime factor {factor}: must be above 0")
        self.name = name
        self.factor = factor
        self._advance = advance
        self._idle = idle or self._wait_a_tick
        self.burst = burst
        self.max_lag = max_lag
        self._on_stall = on_stall
        self._clock = clock
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._start = 0.0
        self.ticks = 0            # ticks handed to the host (and dropped ones) since the start
        self.stalls = 0           # times the clock dropped ticks instead of catching up
        self.dropped = 0          # ticks dropped in all

    @property
    def stopping(self) -> bool:
        return self._stop.is_set()

    @property
    def running(self) -> bool:
        return not self._stop.is_set() and self._thread is not None and self._thread.is_alive()

    def start(self) -> None:
        hand_over_quickly()
        self._start = self._clock()
        self._thread = threading.Thread(target=self._run, name=self.name, daemon=True)
        self._thread.start()

    def stop(self, timeout: float = 2.0) -> None:
        self._stop.set()
        if self._thread is not None and self._thread is not threading.current_thread():
            self._thread.join(timeout=timeout)

    def round(self) -> int:
        """One round: the ticks due now, at most one burst, handed to the host; returns how many."""
        due = int((self._clock() - self._start) * 1000 * self.factor)
        burst = max(0, min(due - self.ticks, self.burst))
        self._advance(burst)
        self.ticks += burst
        behind = due - self.ticks
        if self.max_lag is not None and behind > self.max_lag:
            self.ticks = due
            self.stalls += 1
            self.dropped += behind
            if self._on_stall is not None:
                self._on_stall(behind)
        return burst

    def _wait_a_tick(self) -> None:
        self._stop.wait(0.001)

    def _run(self) -> None:
        while not self._stop.is_set():
            if self.round() < self.burst:   # not behind: wait for the next tick
                self._idle()
