"""What each APOSS command does on the simulated controller: name → fn(controller, vm, args).

A function returns the command's value, None, or a Wait the program blocks on. Positions and velocities
the program gives are user units and VELRES fractions (spec a); the axis works in qc.
"""

from __future__ import annotations

from motiontool.kernel import io as iomod
from motiontool.kernel.command_base import (
    COMMANDS,
    Deadline,
    InputWait,
    Until,
    WaitT,
    command,
    motion_allowed,
    motion_limits,
    position_to,
)
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.homing import Homing
from motiontool.kernel.parameters import is_axis_parameter, is_global_parameter, is_user_parameter
from motiontool.kernel.sysvars import read_sysvar


@command("POSA")
def posa(ctl, vm, args):
    return position_to(ctl, vm, ctl.qc(args[0]), "POSA")


@command("POSR")
def posr(ctl, vm, args):
    # CR 3502-3520: relative to the actual position
    return position_to(ctl, vm, ctl.axis.apos + ctl.axis.scaling.uu_to_qc(args[0]), "POSR")


@command("VEL")
def vel(ctl, vm, args):
    ctl.motion.vel = args[0]


@command("ACC")
def acc(ctl, vm, args):
    ctl.motion.acc = args[0]


@command("DEC")
def dec(ctl, vm, args):
    ctl.motion.dec = args[0]


@command("CVEL")
def cvel(ctl, vm, args):
    ctl.program_data.speed_value = args[0]
    if ctl.axis.mode == "speed":  # a new CVEL in speed mode changes the running speed
        ctl.axis.run_at(ctl.axis.scaling.velocity(args[0]), motion_limits(ctl, args[0]))


@command("CSTART")
def cstart(ctl, vm, args):
    motion_allowed(ctl, "CSTART")
    v = ctl.program_data.speed_value
    if ctl.limit_blocked_direction and v * ctl.limit_blocked_direction > 0:
        raise ControllerError(198, "speed mode again in the direction of the violated limit")
    ctl.axis.run_at(ctl.axis.scaling.velocity(v), motion_limits(ctl, v))


@command("CSTOP")
def cstop(ctl, vm, args):
    ctl.axis.stop(motion_limits(ctl), remember=False)


@command("MOTOR STOP")
def motor_stop(ctl, vm, args):
    axis = ctl.axis
    axis.stop(motion_limits(ctl))
    if vm is None or vm.effective_nowait:
        return None
    return Until(lambda: axis.mode == "idle")


@command("MOTOR ON")
def motor_on(ctl, vm, args):
    ctl.axis.motor_on()


@command("MOTOR OFF")
def motor_off(ctl, vm, args):
    ctl.axis.motor_off()


@command("CONTINUE")
def continue_(ctl, vm, args):
    motion = ctl.axis.stopped_motion
    if motion is None:
        return None
    motion_allowed(ctl)
    if not ctl.axis.control_on:  # CONTINUE after MOTOR OFF switches the control on again (CR 564-578)
        ctl.axis.motor_on()
    ctl.axis.stopped_motion = None
    kind, value, limits = motion
    if kind == "position":
        ctl.axis.move_to(value, limits)
        if vm is not None and not vm.effective_nowait:
            return Until(ctl.axis.position_reached)
    else:
        ctl.axis.run_at(value, limits)
    return None


@command("WAITAX")
def waitax(ctl, vm, args):
    # A synchronisation has no target position (AXEND bit 1 clear, kernel-spec p.4): WAITAX returns at once
    # instead of blocking the program for as long as the axis follows the master.
    if ctl.axis.mode == "sync":
        return None
    return Until(ctl.axis.position_reached)


@command("HOME", "INDEX")
def home(ctl, vm, args, index_only=False):
    motion_allowed(ctl, "INDEX" if index_only else "HOME", home_run=not index_only)
    p, axis = ctl.params, ctl.axis
    home_vel = p["HOME_VEL"]
    if home_vel == 0:
        raise ControllerError(107)
    s = axis.scaling
    ramp = s.acceleration(max(1, p["HOME_RAMP"]))  # DG 9224-9246: ramp time = VELRES / HOME_RAMP × RAMPMIN
    limits = axis.limits(abs(s.velocity(home_vel)), ramp, ramp, 0, (0, 0, 0, 0))
    functions = ctl.input_functions()
    if not index_only and iomod.HOME_SWITCH not in functions:
        raise ControllerError(183, "HOME needs an input with I_FUNCTION 1 or 2 (home switch)")

    def switch() -> bool:
        return ctl._function_input(iomod.HOME_SWITCH, ctl.input_functions())

    home_type = p["HOME_TYPE"]
    axis.homing = Homing(axis, home_type, s.velocity(home_vel), limits, 0 if index_only else p["HOME_OFFSET"],
                         switch, index_only=index_only)
    axis.mode = "homing"
    def abandon() -> None:
        axis.homing = None
        axis.stop(limits, remember=False)

    # CR 1505: HOME runs to the end even with NOWAIT ON; an interrupt abandons it (CR 1498-1500).
    return Until(lambda: axis.homing is None, resumable=False, on_abandon=abandon)


