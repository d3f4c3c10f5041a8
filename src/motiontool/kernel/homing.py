"""HOME and INDEX as phase machines driven by the axis tick (CR 1478-1520, 1655-1680; DG 9191-9298).

HOME_TYPE 0: to the switch at HOME_VEL, reverse, leave it at HOME_VEL/10, then on to the next index pulse;
1: as 0 without index; 2: leave the switch in the same direction; 3: as 2 without index. The reference
point found (switch edge or index) plus HOME_OFFSET (qc) is where the drive then goes and sets zero
(kernel-spec p.7, docs/decisions.md).
"""

from __future__ import annotations

import math

from motiontool.kernel.errors import ControllerError

SLOW_FACTOR = 10  # leaving the switch and searching the index run at HOME_VEL / 10 (our choice, spec p.7)


class Homing:
    def __init__(self, axis, home_type: int, velocity: float, limits, offset: int, switch, index_only=False):
        """velocity: signed qc/ms (sign = search direction); switch(): True while the reference switch is on."""
        self.axis = axis
        self.type = home_type
        self.velocity = velocity
        self.limits = limits
        self.offset = offset
        self.switch = switch
        self.period = axis.index_period()
        self.index_only = index_only
        self.phase = "index" if index_only else "search"
        self.reference: float | None = None
        self.index_start = axis.raw
        self.done = False
        self.last_raw = axis.raw
        axis.profile.run_at(velocity, limits)

    def tick(self, axis) -> None:
        raw = axis.raw
        previous, self.last_raw = self.last_raw, raw
        if self.phase == "search":
            if self.switch():
                self.phase = "leave"
                direction = -1 if self.type in (0, 1) else 1
                axis.profile.run_at(direction * self.velocity / SLOW_FACTOR, self.limits)
        elif self.phase == "leave":
            if not self.switch():
                if self.type in (1, 3):
                    self._found(raw)
                else:
                    self.phase = "index"
                    self.index_start = raw
                    axis.profile.run_at(math.copysign(abs(self.velocity) / SLOW_FACTOR,
                                                      raw - previous or self.velocity), self.limits)
        elif self.phase == "index":
            crossed = self._index_crossed(previous, raw)
            if crossed is not None:
                self._found(crossed)
            elif abs(raw - self.index_start) > self.period + 1:
                axis.homing = None
                raise ControllerError(109, "no index pulse within one revolution")
        elif self.phase == "approach" and axis.profile.done:
            self.phase = "finished"
            self.done = True

    def _index_crossed(self, a: int, b: int) -> int | None:
        p = self.period
        if a == b:
            return None
        lo, hi = (a, b) if b > a else (b, a)
        k = math.floor(hi / p) * p
        return k if lo < k <= hi or (k == hi and lo < hi) else None

    def _found(self, raw_reference: int) -> None:
        axis = self.axis
        self.reference = raw_reference
        self.phase = "approach"
        # Go to the reference point + HOME_OFFSET (axis frame); HOME makes it zero when there.
        axis.profile.move_to(float(raw_reference - axis.origin + self.offset), self.limits)
        axis.mode = "homing"
