"""The master encoder input of the simulated MCO 305 (kernel-spec a.3, f.4).

The master position is a counter of master quad counts (qc). Its increments come either from a simulated
external master encoder (`MasterConfig`: standing still by default, a constant speed, a ramp or a
speed/time table) or, after PULSVEL, from the virtual master (encoder simulation, CR 3552-3611), whose
signal is fed back as the master input so that MAPOS, MAVEL and the synchronisation behave as with an
external master (CR 3565).

One virtual-master "pulse" is one encoder line = 4 qc: CR 3574-3589 computes PULSACC from "an encoder signal
of 1024 counts/revolution" and 25 revolutions/s (25600 Hz/s), CR 3604-3611 PULSVEL 102400 Hz from 2048
counts/revolution at 50 revolutions/s; "counts per revolution" is the encoder's line count (32-01 ENCODER,
which the controller quadruples to qc, DG 9318-9324 "Encoder resolution * 4"). So PULSVEL v is v * 4 master
qc per second (kernel-spec p.7).

Everything is computed from the tick count; nothing reads the wall clock.
"""

from __future__ import annotations

import math
import random
from collections import deque
from dataclasses import dataclass, fields

QC_PER_PULSE = 4      # one virtual-master pulse = one encoder line = 4 qc (module docstring)
MAVEL_WINDOW_MS = 20  # MAVEL is averaged over 20 ms like AVEL (CR 2175-2195, _GETVEL)


@dataclass
class MasterConfig:
    """Motion of the simulated external master encoder (qc, qc/ms, qc/ms²; default: standing still).

    * `velocity`: constant speed in master qc per ms, reached at once or, with `acceleration` > 0, by a
      linear ramp from standstill at t = 0;
    * `table`: ((t_ms, qc_per_ms), …) sorted by time: the speed is interpolated linearly between the points,
      is the first point's speed before it and the last point's speed after it. A table replaces
      `velocity`/`acceleration`.
    """

    velocity: float = 0.0
    acceleration: float = 0.0
    table: tuple = ()
    start_position_qc: float = 0.0
    jitter: float = 0.0             # ± qc/ms of random speed noise per tick (deterministic from `seed`)
    seed: int = 0
    # a marker sensor on the master side, wired to input 5 (kernel/markers.py MarkerSensor): products every
    # marker_period_qc (or at marker_positions_qc), marker_width_qc long, each displaced by ±marker_jitter_qc
    marker_period_qc: float = 0.0
    marker_offset_qc: float = 0.0
    marker_width_qc: float = 100.0
    marker_positions_qc: tuple = ()
    marker_jitter_qc: float = 0.0

    @classmethod
    def from_mapping(cls, values: dict) -> MasterConfig:
        known = {f.name for f in fields(cls)}
        unknown = set(values) - known
        if unknown:
            raise ValueError(f"unknown master setting(s): {', '.join(sorted(unknown))}")
        values = dict(values)
        if "table" in values:
            values["table"] = tuple((float(t), float(v)) for t, v in values["table"])
        if "marker_positions_qc" in values:
            values["marker_positions_qc"] = tuple(float(p) for p in values["marker_positions_qc"])
        return cls(**values)

    def speed_at(self, t_ms: float) -> float:
        """Speed of the external master encoder at time t (qc/ms)."""
        table = self.table
        if table:
            if t_ms <= table[0][0]:
                return table[0][1]
            for (t0, v0), (t1, v1) in zip(table, table[1:], strict=False):
                if t_ms <= t1:
                    return v0 + (v1 - v0) * (t_ms - t0) / (t1 - t0) if t1 > t0 else v1
            return table[-1][1]
        if self.acceleration > 0:
            return math.copysign(min(abs(self.velocity), self.acceleration * t_ms), self.velocity)
        return self.velocity


