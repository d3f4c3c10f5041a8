"""Profile generator of the simulated MCO 305: the commanded position CPOS, one kernel tick at a time.

Units: position qc (float), velocity qc/tick, acceleration qc/tick², jerk qc/tick³, time in ticks.

Every command (``move_to``, ``run_at``, ``stop``) plans an exact continuous-time profile from the current
state (p, v, a) as a short list of polynomial segments; ``step`` advances the time by one tick and samples
that profile (no search, no allocation).  Because the samples come from a continuous profile that respects
the limits, the per-tick differences respect them too, and the final tick lands exactly on the target.
The algorithm, the S-ramp design choice and the manual references are in ``docs/profile-generator.md``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

__all__ = ["Limits", "ProfileGenerator"]

_END_EPS = 1e-7  # a segment boundary closer than this (ticks) to the current tick counts as reached
_INF = math.inf

# raw segment kinds (duration, kind, value) produced by the planners
_ACC = 0  # constant acceleration `value` (ramp type 0)
_SIN = 1  # sin² acceleration bump of peak `value` over the whole duration (ramp type 1)
_JERK = 2  # constant jerk `value`, the acceleration continues (ramp type 2)
_CRUISE = 3  # constant velocity `value`, acceleration 0
# a planned segment (ProfileGenerator._load): t1, t0, p0, v0, a0, j, value, amp, w2
_Rec = tuple[float, float, float, float, float, float, float, float, float]


@dataclass(frozen=True)
class Limits:
    """Limits of one motion. ``jerk`` = (J1 acc ramp-up, J2 acc ramp-down, J3 dec ramp-up, J4 dec ramp-down).

    As for JERKMIN2..4 [DG 1888-1890, 9102, 9140, 9170], a jerk of 0 in J2..J4 means "same as J1"; J1 must be
    > 0 for type 2. Type 1 (S-ramp) does not use the jerk (docs/profile-generator.md).
    """

    vel: float
    acc: float
    dec: float
    ramp_type: int = 0
    jerk: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        for name in ("vel", "acc", "dec"):
            x = getattr(self, name)
            if not (x > 0.0 and math.isfinite(x)):
                raise ValueError(f"Limits.{name} must be a finite number > 0, got {x!r}")
        if self.ramp_type not in (0, 1, 2):
            raise ValueError(f"Limits.ramp_type must be 0, 1 or 2, got {self.ramp_type!r}")
        if len(self.jerk) != 4 or not all(math.isfinite(j) and j >= 0.0 for j in self.jerk):
            raise ValueError(f"Limits.jerk must be four finite numbers >= 0, got {self.jerk!r}")
        if self.ramp_type == 2 and not self.jerk[0] > 0.0:
            raise ValueError("Limits.jerk[0] (JERKMIN) must be > 0 for ramp type 2")

    def jerks(self) -> tuple[float, float, float, float]:
        """The four effective jerk limits (0 in J2..J4 replaced by J1)."""
        j1 = float(self.jerk[0])
        return (j1, float(self.jerk[1]) or j1, float(self.jerk[2]) or j1, float(self.jerk[3]) or j1)


# --------------------------------------------------------------------------------------------------------
# planners: velocity changes (v, a) -> (v1, 0) as raw segments


class _LinearPlanner:
    """Ramp types 0 (constant acceleration) and 1 (sin² acceleration bump, peak = limit, twice as long)."""

    __slots__ = ("acc", "dec", "kind", "k")

    def __init__(self, lim: Limits) -> None:
        self.acc = float(lim.acc)
        self.dec = float(lim.dec)
        self.kind = _ACC if lim.ramp_type == 0 else _SIN
        self.k = 1.0 if lim.ramp_type == 0 else 2.0  # mean acceleration of a sin² bump is half its peak

    def ramp_end(self, v: float, a: float) -> float:
        return v  # the acceleration is not a state of these ramps

    def change(self, v: float, a: float, v1: float, out: list) -> None:
        kind, k, acc, dec = self.kind, self.k, self.acc, self.dec
        if v * v1 < 0.0:  # reversal: slow down to 0 with DEC, then speed up with ACC
            out.append((k * abs(v) / dec, kind, -dec if v > 0.0 else dec))
            v = 0.0
        dv = v1 - v
        if dv != 0.0:
            lim = acc if abs(v1) > abs(v) else dec
            out.append((k * abs(dv) / lim, kind, lim if dv > 0.0 else -lim))


class _JerkPlanner:
    """Ramp type 2, limited jerk, with the DG's direction-independent acc/dec and J1..J4 [DG 1860-1972]."""

    __slots__ = ("j1", "j2", "j3", "j4", "acc", "dec")

    def __init__(self, lim: Limits) -> None:
        self.j1, self.j2, self.j3, self.j4 = lim.jerks()
        self.acc = float(lim.acc)
        self.dec = float(lim.dec)

    # All helpers below work in a "region frame": the velocity is >= 0 throughout, so a > 0 is speeding up
    # (limit acc; |a| up J1, |a| down J2) and a < 0 is slowing down (limit dec; |a| up J3, |a| down J4).

    def _ramp(self, a: float, b: float, out: list) -> None:
        """Ramp the acceleration linearly from a to b; append (duration, jerk) pieces."""
        if b > a:
            if a < 0.0:
                m = b if b < 0.0 else 0.0
                out.append(((m - a) / self.j4, self.j4))
                a = m
            if b > a:
                out.append(((b - a) / self.j1, self.j1))
        elif b < a:
            if a > 0.0:
                m = b if b > 0.0 else 0.0
                out.append(((a - m) / self.j2, -self.j2))
                a = m
            if b < a:
                out.append(((a - b) / self.j3, -self.j3))

    def _gain(self, a: float, b: float) -> float:
        """Velocity change of _ramp(a, b)."""
        g = 0.0
        if b > a:
            if a < 0.0:
                m = b if b < 0.0 else 0.0
                g += (m * m - a * a) / (2.0 * self.j4)
                a = m
            if b > a:
                g += (b * b - a * a) / (2.0 * self.j1)
        elif b < a:
            if a > 0.0:
                m = b if b > 0.0 else 0.0
                g += (a * a - m * m) / (2.0 * self.j2)
                a = m
            if b < a:
                g -= (b * b - a * a) / (2.0 * self.j3)
        return g

    def _region(self, v: float, a: float, v1: float, a1: float, out: list) -> None:
        """(v, a) -> (v1, a1) without leaving v >= 0: ramp to a peak, maybe hold at the limit, ramp to a1.

        a1 >= 0 when more velocity is needed, a1 <= 0 otherwise (the callers guarantee it).
        """
        j1, j2, j3, j4, acc, dec = self.j1, self.j2, self.j3, self.j4, self.acc, self.dec
        if a > acc:  # outside the limits: first bring the acceleration inside [DG 1896]
            t = (a - acc) / j2
            out.append((t, -j2))
            v += 0.5 * (a + acc) * t
            a = acc
        elif a < -dec:
            t = (-dec - a) / j4
            out.append((t, j4))
            v += 0.5 * (a - dec) * t
            a = -dec
        vdir = v + self._gain(a, a1)
        if abs(v1 - vdir) <= 1e-13 * (abs(v) + abs(v1) + abs(vdir)) + 1e-300:
            self._ramp(a, a1, out)
            return
        dv = v1 - v
        lo = a if a < 0.0 else 0.0
        hi = a if a > 0.0 else 0.0
        hold = 0.0
        if v1 > vdir:  # more velocity: a rises to a peak ap >= max(a, a1, 0)
            k = 0.5 / j1 + 0.5 / j2
            c = -lo * lo / (2.0 * j4) - hi * hi / (2.0 * j1) - a1 * a1 / (2.0 * j2)
            ap = math.sqrt(max((dv - c) / k, 0.0))
            if ap > acc:
                hold = (dv - c - k * acc * acc) / acc
                ap = acc
            ap = max(ap, a, a1)
        else:  # less velocity: a falls to a trough ap <= min(a, a1, 0)
            k = 0.5 / j3 + 0.5 / j4
            c = hi * hi / (2.0 * j2) + lo * lo / (2.0 * j3) + a1 * a1 / (2.0 * j4)
            ap = -math.sqrt(max((c - dv) / k, 0.0))
            if ap < -dec:
                hold = (c - k * dec * dec - dv) / dec
                ap = -dec
            ap = min(ap, a, a1)
        self._ramp(a, ap, out)
        if hold > 0.0:
            out.append((hold, 0.0))
        self._ramp(ap, a1, out)

    def ramp_end(self, v: float, a: float) -> float:
        """Velocity reached if the acceleration is ramped to 0 at once (ignoring a zero crossing)."""
        if (v >= 0.0) == (a >= 0.0):
            j = self.j2  # speeding up
        else:
            j = self.j4
        return v + a * abs(a) / (2.0 * j)

    def change(self, v: float, a: float, v1: float, out: list) -> None:
        j2, j3, j4 = self.j2, self.j3, self.j4
        for _ in range(8):
            m = 1.0 if v > 0.0 or (v == 0.0 and (a > 0.0 or (a == 0.0 and v1 >= 0.0))) else -1.0
            rv, ra, rv1 = m * v, m * a, m * v1
            seg: list = []
            done = False
            if rv1 >= 0.0:
                if ra < 0.0 and 2.0 * j4 * rv < ra * ra:
                    # even the gentlest braking passes v = 0 [DG 1922-1924]: ramp down with J4 through zero
                    r = math.sqrt(ra * ra - 2.0 * j4 * rv)
                    seg.append(((-ra - r) / j4, j4))
                    v, a = 0.0, -m * r
                else:
                    self._region(rv, ra, rv1, 0.0, seg)
                    done = True
            else:
                # reversal: reach v = 0 with a deceleration z that continues as acceleration [DG 1898, 1940-1942]
                z = min(self.acc, self.dec, math.sqrt(2.0 * j2 * -rv1))
                lo = ra if ra < 0.0 else 0.0
                hi = ra if ra > 0.0 else 0.0
                z = min(z, math.sqrt(lo * lo + 2.0 * j3 * (rv + hi * hi / (2.0 * j2))))
                if ra < 0.0:
                    z = max(z, math.sqrt(max(ra * ra - 2.0 * j4 * rv, 0.0)))
                self._region(rv, ra, 0.0, -z, seg)
                v, a = 0.0, -m * z
            out.extend((d, _JERK, m * j) for d, j in seg)
            if done:
                return
        raise RuntimeError("limited-jerk planner did not converge")  # pragma: no cover


