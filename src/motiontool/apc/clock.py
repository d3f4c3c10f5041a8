"""When the POS samples of a drive or a CTSync line fall, for whatever runs them against a clock of its own (the
Link service's millisecond, the CLI's and the IDE's runs).

A sample falls one POS period after the one before, the period read before every sample, so a new #81.12 taken
by REINIT acts from the next sample on (L4678-4723): a 2 ms program runs every 2 ms from its first sample after
the REINIT, and [13] never disagrees with the rate the tasks run at. The time slice before a sample (Initial,
Background) runs once; when it lengthens the period (REINIT in Initial) its sample waits for the new period.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol


class Timed(Protocol):
    @property
    def period_ns(self) -> int: ...


class PosClock:
    def __init__(self) -> None:
        self.last_ns = 0          # when the last sample fell, on the owner's clock
        self.sliced = False       # the next sample's time slice has run

    def run_until(self, now_ns: int, timed: Timed, time_slice: Callable[[], object],
                  sample: Callable[[], object]) -> None:
        """Run the samples due by `now_ns`, each after its time slice; `timed.period_ns` is read for each."""
        while self.last_ns + timed.period_ns <= now_ns:
            if not self.sliced:
                time_slice()
                self.sliced = True
            period = timed.period_ns
            if self.last_ns + period > now_ns:      # the slice lengthened the period: the sample waits for it
                return
            self.sliced = False
            sample()
            self.last_ns += period