COMMANDS["INDEX"] = lambda ctl, vm, args: home(ctl, vm, args, index_only=True)


# --- origins ---------------------------------------------------------------------------------------------
@command("DEFORIGIN")
def deforigin(ctl, vm, args):
    shift = ctl.axis.apos
    ctl.axis.shift_origin(shift)
    ctl.axis.limit_offset += shift
    ctl.temp_origin = 0


@command("DEFCORIGIN")
def defcorigin(ctl, vm, args):
    ctl.axis.shift_origin(round(ctl.axis.cpos))


@command("SETORIGIN")
def setorigin(ctl, vm, args):
    ctl.temp_origin = args[0]  # absolute, relative to the real zero (CR 3984-4003)


@command("RSTORIGIN")
def rstorigin(ctl, vm, args):
    ctl.temp_origin = 0


# --- waiting and time ----------------------------------------------------------------------------------
@command("DELAY")
def delay(ctl, vm, args):
    return Deadline(ctl, ctl.time_ms + max(0, args[0]))  # interrupts count toward the delay (C:980-989)


@command("WAITT")
def waitt(ctl, vm, args):
    return WaitT(ctl, max(0, args[0]))


@command("WAITI")
def waiti(ctl, vm, args):
    number = args[0]
    state = 1 if len(args) < 2 or args[1] == "ON" else 0
    return InputWait(lambda: ctl.io.inputs.get(number, 0) == state)


@command("WAITP")
def waitp(ctl, vm, args):
    target = args[0]
    start = ctl.uu(ctl.axis.apos)
    up = target >= start
    return Until(lambda: (ctl.uu(ctl.axis.apos) >= target) if up else (ctl.uu(ctl.axis.apos) <= target))


@command("NOWAIT")
def nowait(ctl, vm, args):
    vm.nowait = args[0] == "ON"


@command("TIME")
def time_(ctl, vm, args):
    return ctl.time_ms


@command("EXIT")
def exit_(ctl, vm, args):
    vm.ended = True


# --- readouts --------------------------------------------------------------------------------------------
COMMANDS.update({
    "APOS": lambda c, vm, a: c.uu(c.axis.apos),
    "CPOS": lambda c, vm, a: c.uu(c.axis.cpos),
    "TRACKERR": lambda c, vm, a: c.axis.scaling.qc_to_uu(c.axis.tracking_error),
    "AVEL": lambda c, vm, a: c.avel(),
    "AXEND": lambda c, vm, a: c.axis.axend(),
    "STAT": lambda c, vm, a: c.stat(),
    "ERRNO": lambda c, vm, a: c.error,
    "IPOS": lambda c, vm, a: c.uu(c.markers.ipos_qc()),
    "MIPOS": lambda c, vm, a: c.markers.mipos(),
    "APOSDIFF": lambda c, vm, a: _posdiff(c.uu(c.axis.apos), a[0]),
    "CPOSDIFF": lambda c, vm, a: _posdiff(c.uu(c.axis.cpos), a[0]),
    "IPOSDIFF": lambda c, vm, a: _posdiff(c.uu(c.markers.ipos_qc()), a[0]),   # CR 1817-1842
    "MAPOSDIFF": lambda c, vm, a: _posdiff(c.master.mapos, a[0]),             # CR 2152-2174, MAPOS as read (K46)
    "MIPOSDIFF": lambda c, vm, a: _posdiff(c.markers.mipos(), a[0]),          # CR 2316-2338
    "SYNCSTAT": lambda c, vm, a: c.syncstat(),
    "SYNCERR": lambda c, vm, a: c.syncerr(),
    "MAPOS": lambda c, vm, a: c.master.mapos,
    "MAVEL": lambda c, vm, a: c.master.mavel,
})


def _posdiff(now: int, old: int) -> int:
    """CR 260-289: a difference beyond POS_LIMIT = 0x3FFFFFFF is an overflow of the 31-bit position."""
    d = now - old
    if d > 0x3FFFFFFF:
        d -= 0x80000000
    elif d < -0x3FFFFFFF:
        d += 0x80000000
    return d


# --- I/O -------------------------------------------------------------------------------------------------
def _pin(number):
    """OUT X59/3 1: connector pins of the MCO map to output numbers; other connectors are unknown (171)."""
    if isinstance(number, str):
        connector, _, pin = number.partition("/")
        if connector == "X59" and pin.isdigit():
            return int(pin)
        raise ControllerError(171, f"connector pin {number} is not valid")  # CR 3127-3128
    return number


@command("IN")
def in_(ctl, vm, args):
    return ctl.io.read(_pin(args[0]))


@command("INB")
def inb(ctl, vm, args):
    return ctl.io.read_byte(args[0])


@command("INAD")
def inad(ctl, vm, args):
    return ctl.io.read_analog(args[0])


@command("OUT")
def out(ctl, vm, args):
    ctl.io.write(_pin(args[0]), args[1])


