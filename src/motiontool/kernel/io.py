"""Simulated digital and analog I/O of the MCO 305 and the FC 300 (spec i).

Inputs 1-12 (MCO), 18-33 (FC 300); outputs 1-8 (MCO), 21/22 (relays), 27/29 (FC). Input values come from
scripted events (--input N=V@T, the link) and, for inputs given a home or limit-switch function, from the
simulated machine. INB/OUTB byte n covers numbers 8n+1 … 8n+8.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass, field

from motiontool.kernel.errors import ControllerError

MCO_INPUTS = range(1, 13)
FC_INPUTS = range(18, 34)
OUTPUTS = set(range(1, 9)) | {21, 22, 27, 29}
ANALOG_INPUTS = (53, 54)

# 33-50 … 33-59 are I_FUNCTION_1 … 10; 33-61/33-62 are inputs 11/12 (DG 10336-10418).
INPUT_FUNCTION_PARAMETERS = {n: 3349 + n for n in range(1, 11)} | {11: 3361, 12: 3362}
# 33-63 … 33-70 are O_FUNCTION_1 … 8 (DG 10532-10590).
OUTPUT_FUNCTION_PARAMETERS = {n: 3362 + n for n in range(1, 9)}

HOME_SWITCH, NEG_LIMIT, POS_LIMIT, ERROR_CLEAR, BREAK, CONTINUE, START = (
    "home", "neg_limit", "pos_limit", "error_clear", "break", "continue", "start")
_FUNCTIONS = {1: (HOME_SWITCH, False), 2: (HOME_SWITCH, True), 3: (NEG_LIMIT, False), 4: (NEG_LIMIT, True),
              5: (POS_LIMIT, False), 6: (POS_LIMIT, True), 7: (ERROR_CLEAR, False), 8: (ERROR_CLEAR, True),
              9: (BREAK, False), 10: (BREAK, True), 11: (CONTINUE, False), 12: (CONTINUE, True),
              13: (START, False), 14: (START, True)}


@dataclass(order=True)
class InputEvent:
    time_ms: int
    number: int
    value: int


@dataclass
class IO:
    inputs: dict[int, int] = field(default_factory=dict)
    outputs: dict[int, int] = field(default_factory=dict)
    analog: dict[int, int] = field(default_factory=dict)
    events: list[InputEvent] = field(default_factory=list)

    def schedule(self, time_ms: int, number: int, value: int) -> None:
        bisect.insort(self.events, InputEvent(time_ms, number, value))

    def apply_events(self, now_ms: int) -> None:
        while self.events and self.events[0].time_ms <= now_ms:
            e = self.events.pop(0)
            if e.number in ANALOG_INPUTS:
                self.analog[e.number] = e.value
            else:
                self.inputs[e.number] = 1 if e.value else 0

    # --- program access -----------------------------------------------------------------------------
    def read(self, number: int) -> int:
        if number not in MCO_INPUTS and number not in FC_INPUTS and number < 256:
            raise ControllerError(183, f"there is no digital input {number}")
        return self.inputs.get(number, 0)

    def read_byte(self, n: int) -> int:
        return sum(self.inputs.get(8 * n + k + 1, 0) << k for k in range(8))

    def write(self, number: int, value: int) -> None:
        if number not in OUTPUTS:
            raise ControllerError(171, f"there is no digital output {number}")  # CR 3127-3128
        self.outputs[number] = 1 if value else 0

    def write_byte(self, n: int, value: int) -> None:
        if n == 1:  # CR 3181-3220: OUTB 1 = FC outputs 27 and 29
            self.outputs[27], self.outputs[29] = value & 1, (value >> 1) & 1
            return
        for k in range(8):
            number = 8 * n + k + 1
            if number in OUTPUTS:
                self.outputs[number] = (value >> k) & 1

    def read_analog(self, number: int) -> int:
        if number not in ANALOG_INPUTS:
            raise ControllerError(183, f"there is no analog input {number}")
        return self.analog.get(number, 0)

    def input_word(self) -> int:
        """34-40: digital inputs as bits (bit 0 = input 1)."""
        return sum(v << (n - 1) for n, v in self.inputs.items() if 1 <= n <= 32 and v)

    def output_word(self) -> int:
        return sum(v << (n - 1) for n, v in self.outputs.items() if 1 <= n <= 32 and v)


def input_functions(params) -> dict[str, tuple[int, bool]]:
    """function name → (input number, normally closed) from I_FUNCTION_n; the first input wins (DG 10410)."""
    found: dict[str, tuple[int, bool]] = {}
    for number, index in INPUT_FUNCTION_PARAMETERS.items():
        code = params.values.get(index, 0)
        if code in _FUNCTIONS:
            name, nc = _FUNCTIONS[code]
            found.setdefault(name, (number, nc))
    return found