class Master:
    """The master position counter (raw qc), its origin (DEFMORIGIN/SETMORIGIN) and the virtual master."""

    def __init__(self, config: MasterConfig | None = None):
        self.config = config or MasterConfig()
        self.position = float(self.config.start_position_qc)  # raw counter, continuous
        self.raw = math.floor(self.position)
        self.origin = 0            # raw qc that is MAPOS 0
        self.velocity = 0.0        # increment of the last tick (qc/ms)
        self.virtual = False       # PULSVEL drives the counter instead of the external encoder
        self.virtual_speed = 0.0   # qc/ms
        self.virtual_target = 0.0  # qc/ms
        self.virtual_acc = 0.0     # qc/ms², 0 = change at once
        self.pending_acc: float | None = None  # PULSACC waits for the next PULSVEL
        self._history: deque[int] = deque([self.raw], maxlen=MAVEL_WINDOW_MS + 1)
        self._noise = random.Random(self.config.seed) if self.config.jitter else None
        # the master input is wired to a signal shared by several controllers (kernel/simulation.py): the increment
        # of this tick of `feed` (a Master ticked before this one) replaces the external encoder's — with
        # `feed_virtual_only` only while feed's virtual master runs (its encoder output); own PULSVEL still wins
        self.feed: Master | None = None
        self.feed_virtual_only = False

    # --- readouts -------------------------------------------------------------------------------------------
    @property
    def mapos(self) -> int:
        return self.raw - self.origin

    @property
    def mavel(self) -> int:
        """qc/s over the last 20 ms (less right after start)."""
        h = self._history
        span = len(h) - 1
        if span <= 0:
            return 0
        return round((h[-1] - h[0]) * 1000 / span)

    def set_velocity_window(self, ms: int) -> None:
        """_GETVEL: MAVEL is averaged over `ms` from now on (CR 2186-2191); the counts seen so far are kept."""
        self._history = deque(self._history, maxlen=ms + 1)

    # --- one tick -------------------------------------------------------------------------------------------
    def tick(self, time_ms: int) -> None:
        # kernel/tick.py repeats the fed counter's case (controller_tick): change both
        if self.virtual:
            v, target, acc = self.virtual_speed, self.virtual_target, self.virtual_acc
            if acc <= 0 or abs(target - v) <= acc:
                v = target
            else:
                v += acc if target > v else -acc
            self.virtual_speed = v
        elif self.feed is not None:
            feed = self.feed
            v = feed.velocity if feed.virtual or not self.feed_virtual_only else 0.0
        else:
            v = self.config.speed_at(time_ms)
            if self._noise is not None:
                v += self._noise.uniform(-self.config.jitter, self.config.jitter)
        self.velocity = v
        self.position = position = self.position + v
        self.raw = raw = math.floor(position)
        self._history.append(raw)

    # --- commands -------------------------------------------------------------------------------------------
    def pulsacc(self, hz_per_s: int) -> None:
        """PULSACC a: acceleration of the virtual master in Hz/s, used from the next PULSVEL (CR 3560-3571)."""
        self.pending_acc = abs(hz_per_s) * QC_PER_PULSE / 1e6

    def pulsvel(self, hz: int) -> None:
        """PULSVEL v: virtual master speed in Hz; after PULSACC 0 it switches the virtual master off."""
        if self.pending_acc == 0.0:
            self.virtual = False
            self.virtual_speed = self.virtual_target = 0.0
            self.pending_acc = None
            return
        if not self.virtual:
            self.virtual = True
            self.virtual_speed = self.velocity  # the counter continues smoothly from its last speed
        if self.pending_acc is not None:
            self.virtual_acc = self.pending_acc
        self.virtual_target = hz * QC_PER_PULSE / 1000.0

    def stop_virtual(self) -> None:
        """[Esc] stops the master simulation (DG 10782)."""
        if self.virtual:
            self.virtual_speed = self.virtual_target = 0.0

    def defmorigin(self) -> None:
        """DEFMORIGIN: the current master position is the master zero (CR 849-859)."""
        self.origin = self.raw

    def setmorigin(self, value: int) -> None:
        """SETMORIGIN value: the zero point of the master is at `value` of the master counter (CR 3969-3983);
        it replaces a DEFMORIGIN, so MAPOS = counter − value."""
        self.origin = value

    def write_position(self, value: int) -> None:
        """SYSVAR[4105] := value: a program-driven master (32-32 MENCODERABSTYPE 5, DG 8370) sets the raw
        counter (SYSVAR 4105 reads and writes the counter, not MAPOS)."""
        delta = value - self.raw
        self.position += delta
        self.raw = value
