"""The FC 300 frequency converter the MCO 305 sits in, as far as a program reaches it: its parameters
(GETVLT/GETVLTSUB/SETVLT/SETVLTSUB, CR 1387-1428, 4009-4053; table in kernel/fc300_table.py), its control word in
MOTOR OFF state (VLTCONTROL), its alarm (VLTALARMSTAT, VLTERRCLR; ERRCLR resets it with bit 7, CR 1315). K124-K126.

A host trips the drive with `trip` (there is no electrical model that could trip it by itself).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from motiontool.kernel.command_base import command
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.fc300_table import FC_PARAMETERS, FCParam
from motiontool.kernel.vm import Wait

READ_MS = 20     # DG 6190: "The GETVLT commands are typically 20 ms or faster"
WRITE_MS = 100   # DG 6192: a write "may take up to 100, or 500 ms, or even more" (the short end, K124)

# FC profile control word (FC 300 Design Guide, "Control Word According to FC Profile"): 1 = the named function
CTW_NO_COAST, CTW_START, CTW_RESET, CTW_DATA_VALID = 1 << 3, 1 << 6, 1 << 7, 1 << 10
CTW_RUN = 0x047C   # the Design Guide's start telegram: ramp, no coasting, no quick stop, use ramp, start, data valid
CTW_OFF = CTW_RUN & ~CTW_NO_COAST   # before any VLTCONTROL in MOTOR OFF: coast (assumed)
# FC profile status word: 1 = the named state
STW_CONTROL_READY, STW_DRIVE_READY, STW_ENABLE, STW_TRIP = 1 << 0, 1 << 1, 1 << 2, 1 << 3
STW_SPEED_AT_REF, STW_BUS_CONTROL, STW_FREQ_OK, STW_IN_OPERATION = 1 << 8, 1 << 9, 1 << 10, 1 << 11


@dataclass
class FC300:
    written: dict[tuple[int, int], int] = field(default_factory=dict)  # SETVLT values: RAM only (CR 4019-4021)
    control_word: int = CTW_OFF      # what VLTCONTROL wrote (used in MOTOR OFF state only)
    alarm: int = 0                   # the FC alarm number, 0 = none

    def value(self, p: FCParam, index: int = 0) -> int:
        return self.written.get((p.number, index), p.default)


def drive(ctl) -> FC300:
    # the drive's RAM belongs to the controller, not to a program: a value set survives the program's end
    return vars(ctl).setdefault("fc300", FC300())


def trip(ctl, alarm: int) -> None:
    """The FC 300 trips with `alarm`. With position control on the MCO sees "Not ready" in the status word and
    stops with error 113 (DG 11528-11533: "FC 300 is not enabled but the PID controller MCO 305 is active")."""
    drive(ctl).alarm = alarm
    if ctl.axis.control_on:
        ctl.axis.motor_off()   # a tripped drive lets the motor coast whatever the MCO asks
        ctl.raise_error(ControllerError(113, f"FC 300 alarm {alarm}"))


def reset_alarm(ctl) -> None:
    """Bit 7 of the control word (ERRCLR, VLTERRCLR): the FC leaves its trip."""
    drive(ctl).alarm = 0


def control_word(ctl) -> int:
    """16-00: the MCO sends its run word while it controls the motor, the VLTCONTROL word in MOTOR OFF state."""
    return CTW_RUN if ctl.axis.control_on else drive(ctl).control_word


def status_word(ctl) -> int:
    fc = drive(ctl)
    stw = STW_SPEED_AT_REF | STW_BUS_CONTROL | STW_FREQ_OK   # 8-02 = [5] Option C0: the bus controls
    if fc.alarm:
        return stw | STW_TRIP
    stw |= STW_CONTROL_READY | STW_DRIVE_READY
    ctw = control_word(ctl)
    if ctw & CTW_NO_COAST:
        stw |= STW_ENABLE
        if ctw & CTW_START:
            stw |= STW_IN_OPERATION
    return stw


def _rpm(ctl) -> float:
    """The motor speed from the slave encoder: qc/ms → revolutions per minute (4 qc per encoder line)."""
    return ctl.axis.measured_velocity() * 60_000 / (4 * ctl.axis.scaling.encoder_ppr)


def _frequency(ctl) -> int:
    # f = n · poles / 120 (synchronous speed); 16-13 in 0.1 Hz (CR 1394-1396), positive either way
    poles = drive(ctl).value(FC_PARAMETERS[139])
    return round(abs(_rpm(ctl)) * poles / 120 * 10)


def _reference_percent(ctl) -> int:
    top = drive(ctl).value(FC_PARAMETERS[303]) / 1000
    return round(_rpm(ctl) / top * 1000) if top else 0


_READOUTS = {
    1600: control_word,
    1601: lambda ctl: round(_rpm(ctl) * 1000),
    1602: _reference_percent,
    1603: status_word,
    1613: _frequency,
    1617: lambda ctl: round(_rpm(ctl)),
}


def _parameter(number: int) -> FCParam:
    p = FC_PARAMETERS.get(number)
    if p is None:   # DG 11363: 112 "Illegal parameter number"
        raise ControllerError(112, f"the simulated FC 300 has no parameter {number} (docs/fc300.md)")
    return p


def _index(p: FCParam, index: int) -> int:
    if not 0 <= index < max(1, p.size):   # a parameter without index has only index 0 (FC "sub index" rule)
        raise ControllerError(183, f"{p.label} {p.name} has no index {index}")
    return index


def read(ctl, number: int, index: int = 0) -> int:
    p = _parameter(number)
    index = _index(p, index)
    readout = _READOUTS.get(number)
    return readout(ctl) if readout is not None else drive(ctl).value(p, index)


def write(ctl, number: int, index: int, value: int) -> None:
    p = _parameter(number)
    index = _index(p, index)
    fc = drive(ctl)
    if p.read_only:   # DG 7594: "Parameter groups 16-** and 34-** are read only"; 112 as SET of a 34-** (K124)
        raise ControllerError(112, f"{p.label} {p.name} is read only")
    low = fc.value(FC_PARAMETERS[p.low_par]) if p.low_par else p.low
    high = fc.value(FC_PARAMETERS[p.high_par]) if p.high_par else p.high
    if not low <= value <= high:
        raise ControllerError(183, f"{value} is outside {p.label} {p.name}'s range {low}..{high}")
    fc.written[(number, index)] = int(value)


class _Transfer(Wait):
    """The command's telegram to the FC and its answer: the program waits `ms`, then gets the answer."""

    def __init__(self, ctl, ms: int, answer):
        self.ctl, self.answer = ctl, answer
        self.end = ctl.time_ms + ms

    def done(self) -> bool:
        if self.ctl.time_ms < self.end:
            return False
        self.value = self.answer()
        return True


