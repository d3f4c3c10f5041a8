"""Readouts and waits about the axis's own motion (issue 25): _GETVEL (the measuring time of AVEL and MAVEL),
JERKFINVEL and JERKSTOPDIST (what a jerk-limited ramp from the present motion would do), WAITNDX (the encoder's
index pulse)."""

from __future__ import annotations

from collections import deque

from motiontool.kernel.command_base import Until, command
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.profile import Limits, _integrate, _JerkPlanner


@command("_GETVEL")
def getvel(ctl, vm, args):
    """CR 295-301: sets the measuring time of AVEL and MAVEL, kept "from then on" (not only for this program).
    The value returned is not documented: the measuring time it replaces, so a program can put it back (K121)."""
    axis = ctl.axis
    before = axis.raw_history.maxlen - 1
    ms = max(1, args[0])
    axis.raw_history = deque(axis.raw_history, maxlen=ms + 1)
    ctl.master.set_velocity_window(ms)
    return before


def _jerk_planner(ctl, dec_qc_ms2: float) -> _JerkPlanner:
    """RAMPTYPE 2 with the JERKMIN parameters, whatever RAMPTYPE is set (CR 1850, 1868-1870: "This also works if
    … not … a RAMPTYPE 2 movement"); jerk = maximum acceleration / JERKMIN (DG 9044-9086), 0 = as JERKMIN."""
    p, s = ctl.params, ctl.axis.scaling
    j1 = max(1, p["JERKMIN"])
    jerk = tuple(s.amax / t for t in [j1] + [p[n] or j1 for n in ("JERKMIN2", "JERKMIN3", "JERKMIN4")])
    return _JerkPlanner(Limits(s.vmax, s.amax, dec_qc_ms2, 2, jerk))


@command("JERKFINVEL")
def jerkfinvel(ctl, vm, args):
    """CR 1846-1853: the velocity reached if the present acceleration is ramped to 0 with the JERKMIN times, in
    VELRES units (signed) "so you can use it without conversion for a VEL or CVEL command"."""
    s, pg = ctl.axis.scaling, ctl.axis.profile
    final = _jerk_planner(ctl, s.amax).ramp_end(pg.velocity, pg.acceleration)
    return round(final * s.velres / s.vmax)


@command("JERKSTOPDIST")
def jerkstopdist(ctl, vm, args) -> int:
    """CR 1862-1870: the distance (UU) a RAMPTYPE 2 stop from the present motion needs with deceleration `dec`
    (VELRES units) — the same stop this controller's profile generator runs (K121); signed like the motion."""
    s, pg = ctl.axis.scaling, ctl.axis.profile
    if args[0] <= 0:
        raise ControllerError(183, f"JERKSTOPDIST {args[0]}: the deceleration must be > 0")
    segs: list = []
    _jerk_planner(ctl, s.acceleration(args[0])).change(pg.velocity, pg.acceleration, 0.0, segs)
    return s.qc_to_uu(_integrate(segs, pg.velocity, pg.acceleration))


@command("WAITNDX")
def waitndx(ctl, vm, args):
    """DG 7056: "waits until the next index position is reached", t = timeout in ms; DG 11750-11754: error 179
    "The command WAITNDX was executed and the timeout listed was exceeded". The index pulse comes once per
    revolution (4 × ENCODER qc) in either direction; t <= 0 waits without a timeout (K121)."""
    axis = ctl.axis
    period = max(1, axis.index_period())
    start = axis.raw // period
    end = ctl.time_ms + args[0] if args[0] > 0 else None

    def reached() -> bool:
        if axis.raw // period != start:
            return True
        if end is not None and ctl.time_ms >= end:
            raise ControllerError(179, f"no index pulse within {args[0]} ms")
        return False

    return Until(reached)

