"""TESTSETP recording (DG 7121-7135, 4668-4700): SYSVAR values sampled every n ms into an array or
dynamic memory, one time or cyclic. Samples are stored interleaved: index 1, 2, …, k of sample 1, then
of sample 2 … (docs/decisions.md)."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

from motiontool.kernel.errors import ControllerError
from motiontool.kernel.vm import ArrayRef

MAX_INDICES = 20            # DG 11858-11862: error 195
DYNAMIC_MEMORY = 200_000    # values the simulator's dynamic memory holds (error 194 beyond)


@dataclass
class Recording:
    interval_ms: int
    indices: list[int]
    array: ArrayRef | None          # None = dynamic memory
    cyclic: bool
    limit: int                      # samples to take
    start_ms: int
    samples: deque = field(default_factory=deque)  # bounded by `limit`: cyclic recordings drop the oldest
    running: bool = True
    countdown: int = 0
    taken: int = 0

    @property
    def name(self) -> str:
        return self.array.name if self.array is not None else "DYNMEM"


class Recorder:
    def __init__(self) -> None:
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
        self.active = Recording(self.interval_ms, list(self.indices), self.array, self.cyclic, limit, now_ms,
                                deque(maxlen=limit))
        self.recordings.append(self.active)

    def stop(self, method: int) -> None:
        if method != 0:
            raise ControllerError(183, f"TESTSTOP {method}: only 0 (stop immediately) is known")
        if self.active is not None:
            self.active.running = False
            self.active = None

    def sample(self, read) -> None:
        """Called every tick; read(index) gives a SYSVAR value."""
        rec = self.active
        if rec is None:
            return
        if rec.countdown > 0:
            rec.countdown -= 1
            return
        rec.countdown = rec.interval_ms - 1
        row = [read(i) for i in rec.indices]
        if len(rec.samples) >= rec.limit and not rec.cyclic:
            rec.running = False
            self.active = None
            return
        rec.samples.append(row)
        if rec.array is not None:  # cyclic recordings overwrite the oldest sample in the array
            k = len(row)
            slot = (rec.taken % rec.limit) * k
            rec.array.data[slot:slot + k] = row
        rec.taken += 1
