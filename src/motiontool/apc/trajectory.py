"""Jerk-limited trajectories as lists of constant-jerk pieces, and the planners the profile generators use.

The manual gives the behaviour (seed 004 L803-841, L1193-1222) and the S-ramp closed forms of §8.6
(L7053-7132) but not the algorithm. **Inferred** here (docs/decisions.md A20-A23): a move is planned in
continuous time from the generator's present state (position, speed, acceleration) — a speed change to a cruise
speed, a cruise, a speed change to rest — and sampled every POS period. Because the plan itself respects the
limits, every sampled speed, acceleration and jerk does too, and after the last piece the position is the
target exactly. A retarget replans from the state of that instant, so the change is bumpless.

Units: positions in counts, time in 250 µs quarters (the APC's time base), so a speed of v counts per quarter
is v·2^TB APC speed units. Jerk 0 means linear ramps (the acceleration steps).

The acceleration rate applies moving away from zero speed and the deceleration rate moving toward it (L814-820,
"Figure 4-3"); a speed change through zero is split there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

_EPS = 1e-12


@dataclass
class Piece:
    """A stretch of constant jerk: `duration` quarters from acceleration `a0` with jerk `jerk`."""

    duration: float
    a0: float
    jerk: float


def advance(state: tuple[float, float, float], piece: Piece, t: float) -> tuple[float, float, float]:
    """(position, speed, acceleration) `t` quarters into `piece` from `state` (its acceleration is piece.a0)."""
    p, v, _ = state
    a, j = piece.a0, piece.jerk
    return (p + v * t + a * t * t / 2 + j * t * t * t / 6, v + a * t + j * t * t / 2, a + j * t)


def end_state(state, pieces) -> tuple[float, float, float]:
    for piece in pieces:
        state = advance(state, piece, piece.duration)
    return state


def distance(v0: float, pieces) -> float:
    return end_state((0.0, v0, 0.0), pieces)[0]


def _accel_change(a0: float, v0: float, v1: float, amax: float, jerk: float) -> list[Piece]:
    """Time-optimal change of speed from (v0, a0) to (v1, 0) within |a| ≤ amax and |j| ≤ jerk (jerk 0 =
    unlimited: the acceleration steps). `a0` may exceed amax (the limit was lowered mid-move)."""
    if amax <= 0:
        return []
    if jerk <= 0:
        dv = v1 - v0
        if abs(dv) < _EPS:
            return []
        a = math.copysign(amax, dv)
        return [Piece(abs(dv) / amax, a, 0.0)]
    # speed reached if the acceleration is brought to zero at once
    free = v0 + a0 * abs(a0) / (2 * jerk)
    rest = v1 - free
    if abs(rest) < _EPS:
        return [Piece(abs(a0) / jerk, a0, -math.copysign(jerk, a0))] if abs(a0) > _EPS else []
    s = 1.0 if rest > 0 else -1.0
    b = s * a0                       # the present acceleration seen in the direction of the change
    x = s * (v1 - v0)                # speed to gain in that direction
    if b > amax:                     # above the limit: come down to it, hold, ramp out
        peak = amax
        hold = (x - b * b / (2 * jerk)) / amax
    else:
        peak = math.sqrt(max((2 * jerk * x + b * b) / 2, 0.0))
        hold = 0.0
        if peak > amax:
            peak = amax
            hold = (x - (2 * amax * amax - b * b) / (2 * jerk)) / amax
    pieces = []
    if abs(peak - b) > _EPS:
        pieces.append(Piece(abs(peak - b) / jerk, a0, s * math.copysign(jerk, peak - b)))
    if hold > _EPS:
        pieces.append(Piece(hold, s * peak, 0.0))
    if peak > _EPS:
        pieces.append(Piece(peak / jerk, s * peak, -s * jerk))
    return pieces


@dataclass
class Limits:
    """Profile limits in counts and quarters: accel (away from zero), decel (toward zero), speed, jerk."""

    accel: float
    decel: float
    speed: float
    jerk: float = 0.0


def speed_change(v0: float, a0: float, v1: float, lim: Limits) -> list[Piece]:
    """From speed v0 (acceleration a0) to v1 at rest acceleration, with the accel rate away from zero and the
    decel rate toward it; through zero in two parts."""
    if v0 * v1 < 0:
        first = _accel_change(a0, v0, 0.0, lim.decel, lim.jerk)
        return first + _accel_change(0.0, 0.0, v1, lim.accel, lim.jerk)
    rate = lim.accel if abs(v1) > abs(v0) else lim.decel
    return _accel_change(a0, v0, v1, rate, lim.jerk)


def stop(v0: float, a0: float, lim: Limits) -> list[Piece]:
    return speed_change(v0, a0, 0.0, lim)


def _move_forward(v0: float, a0: float, d: float, lim: Limits) -> list[Piece]:
    """A move of d ≥ 0 counts ending at rest, from (v0, a0), assuming braking now does not pass the target."""
    vmax = lim.speed
    if vmax <= 0 or d <= _EPS and abs(v0) < _EPS and abs(a0) < _EPS:
        return stop(v0, a0, lim)

    def plan(vp: float) -> tuple[list[Piece], list[Piece], float]:
        up = speed_change(v0, a0, vp, lim)
        down = stop(vp, 0.0, lim)
        return up, down, distance(v0, up) + distance(vp, down)

    up, down, dist = plan(vmax)
    vp = vmax
    if dist > d:
        lo, hi = 0.0, vmax
        for _ in range(60):   # the distance grows with the cruise speed; bisect for the fastest that fits
            mid = (lo + hi) / 2
            if plan(mid)[2] <= d:
                lo = mid
            else:
                hi = mid
        vp = lo
        up, down, dist = plan(vp)
    pieces = list(up)
    if vp > _EPS and d - dist > 0:
        pieces.append(Piece((d - dist) / vp, 0.0, 0.0))
    return pieces + down


def move(v0: float, a0: float, d: float, lim: Limits) -> list[Piece]:
    """Pieces that take the generator from speed v0, acceleration a0 to rest d counts further (d signed).
    If braking now already passes the target the axis stops first and comes back (L814-820)."""
    sign = -1.0 if d < 0 else 1.0
    v, a, dd = sign * v0, sign * a0, sign * d
    braking = stop(v, a, lim)
    overshoot = distance(v, braking) - dd
    if overshoot > _EPS:
        pieces = braking + _mirror(_move_forward(0.0, 0.0, overshoot, lim))
    else:
        pieces = _move_forward(v, a, dd, lim)
    return _mirror(pieces) if sign < 0 else pieces


def _mirror(pieces: list[Piece]) -> list[Piece]:
    return [Piece(p.duration, -p.a0, -p.jerk) for p in pieces]


class Trajectory:
    """A plan being followed: pieces from a start state, sampled at increasing times. The position is kept
    as an integer base plus a float offset, so it stays exact however far the axis travels."""

    __slots__ = ("base", "pieces", "starts", "t", "index", "final_offset", "final_speed", "done")

    def __init__(self, base: int, state: tuple[float, float, float], pieces: list[Piece],
                 final_offset: float | None = None, final_speed: float = 0.0):
        self.base = base
        self.pieces = [p for p in pieces if p.duration > 0]
        self.starts = []
        s = state
        for piece in self.pieces:
            self.starts.append(s)
            s = advance(s, piece, piece.duration)
        self.starts.append(s)
        # a position move ends exactly on its target; a speed change ends cruising at its speed
        self.final_offset = s[0] if final_offset is None else final_offset
        self.final_speed = final_speed
        self.t = 0.0
        self.index = 0
        self.done = not self.pieces

    def sample(self, dt: float) -> tuple[float, float, float, float]:
        """Advance by dt quarters: (position offset from base, speed, acceleration, jerk) at the new time."""
        t = self.t + dt
        if self.done:
            self.t = t
            return self.final_offset + self.final_speed * t, self.final_speed, 0.0, 0.0
        i, pieces = self.index, self.pieces
        piece = pieces[i]
        while t >= piece.duration:
            t -= piece.duration
            i += 1
            if i == len(pieces):
                self.done = True
                self.t = t          # time spent cruising after the end
                return self.final_offset + self.final_speed * t, self.final_speed, 0.0, 0.0
            piece = pieces[i]
        self.index, self.t = i, t
        p, v, _ = self.starts[i]
        a, j = piece.a0, piece.jerk
        return (p + t * (v + t * (a / 2 + j * t / 6)), v + t * (a + j * t / 2), a + j * t, j)
