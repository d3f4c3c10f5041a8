"""Triggered capture with pre-trigger, beyond the manual (peers.md: halscope; "a real oscilloscope trigger
mode that stops after N points", MCUViewer #108).

A capture watches one signal of a stream. States follow halscope's sampler: PRE_TRIG (filling the
pre-trigger samples) → TRIG_WAIT → POST_TRIG → DONE. The window kept is `pre` samples before the trigger
sample and `post` samples from it on. Level triggers fire on a crossing in the chosen direction; a bit-pattern
trigger fires when (value & mask) becomes equal to `pattern`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

EDGES = ("rising", "falling", "either")


@dataclass
class Trigger:
    signal: int = 0             # column in the stream's value rows
    level: float = 0.0
    edge: str = "rising"        # rising | falling | either | pattern
    mask: int = 0
    pattern: int = 0
    pre: int = 100
    post: int = 900

    def __post_init__(self):
        if self.edge not in EDGES + ("pattern",):
            raise ValueError(f"trigger edge '{self.edge}': one of {', '.join(EDGES)}, pattern")
        if self.pre < 0 or self.post < 1:
            raise ValueError(f"pre-trigger {self.pre} / post-trigger {self.post}: pre ≥ 0, post ≥ 1")

    def fire_index(self, previous: float | None, y: np.ndarray) -> int | None:
        """Index in y of the first sample that fires the trigger; previous is the sample before y[0]."""
        if y.size == 0:
            return None
        if previous is None:
            prev = y[:-1]
            cur = y[1:]
            offset = 1
        else:
            prev = np.concatenate([[previous], y[:-1]])
            cur = y
            offset = 0
        if self.edge == "pattern":
            hit_cur = (cur.astype(np.int64) & self.mask) == self.pattern
            hit_prev = (prev.astype(np.int64) & self.mask) == self.pattern
            hits = np.nonzero(hit_cur & ~hit_prev)[0]
        else:
            up = (prev < self.level) & (cur >= self.level)
            down = (prev > self.level) & (cur <= self.level)
            hits = np.nonzero(up if self.edge == "rising" else down if self.edge == "falling" else up | down)[0]
        return int(hits[0]) + offset if hits.size else None


class Capture:
    """Feed blocks of (times, rows); when `done`, `result()` gives the window around the trigger."""

    def __init__(self, trigger: Trigger, columns: int):
        self.trigger = trigger
        self.columns = columns
        self.reset()

    def reset(self) -> None:
        self.state = "PRE_TRIG" if self.trigger.pre > 0 else "TRIG_WAIT"
        self._t = np.empty(0)
        self._v = np.empty((0, self.columns))
        self._trigger_at: int | None = None
        self.trigger_time: float | None = None

    @property
    def done(self) -> bool:
        return self.state == "DONE"

    def feed(self, times, rows) -> None:
        if self.done:
            return
        times = np.asarray(times, dtype=float)
        rows = np.asarray(rows, dtype=float).reshape(len(times), self.columns)
        tr = self.trigger
        start = self._t.size  # index of the first new sample
        self._t = np.concatenate([self._t, times])
        self._v = np.concatenate([self._v, rows])
        if self.state in ("PRE_TRIG", "TRIG_WAIT"):
            # search only where enough pre-trigger history exists (a halscope PRE_TRIG must fill first)
            first = max(start, tr.pre)
            if first < self._t.size:
                previous = self._v[first - 1, tr.signal] if first > 0 else None
                hit = tr.fire_index(previous, self._v[first:, tr.signal])
                if hit is not None:
                    self._trigger_at = first + hit
                    self.trigger_time = float(self._t[self._trigger_at])
                    self.state = "POST_TRIG"
                else:
                    self.state = "TRIG_WAIT" if self._t.size >= tr.pre else "PRE_TRIG"
            # keep only the history a trigger can still need
            if self._trigger_at is None and self._t.size > tr.pre + 1:
                cut = self._t.size - tr.pre - 1
                self._t, self._v = self._t[cut:], self._v[cut:]
        if self.state == "POST_TRIG":
            assert self._trigger_at is not None  # set together with POST_TRIG
            if self._t.size - self._trigger_at >= tr.post:
                self.state = "DONE"

    def result(self) -> tuple[np.ndarray, np.ndarray]:
        if not self.done:
            raise RuntimeError(f"capture not complete (state {self.state})")
        i = self._trigger_at
        assert i is not None  # DONE comes only after POST_TRIG
        lo = max(0, i - self.trigger.pre)
        return self._t[lo:i + self.trigger.post], self._v[lo:i + self.trigger.post]
