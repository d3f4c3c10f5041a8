"""Controller error numbers and texts (DG 11340-11958). ERRNO returns these numbers."""

from __future__ import annotations

# number: (LCP text, what it means)
ERRORS: dict[int, tuple[str, str]] = {
    102: ("Too many CAN objects", "no free CAN objects left"),
    103: ("Illegal axis number", "a motion command addressed an axis other than 1"),
    105: ("Error not reset", "a motion command was given while an error is pending"),
    106: ("Home not done", "HOME_FORCE demands a HOME before any other motion"),
    107: ("Home vel. zero", "HOME with HOME_VEL (33-03) = 0"),
    108: ("Position error", "the tracking error exceeded POSERR (32-67)"),
    109: ("Index not found", "no encoder index pulse within one revolution"),
    110: ("Unknown command", "unknown command code in the program"),
    111: ("SW end limit", "the move would leave or has left the active software limits"),
    112: ("Unknown param.", "SET or GET of a parameter that does not exist"),
    113: ("FC not enabled", "the drive is not ready while position control is active"),
    114: ("Too many loops", "LOOP commands nested too deeply"),
    115: ("Par. save failed", "saving parameters failed"),
    119: ("User abort", "program aborted by the user"),
    121: ("No more SDO channels", "more than 5 non-waiting SDO transfers pending"),
    125: ("HW end limit", "a hardware limit switch is active"),
    149: ("Too many interrupts", "more interrupts defined than the controller supports"),
    150: ("No ext. 24 V", "external 24 V supply missing"),
    151: ("Too many GOSUB", "GOSUB nested deeper than 10, or a subprogram calls itself"),
    152: ("Too many RETURN", "RETURN without GOSUB, or a jump out of a subprogram"),
    155: ("LINK failed", "LINKGPAR failed"),
    156: ("Illegal double arg.", "a math function or division got an invalid argument"),
    170: ("Too many DIM arrays", "the DIM list does not match the arrays in the controller"),
    171: ("Array too small", "array index outside its bounds"),
    175: ("Out of array mem.", "no memory for a new DIM array"),
    176: ("Array size wrong", "a DIM size differs from the array in the controller"),
    179: ("WAITNDX timeout", "no index pulse before the WAITNDX timeout"),
    183: ("Invalid argument", "a command got an argument outside its range"),
    184: ("Too many ontime", "more than 12 ON TIME / ON PERIOD"),
    187: ("Out of memory", "not enough memory for the program's variables"),
    188: ("CAN guarding error", "a guarded CAN node did not answer within 100 ms"),
    189: ("CAN send-receive error", "an SDO, CANIN/CANOUT or CAN I/O transfer failed"),
    191: ("Illegal cam array", "SETCURVE got an array that is not a valid curve"),
    192: ("Encoder error", "encoder monitoring detected a fault"),
    193: ("Stack overflow", "too many local variables or nested function calls"),
    194: ("Out of dyn. mem", "not enough dynamic memory for recording"),
    195: ("Too many test indices", "more than 20 indices in a recording command"),
    196: ("Code too old", "the program image is of an unsupported version"),
    198: ("Limit sw. violation", "after a limit error, a move again went in the forbidden direction"),
    199: ("Internal MCO fault", "internal fault"),
}

# Errors that concern the axis and trigger the ERRCOND reaction (spec p.8); others only call the handler.
AXIS_ERRORS = frozenset({106, 107, 108, 109, 111, 113, 125, 150, 179, 192, 198})


def error_text(number: int) -> str:
    return ERRORS.get(number, ("Unknown error", ""))[0]


class ControllerError(Exception):
    """A controller error raised while executing a command or a tick."""

    def __init__(self, number: int, detail: str = ""):
        self.number = number
        self.detail = detail
        super().__init__(f"error {number}: {error_text(number)}" + (f" ({detail})" if detail else ""))