def _read_command(ctl, number: int, index: int) -> _Transfer:
    read(ctl, number, index)   # an unknown number or index stops the program now, not after the transfer
    return _Transfer(ctl, READ_MS, lambda: read(ctl, number, index))


def _write_command(ctl, number: int, index: int, value: int) -> _Transfer:
    write(ctl, number, index, value)
    return _Transfer(ctl, WRITE_MS, lambda: None)


@command("GETVLT")
def getvlt(ctl, vm, args):
    """CR 1390-1391: "access to the operating data … or to the configurations … of the FC 300"."""
    return _read_command(ctl, int(args[0]), 0)


@command("GETVLTSUB")
def getvltsub(ctl, vm, args):
    return _read_command(ctl, int(args[0]), int(args[1]))


@command("SETVLT")
def setvlt(ctl, vm, args):
    """CR 4019-4021: "The parameter alterations are only stored in RAM"."""
    return _write_command(ctl, int(args[0]), 0, int(args[1]))


@command("SETVLTSUB")
def setvltsub(ctl, vm, args):
    return _write_command(ctl, int(args[0]), int(args[1]), int(args[2]))


@command("VLTALARMSTAT")
def vltalarmstat(ctl, vm, args):
    """DG 7051: "returns if an alarm is active or not": 1 or 0 (K125)."""
    return 1 if drive(ctl).alarm else 0


@command("VLTERRCLR")
def vlterrclr(ctl, vm, args):
    """DG 7053: "clears a VLT-alarm"; the MCO's own pending error stays (that is ERRCLR)."""
    reset_alarm(ctl)


@command("VLTCONTROL")
def vltcontrol(ctl, vm, args):
    """DG 7052: "sets the VLT control word in MOTOR OFF state". While position control is on the MCO writes the
    control word itself, so the value is not taken (K125); bit 7 going to 1 resets an alarm as on the FC."""
    word = int(args[0]) & 0xFFFF
    if ctl.axis.control_on:
        ctl.message("VLTCONTROL is ignored while the position control is on (MOTOR ON): it sets the control word "
                    "in MOTOR OFF state only (DG 7052)")
        return
    fc = drive(ctl)
    if word & CTW_RESET and not fc.control_word & CTW_RESET:
        reset_alarm(ctl)
    fc.control_word = word
