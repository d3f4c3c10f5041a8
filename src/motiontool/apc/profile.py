"""The main and offset profile generators (seed 004 §4.2.3 L803-912, §5.2.5 L3803-4050).

A generator has an input (a position [115] or speed [116]; offsets [155]/[156]) and an output position, speed,
acceleration and jerk ([117]-[119], [187]; offsets [157]-[159], [189]). It ramps to a new speed within its
accel/decel rates, and reaches (or synchronises with) a new position within the rates and the maximum speed;
its parameters may change during a profile and a position set point may be retargeted mid-move: heading for
100000 and retargeted to 200000 at 50000 the axis stops at 200000 (L1193-1199). Bypassed, the input passes
straight through (L816-818). The planning is in `trajectory.py`.

Positions are int32 counts that wrap (L1205-1209): the distance to a target is the wrapped difference, the
shortest route (L6986-7037). Speeds are held in counts per 250 µs quarter; a speed that is reached is then
followed with integer counts and a carried remainder, so a long jog keeps the exact average speed.
"""

from __future__ import annotations

from motiontool.apc import trajectory as tj
from motiontool.apc.intmath import wrap32

# flag bits of [186] (Table 4-1, L883-912): main in bits 0-9, offset in bits 16-25
AT_POS, AT_SPD, POS_JERK, NEG_JERK, ACCEL, DECEL, CONST_POS, CONST_NEG, CROSS_0, PROFILING = (1 << i for i in range(10))


