"""SYSVAR indices the simulator serves (docs/sysvar.md). Axis process data are 4096 + n (DG 4831-4888,
5336); SDO-style indices are 0x01000000 + (index << 8) + subindex (CR 2039)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

AXIS_BASE = 4096
# SYSVAR 0x01iiiiss reads object 0xiiii sub ss: kernel/objdict.py puts its reader here when it is loaded (the
# dictionary is built on these process data, so this module imports nothing of it)
object_reader: Callable[[Any, int], int | None] | None = None
GUARD_ERROR_ID = 67   # SYSVAR 67 = 0x01220244: the node a CANINI guarding failed on (CR 471)

# n → (name shown by the oscilloscope as "Axis: Name [Index]", unit, reader(controller) in qc or raw units)
AXIS_PROCESS_DATA = {
    1: ("REG_ACTPOS", "qc", lambda c: c.axis.apos),
    2: ("REG_COMPOS", "qc", lambda c: round(c.axis.cpos)),
    3: ("REG_ACTVEL", "qc/ms", lambda c: round(c.axis.plant.velocity)),
    4: ("REG_COMVEL", "qc/ms", lambda c: round(c.axis.profile.velocity)),
    5: ("REG_SPEEDREF", "qc/ms", lambda c: round(c.axis.reference)),
    6: ("REG_TRACKERR", "qc", lambda c: round(c.axis.tracking_error)),
    7: ("REG_AXEND", "", lambda c: c.axis.axend()),
    8: ("REG_STAT", "", lambda c: c.stat()),
    9: ("MASTER_POS", "qc", lambda c: c.master.raw),  # 4105: simulated master position (DG 8370)
    10: ("VELMAXQC", "qc/s", lambda c: round(c.axis.scaling.vmax * 1000)),
    23: ("sys_clock", "ms", lambda c: c.time_ms),
    # DG 10075-10079: the tracking error relative to the command velocity in % (120 = 1.2 × VCMD)
    28: ("REG_NORMTRACKERR", "%", lambda c: _normtrackerr(c)),
    134: ("CMASTERCPOS", "MU", lambda c: _cmastercpos(c)),  # 4230: curve master position (CR 3936)
}
SDO_PROCESS_DATA = {
    0x01250001: "REG_ACTPOS",   # SDO 0x2500 sub 1 (CR 2040)
    0x01250002: "REG_COMPOS",
    0x01250006: "REG_TRACKERR",
}


def _cmastercpos(controller) -> int:
    from motiontool.kernel.cam import master_curve_position  # cam needs the controller's modules first

    value = master_curve_position(controller)
    return 0 if value is None else value


_BY_NAME = {name: n for n, (name, _, _) in AXIS_PROCESS_DATA.items()}


def _normtrackerr(c) -> int:
    v = abs(c.axis.profile.velocity)
    return round(100 * abs(c.axis.tracking_error) / v) if v > 1e-6 else 0


def read_sysvar(controller, index: int) -> int | None:
    """Value of SYSVAR[index], or None if the simulator does not know the index."""
    if AXIS_BASE < index <= AXIS_BASE + 255:
        entry = AXIS_PROCESS_DATA.get(index - AXIS_BASE)
        return entry[2](controller) if entry else None
    if index in SDO_PROCESS_DATA:
        return AXIS_PROCESS_DATA[_BY_NAME[SDO_PROCESS_DATA[index]]][2](controller)
    if index == 0x01220202:  # SDO 0x2202 sub 2: digital inputs 1-8
        return controller.io.read_byte(0)
    if index == 0x0122020A:  # sub 0x0A: digital outputs 1-8
        return controller.io.output_word() & 0xFF
    if 0x01220100 < index <= 0x01220164:  # 0x2201: user parameters 19-00 … 19-99
        return controller.params.values.get(1900 + (index - 0x01220101), 0)
    if index == GUARD_ERROR_ID:
        return controller.can.guard_error_id
    if index >> 24 == 1 and object_reader is not None:  # any other object of the dictionary (kernel/objdict.py)
        value = object_reader(controller, index)
        if value is not None:
            return value
    return controller.sysvar_memory.get(index)


def sysvar_name(index: int) -> str:
    if AXIS_BASE < index <= AXIS_BASE + 255 and index - AXIS_BASE in AXIS_PROCESS_DATA:
        return AXIS_PROCESS_DATA[index - AXIS_BASE][0]
    return SDO_PROCESS_DATA.get(index, f"SYSVAR 0x{index:X}" if index > 0xFFFF else f"SYSVAR {index}")
