"""What every command module shares: the command table and its `command` decorator, the waits a command returns,
and the motion checks (limits, pending errors, soft limits) of the positioning and synchronising commands.

A command module (commands.py, sync_commands.py, can_commands.py, ...) imports this and registers its commands
with `@command`; kernel/commands.py imports every command module, so loading it loads the whole table
(kernel/controller.py does). None of them imports another's module: the table is assembled in one place.
"""

from __future__ import annotations

from collections.abc import Callable

from motiontool.kernel.errors import ControllerError
from motiontool.kernel.vm import Wait

COMMANDS: dict[str, Callable[..., object]] = {}  # name → fn(ctl, vm, args): a value, a Wait or None


def command(*names):
    def register(fn):
        for name in names:
            COMMANDS[name] = fn
        return fn
    return register


# --- waits ---------------------------------------------------------------------------------------------
class Until(Wait):
    def __init__(self, condition, value=None, resumable=True, on_abandon=None):
        self.done = condition  # Wait.done, checked every tick: the condition itself (one call less per tick)
        self.value = value
        self.resumable = resumable
        self.on_abandon = on_abandon

    def abandon(self) -> None:
        if self.on_abandon is not None:
            self.on_abandon()


class InputWait(Until):
    """WAITI: ends only when an input changes (kernel/steady_line.py runs stretches of ticks while none can)."""


class Deadline(Until):
    """DELAY: ends at time_ms >= end (kernel/steady_line.py runs stretches of ticks up to it)."""

    def __init__(self, ctl, end: int):
        super().__init__(lambda: ctl.time_ms >= end)
        self.end = end


class WaitT(Wait):
    """WAITT restarts its time after an interrupt (DG 6301-6303)."""

    def __init__(self, ctl, ms: int):
        self.ctl, self.ms = ctl, ms
        self.end = ctl.time_ms + ms

    def done(self) -> bool:
        return self.ctl.time_ms >= self.end

    def resume(self) -> None:
        self.end = self.ctl.time_ms + self.ms


# --- motion helpers ------------------------------------------------------------------------------------
def motion_limits(ctl, vel_value=None, for_stop=False):
    p, a, m = ctl.params, ctl.axis, ctl.motion
    s = a.scaling
    vel = s.velocity(abs(vel_value if vel_value is not None else (m.vel if m.vel is not None else p["DFLTVEL"])))
    acc = s.acceleration(m.acc if m.acc is not None else p["DFLTACC"])
    dec = s.acceleration(m.dec if m.dec is not None else p["DFLTACC"])  # DEC never set → DFLTACC (CR 747)
    ramp = p["RAMPTYPE"]
    jerk = (0, 0, 0, 0)
    if ramp in (1, 2):
        j1 = max(1, p["JERKMIN"])
        times = [j1] + [p[n] or j1 for n in ("JERKMIN2", "JERKMIN3", "JERKMIN4")]
        jerk = tuple(s.amax / t for t in times)  # jerk = max. acceleration / JERKMIN (DG 9044-9086)
    return a.limits(vel, acc, dec, ramp, jerk)


def motion_allowed(ctl, command: str = "", home_run: bool = False) -> None:
    """DG 11444-11456: no motion while an error is pending (105) or, with 33-00 HOME_FORCE 1, before a completed
    HOME (106) — HOME itself is the home run that is demanded (DG 9199-9204). A motion command does not switch
    the motor on (CR 624-648: CSTART does not imply MOTOR ON, K11): the motion waits, and the user is told why."""
    if ctl.error:
        raise ControllerError(105, f"error {ctl.error} is pending")
    if not home_run and ctl.params["HOME_FORCE"] == 1 and not ctl.homed:
        raise ControllerError(106, "HOME_FORCE 1: HOME first (after power on or a changed axis parameter)")
    if command and not ctl.axis.control_on:
        line = ctl.vm.line if ctl.vm is not None else None
        ctl.message(f"{command} waits: the position control is off (MOTOR OFF); MOTOR ON, ERRCLR or CONTINUE "
                    "switches it on", line)


def check_soft_limits(ctl, target_qc: int) -> None:
    p = ctl.params
    offset = ctl.axis.limit_offset
    blocked = ctl.limit_blocked_direction  # DG 11872-11876: after a cleared limit error, 198 that way
    if blocked and (target_qc - ctl.axis.apos) * blocked > 0:
        raise ControllerError(198, "move again in the direction of the violated limit")
    if p["SWNEGLIMACT"] and target_qc < p["NEGLIMIT"] - offset:
        raise ControllerError(111, f"target {target_qc} qc below NEGLIMIT")
    if p["SWPOSLIMACT"] and target_qc > p["POSLIMIT"] - offset:
        raise ControllerError(111, f"target {target_qc} qc above POSLIMIT")


def position_to(ctl, vm, target_qc: int, command: str):
    motion_allowed(ctl, command)
    check_soft_limits(ctl, target_qc)  # CR 3451: a target beyond an active limit is not started (111)
    axis = ctl.axis
    axis.move_to(target_qc, motion_limits(ctl))
    if vm is None or vm.effective_nowait:
        return None
    return Until(axis.position_reached)