class ProfileGenerator:
    """One profile generator. Limits are in APC units (speed 2^32/rev/250 µs, accel per 250 µs, jerk per 250 µs)
    and are converted with the turns bits when a move is planned."""

    def __init__(self, *, accel: int = 22369, decel: int = 22369, jerk: int = 0, max_speed: int = 48318382):
        self.accel, self.decel, self.jerk, self.max_speed = accel, decel, jerk, max_speed
        self.disabled = False            # [114] / [154]
        self.turns_bits = 16
        self.version = 0                 # raised when a limit changes: the present plan is then replanned
        self.reset(0)

    # --- state ------------------------------------------------------------------------------------------
    def reset(self, position: int) -> None:
        """Output set to `position`, at rest (Table 4-2: the generator output is set from the feedback
        integrator on a reset)."""
        self.base = wrap32(position)
        self.offset = 0.0
        self.position = self.base       # output position [117], int32
        self.speed = 0.0                # counts per quarter
        self.acceleration = 0.0
        self.jerk_out = 0.0
        self.prev_speed = 0.0
        self.input_position = self.base  # [115]
        self.input_speed = 0         # [116], APC units
        self.mode = "idle"           # idle | position | speed | cruise | bypass
        self.target: int | None = None
        self.traj: tj.Trajectory | None = None
        self._planned: tuple | None = None
        self._cruise = (0, 0)        # integer cruise: (APC speed units, remainder in 1/2^TB counts)

    def limits(self, linear: bool = False, decel_from_accel: bool = False) -> tj.Limits:
        scale = float(1 << self.turns_bits)
        decel = self.accel if decel_from_accel else self.decel
        return tj.Limits(self.accel / scale, decel / scale, self.max_speed / scale,
                         0.0 if linear else self.jerk / scale)

    def set_limit(self, name: str, value: int) -> None:
        """Change accel, decel, jerk or max_speed; a profile in progress replans from where it is (L803-812)."""
        setattr(self, name, value)
        self.version += 1

    def _rebase(self) -> float:
        """Move the integer base to the present position; return the fractional offset left."""
        whole = round(self.offset)
        self.base = wrap32(self.base + whole)
        self.offset -= whole
        return self.offset

    # --- references ---------------------------------------------------------------------------------------
    def to_position(self, target: int, n: int, *, linear: bool = False, decel_from_accel: bool = False) -> None:
        """One sample toward position `target` (counts), replanning when the target or a limit changed."""
        if (target != self.target or self.mode != "position"
                or self._planned != (self.version, self.turns_bits, linear, decel_from_accel)):
            target = wrap32(target)
            self.input_position = target
            off = self._rebase()
            lim = self.limits(linear, decel_from_accel)
            d = wrap32(target - self.base)
            pieces = tj.move(self.speed, self.acceleration, d - off, lim)
            self.traj = tj.Trajectory(self.base, (off, self.speed, self.acceleration), pieces, final_offset=float(d))
            self.mode, self.target = "position", target
            self._planned = (self.version, self.turns_bits, linear, decel_from_accel)
        assert self.traj is not None  # mode "position" comes with its plan (only reset() drops both)
        if self.traj.done:               # resting on the target
            self.prev_speed = self.speed
            self.speed = self.acceleration = self.jerk_out = 0.0
            return
        self._follow_plan(n)

    def to_speed(self, speed: int, n: int, *, linear: bool = False) -> None:
        """One sample toward speed `speed` (APC units), clamped to the maximum speed."""
        speed = max(-self.max_speed, min(self.max_speed, speed))
        self.input_speed = speed
        key = (self.version, self.turns_bits, speed, linear)
        if self.mode not in ("speed", "cruise") or key != self._planned:
            off = self._rebase()
            v1 = speed / (1 << self.turns_bits)
            pieces = tj.speed_change(self.speed, self.acceleration, v1, self.limits(linear))
            self.traj = tj.Trajectory(self.base, (off, self.speed, self.acceleration), pieces, final_speed=v1)
            self.mode, self.target, self._planned = "speed", None, key
        if self.mode == "cruise":
            self._cruise_step(n)
        else:
            self._follow_plan(n)
            assert self.traj is not None  # mode "speed" comes with its plan
            if self.traj.done:            # reached: continue with exact integer counts
                off = self._rebase()
                self._cruise = (speed, round(off * (1 << self.turns_bits)))
                self.offset = 0.0
                self.mode = "cruise"

    def bypass(self, position: int, n: int) -> None:
        """Bypassed (disabled, CAM, locked digital lock, instant stop): the output is the input; the speed is
        the increment per sample, so leaving the bypass later is bumpless in speed (acceleration restarts
        from 0, **inferred**)."""
        if (position + 0x80000000) >> 32:       # outside int32
            position = wrap32(position)
        step = position - self.position
        if (step + 0x80000000) >> 32:
            step = wrap32(step)
        self.input_position = self.position = self.base = position
        self.prev_speed = self.speed
        self.speed = step / n
        if self.mode != "bypass":
            self.acceleration = self.jerk_out = self.offset = 0.0
            self.mode, self._planned = "bypass", None

    # --- stepping -------------------------------------------------------------------------------------------
    def _follow_plan(self, n: int) -> None:
        assert self.traj is not None  # called in modes "position" and "speed", which have their plan
        off, v, a, j = self.traj.sample(n)
        self.offset = off
        self.prev_speed = self.speed
        self.speed, self.acceleration, self.jerk_out = v, a, j
        self.position = wrap32(self.base + round(off))

    def _cruise_step(self, n: int) -> None:
        speed, rem = self._cruise
        step, rem = divmod(speed * n + rem, 1 << self.turns_bits)
        self._cruise = (speed, rem)
        self.base = self.position = wrap32(self.position + step)
        self.prev_speed = self.speed
        self.speed = speed / (1 << self.turns_bits)
        self.acceleration = self.jerk_out = 0.0

    def take_over(self, other: ProfileGenerator) -> None:
        """Add another generator's output into this one (offsets switched off: the main generator profiles back
        from the total, L848-852; **inferred** mechanism) and zero the other."""
        self.offset += other.position
        self._rebase()
        self.position = wrap32(self.base + round(self.offset))
        self.speed += other.speed
        self.acceleration += other.acceleration
        self._planned = None
        other.reset(0)

    # --- read-outs ---------------------------------------------------------------------------------------
    def stop_position(self, linear: bool = False) -> int:
        """Where the output comes to rest when it brakes now with the deceleration rate ([91], L1172-1176)."""
        pieces = tj.stop(self.speed, self.acceleration, self.limits(linear))
        return wrap32(self.base + round(self.offset + tj.distance(self.speed, pieces)))

    def at_target(self) -> bool:
        return self.mode == "position" and self.traj is not None and self.traj.done

    def flags(self) -> int:
        """The ten flags of Table 4-1 as bits (L883-912); which rise depends on the move (L914-918)."""
        scale = 1 << self.turns_bits
        v, a, j = round(self.speed * scale), round(self.acceleration * scale), round(self.jerk_out * scale)
        bits = 0
        traj = self.traj   # not None in modes "position" and "speed"
        moving = self.mode in ("position", "speed") and traj is not None and not traj.done
        if self.mode == "position" and traj is not None and traj.done or self.mode in ("idle", "bypass") and v == 0:
            bits |= AT_POS
        if self.mode == "cruise" or self.mode == "speed" and traj is not None and traj.done:
            bits |= AT_SPD
        if j > 0:
            bits |= POS_JERK
        elif j < 0:
            bits |= NEG_JERK
        if a and (v == 0 or (a > 0) == (v > 0)):
            bits |= ACCEL
        elif a:
            bits |= DECEL
        if not a and v and (moving or self.mode == "cruise"):
            bits |= CONST_POS if v > 0 else CONST_NEG
        before = round(self.prev_speed * scale)
        if (before > 0 > v) or (before < 0 < v):
            bits |= CROSS_0
        if moving:
            bits |= PROFILING
        return bits

    def output_speed(self) -> int:
        """[118] in APC units."""
        return round(self.speed * (1 << self.turns_bits))

    def output_acceleration(self) -> int:
        return round(self.acceleration * (1 << self.turns_bits))

    def output_jerk(self) -> int:
        return round(self.jerk_out * (1 << self.turns_bits))
