"""The Single Shot recording the oscilloscope configures on the controller (DG 4662-4674, 5287-5324).

It is the TESTSETP recorder driven from the link instead of from a program: storage in dynamic memory or a
user array, cyclic or stop-when-full, a fixed count of sample sets or "fill available space", an interval in
ms. It belongs to the link, not to the program, so it survives a program start, [Esc] and the program's end
("Aborting the program does not stop the Oscilloscope from recording", DG 5859).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

from motiontool.kernel.errors import ControllerError
from motiontool.kernel.recorder import DYNAMIC_MEMORY, MAX_INDICES
from motiontool.kernel.vm import ArrayRef
from motiontool.sampling import BoundedStore, Sampler


@dataclass
class ScopeRecording:
    signals: list[str]
    destination: str            # "DYNMEM" or the name of a user array
    start_ms: int
    sampler: Sampler            # from the first tick after the start, every interval
    store: BoundedStore

    @property
    def running(self) -> bool:
        return self.sampler.running

    def status(self) -> dict:
        store = self.store
        return {"running": self.running, "samples": len(store.samples), "limit": store.limit, "taken": store.taken,
                "interval_ms": self.sampler.interval_ms}

    def upload(self) -> dict:
        store = self.store
        return {"name": f"Single Shot ({self.destination})", "interval_ms": self.sampler.interval_ms,
                "start_ms": self.start_ms, "signals": list(self.signals), "time_ms": list(store.times),
                "samples": [list(s) for s in store.samples], "taken": store.taken}


def configure(controller, signals: list[str], readers: list[Callable], interval_ms: int, destination: str,
              cyclic: bool, count: int) -> ScopeRecording:
    """Check the set-up as TESTSTART would (errors 195, 171, 194) and return a started recording."""
    if not signals:
        raise ValueError("a Single Shot recording needs at least one signal")
    if len(signals) > MAX_INDICES:
        raise ControllerError(195, f"{len(signals)} values to record (at most {MAX_INDICES})")
    if int(interval_ms) < 1:
        raise ValueError(f"sample interval {interval_ms} ms: at least 1 ms")
    if int(count) < 0:
        raise ValueError(f"sample count {count}: 0 (fill available space) or more")
    k = len(signals)
    array: ArrayRef | None = None
    if str(destination).upper() == "DYNMEM":
        destination = "DYNMEM"
        capacity = DYNAMIC_MEMORY // k
    else:
        found = [a for a in controller.arrays.arrays if a.name.upper() == str(destination).upper()]
        if not found:
            raise ValueError(f"no array '{destination}' on the controller (the program must DIM it first)")
        array = found[0]
        capacity = len(array.data) // k
    if count > capacity:
        raise ControllerError(171 if array is not None else 194,
                              f"{count} sample sets do not fit in {destination} ({capacity} fit)")
    limit = int(count) if count > 0 else capacity
    store = BoundedStore(limit, bool(cyclic), array)
    sampler = Sampler([partial(read, controller) for read in readers], int(interval_ms), store, aligned=False)
    return ScopeRecording(list(signals), destination, controller.time_ms, sampler, store)
