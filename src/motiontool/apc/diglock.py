"""The digital lock reference (seed 004 §4.8 L1706-1853, §5.2.4.6 L3699-3800).

The slave follows ratio × master ([62]/[63], remainder kept, so tooth counts never drift, L1825-1840). Modes
([61]): 0 Unlocked — the profile generator acquires the lock within accel, decel and maximum speed and the mode
becomes Locked by itself once the windows hold; 1 Locked — the generator is bypassed; 2 Never lock — the
generator stays in the path (L1742-1762).

* Non-rigid ([60] = 0): the slave ramps to the master's speed; locked when |ref speed − fbk speed| ≤ [64]; the
  position lost while accelerating is not recovered (L1763-1789) — so the lag stays constant once locked.
* Rigid ([60] = 1): the slave may overspeed, up to the profile maximum, to win back the position lost while
  accelerating; locked when the speed window holds and |position difference| ≤ [65]; the deceleration rate
  is the acceleration rate (L1791-1823, L3777-3787). So fbk − ratio·ref returns to its value at selection.
* No jerk while acquiring (L840).

The acquisition law is **inferred** (docs/decisions.md A40): rigid chases the moving target on a braking curve
relative to it, sqrt(2·a·|e|) on top of the target speed; non-rigid ramps its speed to the target speed.
The target is the slave position at selection plus ratio × the master's travel since (the freeze position
when selected by a freeze, L1842-1853).
"""

from __future__ import annotations

import math

from motiontool.apc.intmath import Ratio, wrap32
from motiontool.apc.profile import ProfileGenerator

UNLOCKED, LOCKED, NEVER_LOCK = 0, 1, 2


class DigitalLock:
    def __init__(self) -> None:
        self.rigid = False                 # [60]
        self.mode = UNLOCKED               # [61]
        self.ratio = Ratio(1000, 1000)     # [62]/[63]
        self.lock_speed = 17895            # [64] ≈ 1 rpm
        self.lock_position = 6553          # [65] ≈ 0.1 rev at 16 bits
        self.target = 0                    # ratio × reference, the slave position the lock aims at

    def engage(self, slave_position: int, master_since: int = 0) -> None:
        """Selected (by APCSelectReference(4) or a freeze): unlocked, the target starts at the slave's position
        and has already moved by ratio × `master_since` (travel since the freeze)."""
        self.mode = UNLOCKED
        self.ratio.reset()
        self.target = wrap32(slave_position + self.ratio.step(master_since))

    def rebase(self, target: int) -> None:
        self.target = wrap32(target)
        self.ratio.reset()

    def step(self, master_delta: int, pg: ProfileGenerator, n: int) -> None:
        """One sample: advance the target by ratio × the master's increment and move the profile generator."""
        step = self.ratio.step(master_delta)
        self.target = target = wrap32(self.target + step)
        if self.mode == LOCKED or pg.disabled:
            pg.bypass(target, n)
            return
        scale = 1 << pg.turns_bits
        v_target = step / n                                # counts per quarter
        if self.rigid:
            self._chase(pg, target, v_target, n)
            locked = (abs(v_target - pg.speed) * scale <= self.lock_speed
                      and abs(wrap32(target - pg.position)) <= self.lock_position)
        else:
            self._ramp(pg, v_target, n)
            locked = abs(v_target - pg.speed) * scale <= self.lock_speed
        if locked and self.mode == UNLOCKED:
            self.mode = LOCKED
            if not self.rigid:          # the lag acquired while ramping is kept
                self.target = pg.position
                self.ratio.reset()
            pg.bypass(self.target, n)

    @staticmethod
    def _advance(pg: ProfileGenerator, v_new: float, n: int) -> None:
        pg.prev_speed = pg.speed
        pg.offset += (pg.speed + v_new) * n / 2
        pg.acceleration = (v_new - pg.speed) / n
        pg.jerk_out = 0.0
        pg.speed = v_new
        whole = round(pg.offset)
        pg.base = wrap32(pg.base + whole)
        pg.offset -= whole
        pg.position = pg.base
        pg.mode, pg._planned = "chase", None

    def _ramp(self, pg: ProfileGenerator, v_target: float, n: int) -> None:
        lim = pg.limits(linear=True)
        v = pg.speed
        rate = lim.accel if abs(v_target) > abs(v) and v * v_target >= 0 else lim.decel
        dv = max(-rate * n, min(rate * n, v_target - v))
        self._advance(pg, max(-lim.speed, min(lim.speed, v + dv)), n)

    def _chase(self, pg: ProfileGenerator, target: int, v_target: float, n: int) -> None:
        lim = pg.limits(linear=True, decel_from_accel=True)
        a = lim.accel
        e = wrap32(target - pg.base) - pg.offset + v_target * n     # where the target will be after this sample
        # the fastest relative speed that can still brake onto the moving target (sampled braking curve)
        w = max(math.sqrt(2 * a * abs(e) + (a * n / 2) ** 2) - a * n / 2, 0.0) if a > 0 else 0.0
        w = math.copysign(min(w, abs(e) / n), e)
        v_cmd = max(-lim.speed, min(lim.speed, v_target + w))
        dv = max(-a * n, min(a * n, v_cmd - pg.speed))
        self._advance(pg, pg.speed + dv, n)
