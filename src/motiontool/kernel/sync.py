"""Velocity and position synchronisation of the slave axis to the master (kernel-spec f.0-f.2).

The gear SYNCFACTS/SYNCFACTM (33-11 / 33-10, slave qc per master qc, DG 9318-9324) is an exact fraction:
`Gear` keeps the remainder as an integer numerator, so the slave command never drifts against the master
(DG 946: "even the smallest rounding error will lead to position drifting over time").

SYNCV: the commanded velocity follows master velocity × gear, clamped to VEL and ramped with ACC/DEC (DG 810).

SYNCP: the commanded position follows the target T = base_slave + ⌊(MAPOS − base_master + SYNCPOSOFFS +
Σ MOVESYNCORIGIN) · SYNCFACTS / SYNCFACTM⌋ (offsets in master qc, converted with the gear; base = the
DEFSYNCORIGIN pair, else 0, i.e. slave axis position 0 belongs to MAPOS 0). While the slave is away from
T (start, offset change, a master faster than the slave can follow) it catches up within VEL and ACC/DEC:
relative to the master it runs on a braking curve for min(ACC, DEC); when the remaining gap and the
relative velocity are below one step it locks, and from then on CPOS = T exactly each ms.
"""

from __future__ import annotations

import math

from motiontool.kernel.errors import ControllerError

SYNCSTAT_READY, SYNCSTAT_FAULT, SYNCSTAT_ACCURACY = 1, 2, 4


class Gear:
    """out = ⌊input · s / m⌋ exactly, updated with integer increments of the input."""

    def __init__(self, s: int, m: int, start: int = 0):
        if m == 0:
            raise ControllerError(183, "SYNCFACTM must not be 0")
        if m < 0:  # a negative factor turns the direction (DG 9302-9309)
            s, m = -s, -m
        self.s, self.m = s, m
        self.input = start
        self.out, self.rem = divmod(start * s, m)

    @property
    def ratio(self) -> float:
        return self.s / self.m

    def advance(self, d_input: int) -> int:
        """Add an integer increment of the input; returns the new output."""
        if d_input:
            self.input += d_input
            q, self.rem = divmod(self.rem + d_input * self.s, self.m)
            self.out += q
        return self.out


class SyncMotion:
    """One running SYNCV ("velocity") or SYNCP ("position"); stepped by the axis once per tick."""

    def __init__(self, kind: str, master, gear: Gear, limits, offset=lambda: 0, base_slave: int = 0,
                 accuracy: int = 1000):
        self.kind = kind
        self.master = master
        self.gear = gear
        self.vel, self.acc, self.dec = limits.vel, limits.acc, limits.dec
        self.offset = offset          # SYNCPOSOFFS + MOVESYNCORIGIN (master qc), read every tick
        self._offset = offset()
        self._raw = master.raw
        self.base_slave = base_slave
        self.accuracy = accuracy      # SYNCACCURACY as of the SYNC command (DG 9458)
        self.locked = False
        self.target = base_slave + gear.out

    def step(self, pg) -> None:
        m = self.master
        vt = m.velocity * self.gear.ratio
        v0 = pg.velocity
        if self.kind == "velocity":
            v = self._ramp(v0, max(-self.vel, min(self.vel, vt)))
            pg.position += v
        else:
            offset = self.offset()
            d_input = (m.raw - self._raw) + (offset - self._offset)
            if offset != self._offset:
                self.locked = False  # an offset change is realised within the limits, not as a jump
            self._raw, self._offset = m.raw, offset
            t = self.target = self.base_slave + self.gear.advance(d_input)
            if self.locked and (abs(vt) > self.vel * (1 + 1e-9) or abs(vt - v0) > self._acc_limit(v0, vt) + 1e-9):
                self.locked = False  # the master is faster or accelerates harder than the slave may follow
            if self.locked:
                v = vt
                pg.position = float(t)
            else:
                gap = t - pg.position           # what must be moved in this tick to be at the target
                d = gap - vt                    # the offset left if the slave moved like the master
                brake = min(self.acc, self.dec)
                w = math.copysign(min(abs(d), brake * (math.sqrt(0.25 + 2.0 * abs(d) / brake) - 0.5)), d)
                v = self._ramp(v0, max(-self.vel, min(self.vel, vt + w)))
                if abs(gap - v) <= 1.0 and abs(vt - v0) <= self._acc_limit(v0, vt) + 1e-9 and abs(vt) <= self.vel:
                    self.locked = True
                    v = vt
                    pg.position = float(t)
                else:
                    pg.position += v
        pg.acceleration = v - v0
        pg.velocity = v

    def shift(self, delta: int) -> None:
        """The slave's origin moved (DEFORIGIN during a synchronisation)."""
        self.base_slave += delta
        self.target += delta

    def _acc_limit(self, v0: float, v1: float) -> float:
        return self.acc if abs(v1) > abs(v0) and v1 * v0 >= 0 else self.dec

    def _ramp(self, v0: float, v1: float) -> float:
        lim = self._acc_limit(v0, v1)
        return v0 + max(-lim, min(lim, v1 - v0))

    def error_qc(self, apos: int) -> int:
        """Target minus actual slave position (qc); 0 in SYNCV (no position target)."""
        return self.target - apos if self.kind == "position" else 0

    def status(self, apos: int) -> int:
        bits = 0
        if self.kind == "position" and abs(self.target - apos) <= abs(self.accuracy):
            bits |= SYNCSTAT_ACCURACY
        return bits
