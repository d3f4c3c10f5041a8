"""TESTSETP recording (DG 7121-7135, 4668-4700): SYSVAR values sampled every n ms into an array or
dynamic memory, one time or cyclic, by the common sampler (motiontool/sampling.py, decision S34). Samples are
stored interleaved: index 1, 2, …, k of sample 1, then of sample 2 … (decision K4)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

from motiontool.kernel.errors import ControllerError
from motiontool.kernel.vm import ArrayRef
from motiontool.sampling import BoundedStore, Sampler

MAX_INDICES = 20            # DG 11858-11862: error 195
DYNAMIC_MEMORY = 200_000    # values the simulator's dynamic memory holds (error 194 beyond)


@dataclass
class Recording:
    """One TESTSTART: the common sampler (motiontool/sampling.py) reading the indices into a bounded store."""

    indices: list[int]
    array: ArrayRef | None          # None = dynamic memory
    start_ms: int
    sampler: Sampler                # from the first tick after TESTSTART, every interval
    store: BoundedStore             # `limit` sets: cyclic recordings drop the oldest

    @property
    def name(self) -> str:
        return self.array.name if self.array is not None else "DYNMEM"

    @property
    def interval_ms(self) -> int:
        return self.sampler.interval_ms

    @property
    def running(self) -> bool:
        return self.sampler.running

    @property
    def samples(self):
        return self.store.samples

    @property
    def taken(self) -> int:
        return self.store.taken


class Recorder:
    def __init__(self, read: Callable[[int], int]) -> None:
        self.read = read                # SYSVAR index → value, at the moment the kernel's tick samples
        self.interval_ms = 1
        self.indices: list[int] = []
        self.array: ArrayRef | None = None
        self.cyclic = False
        self.recordings: list[Recording] = []
        self.active: Recording | None = None

    def reset_settings(self) -> None:
        """A new program starts with default recording settings; finished recordings stay (newest 20)."""
        self.interval_ms, self.indices, self.array, self.cyclic, self.active = 1, [], None, False, None
        del self.recordings[:-20]

    def set_indices(self, indices: list[int]) -> None:
        if len(indices) > MAX_INDICES:
            raise ControllerError(195, f"{len(indices)} indices")
        self.indices = list(indices)

    def setp(self, interval: int, indices: list[int], array: ArrayRef) -> None:
        """TESTSETP ms vi1 vi2 vi3 arrayname."""
        self.interval_ms = max(1, interval)
        self.set_indices(indices)
        self.array = array

    def start(self, n: int, now_ms: int) -> None:
        if not self.indices:
            raise ControllerError(183, "TESTSTART before TESTSETP/TESTSETINDEX")
        k = len(self.indices)
        capacity = len(self.array.data) // k if self.array is not None else DYNAMIC_MEMORY // k
        if n > capacity and self.array is not None:
            raise ControllerError(171, f"array {self.array.name} holds {capacity} samples, {n} requested")
        if n > capacity:
            raise ControllerError(194, f"{n} samples do not fit in dynamic memory")
        if self.array is None and self.active is not None and self.active.array is None:
            raise ControllerError(194, "TESTSTART repeated while recording into dynamic memory")
        limit = n if n > 0 else capacity
        store = BoundedStore(limit, self.cyclic, self.array, integers=True)  # read_sysvar gives ints
        sampler = Sampler([partial(self.read, i) for i in self.indices], self.interval_ms, store, aligned=False)
        self.active = Recording(list(self.indices), self.array, now_ms, sampler, store)
        self.recordings.append(self.active)

    def stop(self, method: int) -> None:
        if method != 0:
            raise ControllerError(183, f"TESTSTOP {method}: only 0 (stop immediately) is known")
        if self.active is not None:
            self.active.sampler.running = False
            self.active = None

    def sample(self, now_ms: int) -> None:
        """Called every tick while a recording is active (the kernel tests `active` itself, so an idle recorder
        costs nothing)."""
        rec = self.active
        if rec is None:
            return
        rec.sampler.tick(now_ms)
        if not rec.sampler.running:  # full: stop when full (DG 5308)
            self.active = None
