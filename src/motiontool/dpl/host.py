"""The program side of a simulated APC controller behind a Link: downloads DPL program images, starts and stops
the program, and exposes its variables to the watch. The APC Link service (``controller/apc_service.py``) hands it
the program operations (``op_download``, ``op_start``, ``op_break`` …) and calls `slice()` between POS samples.
"""

from __future__ import annotations

import base64
from collections.abc import Callable

from motiontool.dpl.codegen import DplRuntimeError
from motiontool.dpl.driver import check_source
from motiontool.dpl.image import DplImage
from motiontool.dpl.runtime import DplRuntime

# runtime state → the Link's program_state (docs/link-protocol.md)
_STATES = {"idle": "idle", "initial": "running", "running": "running", "stopped": "idle", "error": "error"}


class DplHost:
    def __init__(self, drive, notify: Callable[[str, dict], None] | None = None):
        """`notify(kind, details)` is told of "error" ({"text", "line", "col", "file"}) and "program"
        ({"text": state}) for the Link's events."""
        self.drive = drive
        self.notify = notify
        self.image: DplImage | None = None
        self.runtime: DplRuntime | None = None
        self._reported = "idle"   # the Link state last reported (Initial and Background both count as running)

    # --- Link operations ---------------------------------------------------------------------------------------
    def op_download(self, image, number=None, name="") -> None:
        if number is not None:
            raise ValueError("the simulated SM-Applications module holds one program (download without a number)")
        program = DplImage.from_bytes(base64.b64decode(image))
        checked = check_source(program.source, program.name or name or "program.dpl")
        if not checked.ok:
            raise ValueError("\n".join(d.format() for d in checked.errors))
        if self.runtime is not None:
            self.runtime.stop()
        self.image = DplImage(name or program.name, program.source)
        self.runtime = DplRuntime(self.drive, checked)
        self.runtime.listeners.append(self._forward)

    def op_start(self, number=None, step=False) -> None:
        if self.runtime is None:
            raise ValueError("no program downloaded")
        if step:
            raise ValueError("single-stepping is not available for DPL programs")
        if self.runtime.running:
            raise RuntimeError("the controller is executing a program")
        self.runtime.start()

    def op_break(self) -> None:
        if self.runtime is not None:
            self.runtime.stop()

    def op_continue(self) -> None:
        raise ValueError("a stopped DPL program starts again from its Initial task (Execute)")

    def op_list_programs(self) -> list[dict]:
        return [] if self.image is None else [{"number": None, "name": self.image.name}]

    def op_read_variables(self, names) -> list[int]:
        if self.runtime is None:
            raise ValueError("no program is loaded")
        try:
            return [self.runtime.read_variable(str(n)) for n in names]
        except KeyError as exc:
            raise ValueError(exc.args[0]) from None

    # --- the service's hooks -----------------------------------------------------------------------------------
    def slice(self) -> None:
        """The time between two POS samples (Initial, Background)."""
        if self.runtime is not None and self.runtime.running:
            self.runtime.slice()

    def status(self) -> dict:
        r = self.runtime
        return {"program_state": _STATES[r.state] if r else "idle", "program": self.image.name if self.image else "",
                "line": r.line if r and r.running else None}

    def arrays(self) -> list[tuple[str, list[int]]]:
        """The program's arrays for the array editor (name as upper-case key, live list)."""
        return [] if self.runtime is None else list(self.runtime.memory.arrays.items())

    def _forward(self, kind: str, value) -> None:
        if self.notify is None:
            return
        if kind == "error" and isinstance(value, DplRuntimeError):
            self.notify("error", {"text": value.message, "line": value.loc.line, "col": value.loc.col,
                                  "file": value.loc.file})
        elif kind == "state" and _STATES.get(value, value) != self._reported:
            self._reported = _STATES.get(value, value)
            if self._reported != "error":  # the error itself was reported with its place
                self.notify("program", {"text": self._reported})
