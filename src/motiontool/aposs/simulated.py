"""Documented commands the simulated controller serves only with the manual's own failure result, because the
device they talk to does not exist in the simulation (issue 15: never error 110 for a documented command), or only
in part (the FC 300's parameters and alarm, kernel/fc300.py).

`check`/`compile` warn where a program uses one (codegen_expr.py); the kernel (kernel/unserved.py) answers each as
the manual says a controller without that device answers.
"""

from __future__ import annotations

_NO_ENCODER = ("there is no Hiperface encoder on the simulated RS485 line: {write} returns 0 (sent), {read} 0 "
               "while it waits and -1 (timeout) 300 ms after it (CR 1239-1243)")

UNSERVED: dict[str, str] = {
    "ENCTGWRITE": _NO_ENCODER.format(write="ENCTGWRITE", read="ENCTGREAD"),
    "ENCTGREAD": _NO_ENCODER.format(write="ENCTGWRITE", read="ENCTGREAD"),
    "MENCTGWRITE": _NO_ENCODER.format(write="MENCTGWRITE", read="MENCTGREAD"),
    "MENCTGREAD": _NO_ENCODER.format(write="MENCTGWRITE", read="MENCTGREAD"),
    "ENCPOSOFFS": "there is no Hiperface encoder on the simulated RS485 line: ENCPOSOFFS returns -1 (timeout) after "
                  "300 ms and leaves offset unchanged (CR 1178-1190)",
    "MENCPOSOFFS": "there is no Hiperface encoder on the simulated RS485 line: MENCPOSOFFS returns -1 (timeout) after "
                   "300 ms and leaves offset unchanged (CR 2197-2209)",
    "INKEY": "the simulated controller has no LCP keypad: INKEY reads only keys a host presses (kernel/lcp.py "
             "press_key); without one INKEY (-1) returns -1 and INKEY 0 waits for ever (CR 1701-1738)",
}


_FC300 = ("the simulated FC 300 holds only the parameters docs/fc300.md lists (others stop with error 112) and has "
          "no electrical model: power, motor voltage, current and torque (16-10, 16-12, 16-14, 16-16, 16-22) read 0")
UNSERVED.update({name: _FC300 for name in ("GETVLT", "GETVLTSUB", "SETVLT", "SETVLTSUB")})
UNSERVED["VLTALARMSTAT"] = ("the simulated FC 300 trips only when a host trips it (kernel/fc300.py trip); until then "
                            "VLTALARMSTAT returns 0")


def unserved_note(name: str) -> str | None:
    """The warning for a command the simulator cannot serve, or None."""
    reason = UNSERVED.get(name)
    return None if reason is None else f"{name} on the simulated controller: {reason}"
