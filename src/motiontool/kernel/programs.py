"""Programs saved on the controller, the Autostart program and the Restart mechanism (DG 2699-2788,
ide-spec 2.16-2.23).

* Up to 91 programs, numbers 0-90.  One of them may be marked Autostart.
* Power on: the Autostart program starts (the mechanism is then active).  Without a mark, a Start-program
  input (33-5x function 13/14) starts the program chosen by the Program-select inputs (function 15) on its
  rising edge.
* While the mechanism is active, whenever a program ends the Restart program starts, chosen in this order:
  33-80 PRGPAR if not -1; else the program selected by the inputs on the next rising edge of the start input;
  else the Autostart program if it is the only one that has run; else none.
* A user break, or an end with an error other than 108, 125 and 111, deactivates the mechanism until the
  next power on.  A program started by hand runs as an ordinary program (no restart afterwards).
"""

from __future__ import annotations

from motiontool.aposs.image import ProgramImage
from motiontool.kernel import io as iomod

PROGRAM_NUMBERS = range(0, 91)
KEEPS_AUTOSTART = (108, 125, 111)   # DG 2752-2757: these errors do not deactivate the mechanism
START_CODES = (13, 14)              # I_FUNCTION: Start program exe no / nc
SELECT_CODE = 15                    # I_FUNCTION: Program select


class ProgramStore:
    def __init__(self) -> None:
        self.programs: dict[int, ProgramImage] = {}
        self.autostart: int | None = None
        self.active = False           # the Autostart mechanism (only after a power-on start)
        self.executed: set[int] = set()
        self.running: int | None = None
        # tick() has work only while the program state changes or a start input is watched: the service skips the
        # call otherwise (controller/service.py)
        self.waiting_for_input = False
        self._last_start_input = False
        self.seen_state = "idle"

    # --- memory ----------------------------------------------------------------------------------------
    def save(self, number: int, image: ProgramImage) -> None:
        if number not in PROGRAM_NUMBERS:
            raise ValueError(f"program number {number} outside 0..90")
        self.programs[number] = image

    def delete(self, number: int) -> None:
        self.programs.pop(number, None)
        if self.autostart == number:
            self.autostart = None

    def delete_all(self) -> None:
        self.programs.clear()
        self.autostart = None

    def set_autostart(self, number: int | None) -> None:
        """Autostart on (a number) / off (None); only one program carries the mark (DG 2719-2727)."""
        if number is not None and number not in self.programs:
            raise ValueError(f"no program {number}")
        self.autostart = number

    def listing(self) -> list[dict]:
        return [{"number": n, "name": p.name, "autostart": n == self.autostart}
                for n, p in sorted(self.programs.items())]

    # --- starting --------------------------------------------------------------------------------------
    def start(self, controller, number: int, manual: bool = True) -> None:
        """Load and start a saved program; by hand it runs as an ordinary program (DG 2719-2727)."""
        if number not in self.programs:
            raise ValueError(f"no program {number}")
        if manual:
            self.active = False
            self.waiting_for_input = False
        controller.load(self.programs[number])
        controller.start()
        self.running = number
        self.executed.add(number)
        self.seen_state = controller.program_state

    def power_on(self, controller) -> None:
        """Power on (or Restart): start the Autostart program, or wait for the start input (DG 2707-2717)."""
        self.active = False
        self.executed.clear()
        self.running = None
        self._last_start_input = self._start_input(controller)
        if self.autostart is not None:
            self.active = True
            self.start(controller, self.autostart, manual=False)
        elif self._start_function(controller) is not None:
            self.active = True
            self.waiting_for_input = True
            self._last_start_input = False  # "the pin may already be activated when the controller is powered on"

    # --- every tick, after the controller's ----------------------------------------------------------------
    def tick(self, controller) -> None:
        state = controller.program_state
        if state != self.seen_state:
            previous, self.seen_state = self.seen_state, state
            if previous == "running" and state in ("ended", "error", "break"):
                self._program_ended(controller, state)
        if self.waiting_for_input:
            now = self._start_input(controller)
            rising = now and not self._last_start_input
            self._last_start_input = now
            if rising and controller.program_state != "running":
                self.waiting_for_input = False
                number = self._selected_program(controller)
                if number in self.programs:
                    self.start(controller, number, manual=False)
                else:
                    _message(controller, f"program select: no program {number}")

    def _program_ended(self, controller, state: str) -> None:
        if not self.active:
            return
        if state == "break" or (state == "error" and controller.error not in KEEPS_AUTOSTART):
            self.active = False  # DG 2744-2750
            return
        prgpar = controller.params["PRGPAR"]
        if prgpar != -1:
            if prgpar in self.programs:
                self.start(controller, prgpar, manual=False)
            else:
                _message(controller, f"PRGPAR {prgpar}: no such program")
            return
        if self._start_function(controller) is not None:
            self.waiting_for_input = True  # a rising edge only (DG 2762-2764)
            self._last_start_input = self._start_input(controller)
            return
        if self.autostart is not None and self.executed == {self.autostart}:
            self.start(controller, self.autostart, manual=False)
            return
        self.active = False

    # --- inputs ----------------------------------------------------------------------------------------
    @staticmethod
    def _codes(controller) -> dict[int, int]:
        return {n: controller.params.values.get(index, 0) for n, index in iomod.INPUT_FUNCTION_PARAMETERS.items()}

    def _start_function(self, controller) -> tuple[int, bool] | None:
        for number, code in sorted(self._codes(controller).items()):
            if code in START_CODES:
                return number, code == 14
        return None

    def _start_input(self, controller) -> bool:
        entry = self._start_function(controller)
        if entry is None:
            return False
        number, nc = entry
        return bool(controller.io.inputs.get(number, 0)) != nc

    def _selected_program(self, controller) -> int:
        """The Program-select inputs from the first one with function 15 up to the start input, read as a
        binary number, the first input being bit 0 (DG 10390-10402)."""
        codes = self._codes(controller)
        first = next((n for n, code in sorted(codes.items()) if code == SELECT_CODE), None)
        start = self._start_function(controller)
        if first is None or start is None:
            return 0
        value = 0
        for bit, number in enumerate(range(first, start[0])):
            value |= (1 if controller.io.inputs.get(number, 0) else 0) << bit
        return value


def _message(controller, text: str) -> None:
    controller.message(text)