def _integrate(segs: list, v: float, a: float) -> float:
    """Displacement of raw segments starting at velocity v, acceleration a."""
    p = 0.0
    for d, kind, x in segs:
        if kind == _JERK:
            p += d * (v + d * (0.5 * a + d * x / 6.0))
            v += d * (a + 0.5 * d * x)
            a += d * x
        elif kind == _ACC:
            p += d * (v + 0.5 * d * x)
            v += d * x
        elif kind == _SIN:
            p += d * (v + 0.25 * d * x)
            v += 0.5 * d * x
        else:
            p += d * x
            v = x
            a = 0.0
    return p


def _make_planner(lim: Limits) -> _LinearPlanner | _JerkPlanner:
    return _JerkPlanner(lim) if lim.ramp_type == 2 else _LinearPlanner(lim)


# --------------------------------------------------------------------------------------------------------


class ProfileGenerator:
    """Commanded position/velocity/acceleration of one axis, advanced one tick per ``step()``."""

    __slots__ = (
        "position", "velocity", "acceleration", "mode", "target",
        "_limits", "_planner", "_segs", "_idx", "_t", "_static", "_end_t", "_reach_t", "_end_p",
        "_clamp_from", "_clamp", "_dir", "_tgt",
        "_s_t0", "_s_t1", "_s_p", "_s_v", "_s_a", "_s_j", "_s_amp", "_s_w2", "_off", "_last_p",
    )  # fmt: skip
    position: float
    velocity: float
    acceleration: float
    mode: str
    target: float | None
    _segs: Sequence[_Rec]
    _idx: int
    _t: float
    _static: bool
    _end_t: float
    _reach_t: float
    _end_p: float
    _clamp_from: int
    _clamp: int
    _dir: float
    _tgt: float
    # the segment being sampled (_enter)
    _s_t0: float
    _s_t1: float
    _s_p: float
    _s_v: float
    _s_a: float
    _s_j: float
    _s_amp: float
    _s_w2: float
    _off: float
    _last_p: float

    def __init__(self, position: float = 0.0) -> None:
        self._limits: Limits | None = None
        self._planner: _LinearPlanner | _JerkPlanner | None = None
        self._dir = self._tgt = self._off = self._s_p = 0.0
        self.hold(position)

    # ---------------------------------------------------------------------------------------------- commands

    def hold(self, position: float | None = None) -> None:
        """Stand still at ``position`` (default: the current one): mode idle, v = a = 0."""
        if position is not None:
            self.position = float(position)
        self.velocity = 0.0
        self.acceleration = 0.0
        self.mode = "idle"
        self.target = None
        self._segs = ()
        self._static = True
        self._clamp = 0
        self._t = self._end_t = self._reach_t = 0.0
        self._end_p = self._last_p = self.position

    def shift(self, delta: float) -> None:
        """Move the position, the target and the running plan by ``delta`` qc (origin change, position wrap).

        Assigning ``position`` (and ``target``) directly while moving has the same effect on the next step.
        """
        self.position += delta
        if self.target is not None:
            self.target += delta
        self._moved()

    def move_to(self, target: float, limits: Limits) -> None:
        """POSA/POSR: go to ``target`` from the current state; re-plans a running move seamlessly."""
        target = float(target)
        if not math.isfinite(target):
            raise ValueError(f"target must be finite, got {target!r}")
        if self.mode == "position" and self.target == target and self._limits == limits:
            return  # a repeated POSA with nothing changed keeps the running plan
        pl = self._use(limits)
        p, v, a = self.position, self.velocity, self.acceleration
        stop: list = []
        pl.change(v, a, 0.0, stop)
        d_stop = _integrate(stop, v, a)
        dist = target - p
        scale = abs(dist) + abs(d_stop) + 1.0
        if abs(dist - d_stop) <= 1e-12 * scale:
            segs, m = stop, None  # the stop itself ends there
        else:
            m = 1.0 if dist > d_stop else -1.0
            rv, ra, rd = m * v, m * a, m * dist  # mirrored so that the final approach is forwards
            vp, cruise = self._peak(pl, rv, ra, rd, limits.vel, scale)
            segs = []
            pl.change(rv, ra, vp, segs)
            if cruise > 0.0:
                segs.append((cruise, _CRUISE, vp))
            pl.change(vp, 0.0, 0.0, segs)
            segs = [(d, k, m * x) for d, k, x in segs]
        self.mode = "position"
        self.target = target
        self._load(segs, m, target)

    def run_at(self, velocity: float, limits: Limits) -> None:
        """Speed mode (CSTART/CVEL): ramp to the signed ``velocity`` (clamped to ±vel) and keep it."""
        v1 = max(-limits.vel, min(limits.vel, float(velocity)))
        if self.mode == "velocity" and self._limits == limits and self._segs and self._segs[-1][6] == v1:
            return  # same CVEL again
        pl = self._use(limits)
        segs: list = []
        pl.change(self.velocity, self.acceleration, v1, segs)
        segs.append((_INF, _CRUISE, v1))
        self.mode = "velocity"
        self.target = None
        self._load(segs, 0.0, 0.0)

    def stop(self, limits: Limits) -> None:
        """MOTOR STOP / CSTOP / Esc: decelerate to standstill (final position free)."""
        pl = self._use(limits)
        segs: list = []
        pl.change(self.velocity, self.acceleration, 0.0, segs)
        self.mode = "stop"
        self.target = None
        self._load(segs, None, None)

    # ---------------------------------------------------------------------------------------------- the tick

    def step(self) -> None:
        """Advance one tick."""
        if self._static:
            return
        if self.position != self._last_p:
            self._moved()
        t = self._t + 1.0
        self._t = t
        if t >= self._s_t1 and not self._enter(t):
            return
        tau = t - self._s_t0
        a0 = self._s_a
        j = self._s_j
        v0 = self._s_v
        p = self._s_p + tau * (v0 + tau * (0.5 * a0 + tau * j * (1.0 / 6.0)))
        v = v0 + tau * (a0 + 0.5 * tau * j)
        a = a0 + tau * j
        amp = self._s_amp
        if amp:
            w2 = self._s_w2
            c = math.cos(w2 * tau)
            p += amp * (0.25 * tau * tau + (c - 1.0) / (2.0 * w2 * w2))
            v += amp * (0.5 * tau - math.sin(w2 * tau) / (2.0 * w2))
            a += amp * 0.5 * (1.0 - c)
        c = self._clamp
        if c:  # final approach: rounding must not move the samples back or past the end
            d = self._dir
            if d * (p - self._tgt) > 0.0:
                p = self._tgt
            elif c == 2 and d * (p - self.position) < 0.0:  # (the previous sample may be before the turn)
                p = self.position
            if d * v < 0.0:
                v = 0.0
            self._clamp = 2
        self.position = self._last_p = p
        self.velocity = v
        self.acceleration = a

    @property
    def done(self) -> bool:
        mode = self.mode
        if mode == "position":
            return self.position == self.target and self.velocity == 0.0 and self.acceleration == 0.0
        if mode == "velocity":
            return self._t >= self._reach_t - _END_EPS
        if mode == "stop":
            return self._static
        return True

    def remaining_ticks(self) -> int | None:
        """Ticks until ``done`` for the current plan (0 when done)."""
        if self.mode == "idle" or self.done:
            return 0
        end = self._reach_t if self.mode == "velocity" else self._end_t
        return max(0, math.ceil(end - self._t - _END_EPS))

    # ---------------------------------------------------------------------------------------------- internals

    def _use(self, limits: Limits) -> _LinearPlanner | _JerkPlanner:
        if self._planner is None or limits != self._limits:
            self._planner = _make_planner(limits)
            self._limits = limits
        return self._planner

    @staticmethod
    def _peak(pl, v: float, a: float, dist: float, vel: float, scale: float) -> tuple[float, float]:
        """Peak velocity vp (a = 0 there) and cruise time so that change(v,a->vp) + cruise + stop = dist.

        Mirrored frame: dist is at least the direct stopping distance.
        """

        def f(vp: float) -> float:
            segs: list = []
            pl.change(v, a, vp, segs)
            pl.change(vp, 0.0, 0.0, segs)
            return _integrate(segs, v, a) - dist

        fhi = f(vel)
        if fhi <= 0.0:
            return vel, -fhi / vel
        lo, flo = 0.0, f(0.0)
        vr = pl.ramp_end(v, a)
        if 0.0 < vr < vel:
            fr = f(vr)
            if fr <= 0.0:
                lo, flo = vr, fr
        hi = vel
        ftol = 1e-13 * scale
        side = 0
        for _ in range(200):  # Illinois false position: keeps f(lo) <= 0 < f(hi)
            if flo >= -ftol or hi - lo <= 1e-15 * vel:
                break
            x = (lo * fhi - hi * flo) / (fhi - flo)
            if not lo < x < hi:
                x = 0.5 * (lo + hi)
            fx = f(x)
            if fx <= 0.0:
                lo, flo = x, fx
                if side == -1:
                    fhi *= 0.5
                side = -1
            else:
                hi, fhi = x, fx
                if side == 1:
                    flo *= 0.5
                side = 1
        flo = f(lo)
        return lo, (-flo / lo if lo > 0.0 and flo < 0.0 else 0.0)

    def _load(self, raw: list, direction: float | None, end: float | None) -> None:
        """Turn raw segments into (t1, t0, p0, v0, a0, j, value, amp, w2) records and start them.

        ``direction``/``end``: sense and end position of the final approach, None = that of the last segment.
        """
        t = 0.0
        p, v, a = self.position, self.velocity, self.acceleration
        recs: list[_Rec] = []
        for d, kind, x in raw:
            if not d > 0.0:
                continue
            t1 = t + d
            if kind == _JERK:
                recs.append((t1, t, p, v, a, x, x, 0.0, 0.0))
                p += d * (v + d * (0.5 * a + d * x / 6.0))
                v += d * (a + 0.5 * d * x)
                a += d * x
            elif kind == _ACC:
                recs.append((t1, t, p, v, x, 0.0, x, 0.0, 0.0))
                p += d * (v + 0.5 * d * x)
                v += d * x
                a = 0.0
            elif kind == _SIN:
                recs.append((t1, t, p, v, 0.0, 0.0, x, x, 2.0 * math.pi / d))
                p += d * (v + 0.25 * d * x)
                v += 0.5 * d * x
                a = 0.0
            else:
                recs.append((t1, t, p, x, 0.0, 0.0, x, 0.0, 0.0))
                if d < _INF:
                    p += d * x
                v, a = x, 0.0
            t = t1
        self._segs = recs
        self._end_t = t if t < _INF else recs[-1][1]
        self._reach_t = self._end_t
        self._end_p = p
        if direction is None:
            v_last = recs[-1][3] if recs else 0.0
            direction = 1.0 if v_last > 0.0 else -1.0 if v_last < 0.0 else 0.0
        if end is None:
            end = p
        self._dir, self._tgt = direction, end
        # the samples are clamped from the last start of a segment at v = 0 or moving the other way on
        i = len(recs) - 1
        while i >= 0 and recs[i][3] * direction > 0.0:
            i -= 1
        self._clamp_from = i + 1 if direction else 1 << 62
        self._clamp = 0
        self._off = 0.0
        self._last_p = self.position
        self._t = 0.0
        self._idx = -1
        self._s_t1 = -_INF
        self._static = False
        if self._end_t <= _END_EPS:  # a change shorter than that is done at once
            if self.mode == "velocity":
                self.velocity, self.acceleration = recs[-1][3], 0.0
            else:
                self._finish()

    def _enter(self, t: float) -> bool:
        """Move to the segment containing tick t; False (and the final state set) when the plan is over."""
        recs = self._segs
        i = self._idx
        n = len(recs)
        while True:
            i += 1
            if i >= n:
                self._finish()
                return False
            if t < recs[i][0] - _END_EPS:
                break
        self._idx = i
        r = recs[i]
        self._s_t1 = r[0] - _END_EPS
        self._s_t0 = r[1]
        self._s_p, self._s_v, self._s_a, self._s_j = r[2] + self._off, r[3], r[4], r[5]
        self._s_amp, self._s_w2 = r[7], r[8]
        if i >= self._clamp_from and not self._clamp:
            self._clamp = 1
        return True

    def _moved(self) -> None:
        """``position`` was changed from outside: carry the plan along (the target follows ``target``)."""
        d = self.position - self._last_p
        self._last_p = self.position
        if self._static:
            return
        self._off += d
        self._s_p += d
        self._end_p += d
        if self.mode == "position":
            assert self.target is not None  # move_to sets the mode and the target together
            self._tgt = self.target
        else:
            self._tgt = self._tgt + d

    def _finish(self) -> None:
        self.position = self._last_p = self._tgt if self.mode == "position" else self._end_p
        self.velocity = 0.0
        self.acceleration = 0.0
        self._clamp = 0
        self._static = True