@command("OUTB")
def outb(ctl, vm, args):
    ctl.io.write_byte(args[0], args[1])


@command("OUTAN")
def outan(ctl, vm, args):
    # CR 3157-3180: with MOTOR OFF the bus reference drives the FC open loop, 0x4000 = 100 %
    ctl.axis.open_loop_reference = args[0] / 0x4000 * ctl.axis.scaling.vmax


@command("OUTDA")
def outda(ctl, vm, args):
    ctl.io.analog[args[0]] = args[1]


# --- parameters --------------------------------------------------------------------------------------------
@command("GET")
def get(ctl, vm, args):
    return ctl.params.get(args[0])


@command("SET")
def set_(ctl, vm, args):
    ctl.params.set(args[0], args[1])


@command("SET PID")
def set_pid(ctl, vm, args):
    ctl.program_data.pid_gains[args[0]] = args[1]


@command("PID")
def pid(ctl, vm, args):
    """CR 3409-3444: u(n) = (KP·e(n) + KD·(e(n) − e(n−1)) + KI·Σe) / timer, Σe limited by KILIM."""
    g = ctl.program_data.pid_gains
    e = args[0]
    last, total = ctl.program_data.pid_state
    total += e
    if g["KILIM"]:
        total = max(-g["KILIM"], min(g["KILIM"], total))
    ctl.program_data.pid_state = [e, total]
    return int((g["KPROP"] * e + g["KDER"] * (e - last) + g["KINT"] * total) / max(1, g["TIMER"]))


@command("LINKGPAR")
def linkgpar(ctl, vm, args):
    number, text, low, high, kind = args
    if not 1900 <= number <= 1999:
        raise ControllerError(155, f"LINKGPAR {number}: only 19-00 … 19-99 can be linked")
    ctl.program_data.linked[number] = (text, low, high, kind)
    value = ctl.params.values.get(number, 0)
    ctl.params.values[number] = max(low, min(high, value))  # clamped to the linked range


@command("SAVE AXPARS")
def save_axpars(ctl, vm, args):
    """CR 3654-3656: "SAVE AXPARS saves all other axes parameters" — 32-xx and 33-0x … 33-4x (decision K50)."""
    ctl.params.save(is_axis_parameter)


@command("SAVE GLBPARS")
def save_glbpars(ctl, vm, args):
    """CR 3654-3660: "the range of global parameters (group 30-5* [33-5*] and group 33-8*), and application
    parameters (group 19-**)"; DG 10849 saves CANBAUD (33-91) with it, so 33-9x too (decision K50)."""
    ctl.params.save(lambda index: is_global_parameter(index) or is_user_parameter(index))


@command("SAVE USRPARS", "SAVEPROM")
def save_usrpars(ctl, vm, args):
    ctl.params.save(is_user_parameter)


@command("SAVE ARRAYS")
def save_arrays(ctl, vm, args):
    return None


@command("DELETE ARRAYS")
def delete_arrays(ctl, vm, args):
    ctl.arrays.delete()


# --- errors and interrupts --------------------------------------------------------------------------------
@command("ERRCLR")
def errclr(ctl, vm, args):
    ctl.clear_error()
    fc300.reset_alarm(ctl)   # CR 1315: "ERRCLR also resets FC 300 alarms by means of Bit 7 of the control word"


@command("DISABLE")
def disable(ctl, vm, args):
    ctl.interrupts.disable(args[0])


@command("ENABLE")
def enable(ctl, vm, args):
    ctl.interrupts.enable(args[0])


# --- recording --------------------------------------------------------------------------------------------
@command("TESTSETP")
def testsetp(ctl, vm, args):
    ctl.recorder.setp(args[0], list(args[1:4]), args[4])


@command("TESTSETINDEX")
def testsetindex(ctl, vm, args):
    ctl.recorder.set_indices(list(args))


@command("TESTSETTIME")
def testsettime(ctl, vm, args):
    ctl.recorder.interval_ms = max(1, args[0])


@command("TESTSETDEST")
def testsetdest(ctl, vm, args):
    ctl.recorder.array = None if args[0] == "DYNMEM" else args[0]


@command("TESTSETTYPE")
def testsettype(ctl, vm, args):
    ctl.recorder.cyclic = args[0] == 1


@command("TESTSTART")
def teststart(ctl, vm, args):
    ctl.recorder.start(args[0], ctl.time_ms)


@command("TESTSTOP")
def teststop(ctl, vm, args):
    ctl.recorder.stop(args[0])


@command("PRINTDEV")
def printdev(ctl, vm, args):
    ctl.program_data.print_device = args[0]


@command("SYSVAR")
def sysvar(ctl, vm, args):
    return read_sysvar(ctl, args[0]) or 0


# the synchronisation, marker and CAM commands, the CAN commands and those without a simulated device live in
# their own modules; importing them registers them
from motiontool.kernel import axis_readouts, can_commands, comopt, fc300, lcp, sync_commands, unserved  # noqa: E402, F401, I001
