"""Velocity and position synchronisation of the slave axis to the master (kernel-spec f.0-f.2).

The gear SYNCFACTS/SYNCFACTM (33-11 / 33-10, slave qc per master qc, DG 9318-9324) is an exact fraction:
`Gear` keeps the remainder as an integer numerator, so the slave command never drifts against the master
(DG 946: "even the smallest rounding error will lead to position drifting over time").

SYNCV: the commanded velocity follows master velocity × gear, clamped to VEL and ramped with ACC/DEC (DG 810).

SYNCP: the commanded position follows the target T = base_slave + ⌊(MAPOS − base_master + SYNCPOSOFFS +
Σ MOVESYNCORIGIN) · SYNCFACTS / SYNCFACTM⌋ (offsets in master qc, converted with the gear). The base is the
relation at the start: "the actual slave position will be locked to the actual master position" (DG 948), i.e.
the slave's commanded position belongs to MAPOS at SYNCP, unless DEFSYNCORIGIN named the pair (decision K17).
While the slave is away from
T (start, offset change, a master faster than the slave can follow) it catches up within VEL and ACC/DEC:
relative to the master it runs on a braking curve for min(ACC, DEC); when the remaining gap and the
relative velocity are below one step it locks, and from then on CPOS = T exactly each ms.

Refinements (DG 9462-9492, 9763-9843, 8790-8805): SYNCVELREL bounds the slave speed while it corrects;
the SYNCV command velocity passes the 33-26 velocity filter; offset changes and marker corrections are
realised by `OffsetFilter` (SYNCOFFTIME, 20/60/20 trapezoid) or at once; REVERS blocks reversing;
SYNCFFVEL leads the SYNCP/SYNCM command by VCMD · SYNCFFVEL/1000 (a velocity-proportional feed-forward).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from motiontool.kernel.errors import ControllerError

if TYPE_CHECKING:
    from motiontool.kernel.markers import MarkerSync

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


# 33-26 standard table: master encoder resolution (lines/rev) → τ_filt in µs (DG 9763-9785).
VFILTER_TABLE = ((250, 39500), (256, 38600), (500, 19500), (512, 19000), (1000, 9500), (1024, 9300),
                 (2000, 4500), (2048, 4400), (2500, 3500), (4096, 1900), (5000, 1400))


def velocity_filter_ms(syncvftime: int, master_lines: int) -> float:
    """τ_filt of the SYNCV velocity filter in ms: |SYNCVFTIME| µs, or for −999…999 the standard table by
    32-31 MENCODER. Between table rows τ·resolution is about constant, so the nearest row is scaled."""
    if abs(syncvftime) > 999:
        return abs(syncvftime) / 1000.0
    lines = max(1, master_lines)
    res, tau = min(VFILTER_TABLE, key=lambda row: abs(math.log(row[0] / lines)))
    return tau * res / lines / 1000.0


def trapezoid_part(x: float) -> float:
    """Part of an offset realised after the fraction x of its time: 20 % accelerate, 60 % constant,
    20 % decelerate (DG 9833-9843); peak speed 1/0.8 of the mean."""
    if x >= 1.0:
        return 1.0
    if x < 0.2:
        return 3.125 * x * x
    if x < 0.8:
        return 1.25 * (x - 0.1)
    return 1.0 - 3.125 * (1.0 - x) ** 2


def _trapezoid_rate(x: float) -> float:
    if x >= 1.0:
        return 0.0
    return 6.25 * x if x < 0.2 else (1.25 if x < 0.8 else 6.25 * (1.0 - x))


class OffsetFilter:
    """Offset changes realised over time (33-27 SYNCOFFTIME, DG 9813-9843): each change runs as its own
    20/60/20 trapezoid superimposed on the synchronised motion; a duration below 1 ms applies at once.
    Increments are whole qc (the rounded running sum), so the total arrives exactly."""

    def __init__(self) -> None:
        self.moves: list[list] = []   # [total, duration, elapsed, done]
        self._now = 0
        self.velocity = 0.0           # qc/ms the filter adds in this tick
        self.jumped = False           # an immediate change happened in the last step

    def add(self, amount: int, duration_ms: float) -> None:
        if not amount:
            return
        if duration_ms < 1.0:
            self._now += amount
        else:
            self.moves.append([amount, float(duration_ms), 0, 0])

    @property
    def pending(self) -> int:
        return self._now + sum(total - done for total, _, _, done in self.moves)

    def step(self) -> int:
        inc, self._now = self._now, 0
        self.jumped = inc != 0
        velocity = 0.0
        keep = []
        for move in self.moves:
            move[2] += 1
            total, duration, elapsed, done = move
            x = elapsed / duration
            new = round(total * trapezoid_part(x))
            inc += new - done
            move[3] = new
            if x < 1.0:
                keep.append(move)
                velocity += total * _trapezoid_rate(x) / duration
        self.moves = keep
        self.velocity = velocity
        return inc


class SyncMotion:
    """One running SYNCV ("velocity"), SYNCP or SYNCM ("position"); stepped by the axis once per tick.

    velrel: SYNCVELREL %; vfilter_ms: τ of the SYNCV velocity filter (0 = none); offtime: SYNCOFFTIME ms per
    `marker_distance` (SYNCMPULSM) master qc of offset; revers: 32-68 REVERS. `markers` is the SYNCM
    marker correction (markers.MarkerSync) that adds slave corrections through `correct`.
    """

    def __init__(self, kind: str, master, gear: Gear, limits, offset=lambda: 0, base_slave: int = 0,
                 accuracy: int = 1000, *, velrel: int = 0, vfilter_ms: float = 0.0, offtime: int = 0,
                 marker_distance: int = 4096, revers: int = 0, ffvel: int = 0, spread_ms: float = 0.0,
                 pfilter_ms: float = 0.0, shift: int = 0):
        self.kind = kind
        self.master = master
        self.gear = gear
        self.vel, self.acc, self.dec = limits.vel, limits.acc, limits.dec
        self.offset = offset          # SYNCPOSOFFS (master qc), read every tick
        # Σ MOVESYNCORIGIN of this synchronisation (master qc); not named `shift`, which would hide the method
        # shift() that DEFORIGIN calls
        self.origin_shift = shift
        self._offset = offset() + shift
        self.offset_applied = self._offset  # master qc of offset already in the target
        self._raw = master.raw
        self.base_slave = base_slave
        self.accuracy = accuracy      # SYNCACCURACY as of the SYNC command (DG 9458)
        self.velrel = max(0, min(100, velrel)) / 100.0
        self.vfilter_ms = vfilter_ms
        self.offtime = max(0, offtime)
        self.marker_distance = max(1, abs(marker_distance))
        self.revers = revers
        self.ffvel = ffvel / 1000.0   # 33-32 SYNCFFVEL: position lead of VCMD·SYNCFFVEL/1000 (DG 10062-10075)
        self._lead = 0.0
        self.spread_ms = spread_ms    # negative SYNCVFTIME: marker corrections take 10 τ (DG 9807-9811)
        self.pfilter_ms = pfilter_ms if pfilter_ms > 1.0 else 0.0  # negative SYNCVFTIME: τ of the position filter
        self._command: float | None = None  # the filtered command position (slave qc)
        self._vf = 0.0                      # its filtered velocity
        self.offset_filter = OffsetFilter()  # master qc
        self.slave_filter = OffsetFilter()   # slave qc (marker corrections)
        self.slave_shift = 0
        self.vcmd = master.velocity * gear.ratio  # filtered SYNCV command velocity
        self.markers: MarkerSync | None = None
        self.locked = False
        self.target = base_slave + gear.out

    def step(self, pg) -> None:
        m = self.master
        ratio = self.gear.ratio
        v0 = pg.velocity
        if self.kind == "velocity":
            raw_v = m.velocity * ratio
            if self.vfilter_ms > 1.0:  # DG 9786-9800: Cmdvel += (Actvel − Old_Cmdvel) · 1 ms / τ
                self.vcmd += (raw_v - self.vcmd) / self.vfilter_ms
            else:
                self.vcmd = raw_v
            v = self._ramp(v0, self._reverse_limit(max(-self.vel, min(self.vel, self.vcmd))))
            pg.position += v
        else:
            pg.position -= self._lead  # the lead is added to the output only; the sync runs without it
            offset = self.offset() + self.origin_shift
            if offset != self._offset:  # realised within the limits / by the offset filter, not as a jump
                delta = offset - self._offset
                self.offset_filter.add(delta, self._duration(abs(delta), abs(delta * ratio)))
                self._offset = offset
            applied = self.offset_filter.step()
            self.offset_applied += applied
            d_input = (m.raw - self._raw) + applied
            self._raw = m.raw
            self.slave_shift += self.slave_filter.step()
            if self.offset_filter.jumped or self.slave_filter.jumped:
                self.locked = False
            t: float  # the target; a float once filtered
            t = self.target = self.base_slave + self.gear.advance(d_input) + self.slave_shift
            vt = (m.velocity + self.offset_filter.velocity) * ratio + self.slave_filter.velocity
            if self.pfilter_ms:  # negative SYNCVFTIME: the slave follows the filtered command (DG 9800-9811)
                t, vt = self._filtered(pg.position, pg.velocity, t, vt)
            if self.locked and (abs(vt) > self.vel * (1 + 1e-9) or abs(vt - v0) > self._acc_limit(v0, vt) + 1e-9
                                or self._reverse_limit(vt) != vt):
                self.locked = False  # the master is faster or accelerates harder than the slave may follow
            if self.locked:
                v = vt
                pg.position = float(t)
            else:
                gap = t - pg.position           # what must be moved in this tick to be at the target
                d = gap - vt                    # the offset left if the slave moved like the master
                brake = min(self.acc, self.dec)
                w = math.copysign(min(abs(d), brake * (math.sqrt(0.25 + 2.0 * abs(d) / brake) - 0.5)), d)
                v = self._ramp(v0, self._bound(vt + w, m.velocity * ratio))
                if abs(gap - v) <= 1.0 and abs(vt - v0) <= self._acc_limit(v0, vt) + 1e-9 and abs(vt) <= self.vel \
                        and self._reverse_limit(vt) == vt:
                    self.locked = True
                    v = vt
                    pg.position = float(t)
                else:
                    pg.position += v
            if self.ffvel:
                self._lead = self.ffvel * v
                pg.position += self._lead
        pg.acceleration = v - v0
        pg.velocity = v

    def _filtered(self, position: float, velocity: float, t: int, vt: float) -> tuple[float, float]:
        """DG 9800-9811: with a negative SYNCVFTIME the velocity filter "also applies for angle/position
        synchronization SYNCP and for marker correction SYNCM. In this case filtering takes place as described above,
        but the errors made are summed up. This error sum is taken into the calculation with 1000/(τ*10) in each
        case, so that no position deviation can occur over prolonged periods". Each ms: vf += (vt − vf)/τ and
        C += vf + (T − C − vf)/(10 τ), T the unfiltered target; at constant speed C − T decays with 10 τ, and SYNCERR
        (T − APOS) contains the error made (decision K20)."""
        tau = self.pfilter_ms
        c = self._command
        if c is None:  # from where the slave's command stands at the start
            c, self._vf = position, velocity
        vf = self._vf = self._vf + (vt - self._vf) / tau
        new = c + vf + (t - c - vf) / (10.0 * tau)  # the error after this ms's filtered step
        self._command = new
        return new, new - c

    def regear(self, s: int, m: int) -> None:
        """SYNCFACTS/SYNCFACTM changed during the synchronisation ("the gear-ratio and position offset can be adjusted
        during operation", DG 796; decision K21): the target stays where it is and moves on with the new ratio; the
        slave follows within VEL and ACC/DEC. A factor M of 0 is ignored."""
        if m == 0:
            return
        old, new = self.gear, Gear(s, m, self.gear.input)
        self.base_slave += old.out - new.out
        self.gear = new

    def correct(self, slave_qc: int) -> None:
        """A marker correction of the slave (qc): realised like an offset (SYNCOFFTIME) or at once."""
        ratio = abs(self.gear.ratio) or 1.0
        duration = self._duration(abs(slave_qc) / ratio, abs(slave_qc))
        self.slave_filter.add(slave_qc, max(duration, self.spread_ms) if slave_qc else 0.0)

    def _duration(self, master_qc: float, slave_qc: float) -> float:
        """SYNCOFFTIME per SYNCMPULSM master qc (DG 9829-9833); 0 = at once. The trapezoid's acceleration
        Δ/(0.16 T²) must not exceed the slave's ACC/DEC (DG 9841: the ramps are planned to fit), so a
        too short time is stretched."""
        if not self.offtime:
            return 0.0
        nominal = self.offtime * master_qc / self.marker_distance
        return max(nominal, math.sqrt(slave_qc / (0.16 * min(self.acc, self.dec))))

    def _bound(self, v: float, v_master: float) -> float:
        """VEL, SYNCVELREL (DG 9462-9492: between MAVEL·(1 − r) and min(VEL, MAVEL·(1 + r))) and REVERS."""
        v = max(-self.vel, min(self.vel, v))
        if self.velrel:
            vm = abs(v_master)
            low, high = vm * (1 - self.velrel), min(self.vel, vm * (1 + self.velrel))
            v = max(low, min(high, v)) if v_master >= 0 else min(-low, max(-high, v))
        return self._reverse_limit(v)

    def _reverse_limit(self, v: float) -> float:
        """32-68 REVERS (DG 8790-8805): 1 = backwards only while the master runs backwards, 2 = never."""
        if v < 0 and (self.revers == 2 or (self.revers == 1 and self.master.velocity >= 0)):
            return 0.0
        return v

    def shift(self, delta: int) -> None:
        """The slave's origin moved (DEFORIGIN during a synchronisation)."""
        self.base_slave += delta
        self.target += delta
        if self.markers is not None:
            self.markers.shift(delta)

    def _acc_limit(self, v0: float, v1: float) -> float:
        return self.acc if abs(v1) > abs(v0) and v1 * v0 >= 0 else self.dec

    def _ramp(self, v0: float, v1: float) -> float:
        lim = self._acc_limit(v0, v1)
        return v0 + max(-lim, min(lim, v1 - v0))

    def pending_qc(self) -> float:
        """Offsets and corrections not yet realised (slave qc); SYNCERR includes them (DG 10058-10060)."""
        return self.offset_filter.pending * self.gear.ratio + self.slave_filter.pending

    def error_qc(self, apos: int) -> int:
        """Target minus actual slave position plus pending corrections (qc); 0 in SYNCV."""
        return round(self.target + self.pending_qc() - apos) if self.kind == "position" else 0

    def status(self, apos: int) -> int:
        bits = 0
        if self.kind == "position" and abs(self.error_qc(apos)) <= abs(self.accuracy):
            bits |= SYNCSTAT_ACCURACY
        if self.markers is not None:
            bits |= self.markers.status_bits()
        return bits
