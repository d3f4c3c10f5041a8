"""The messages every link carries (docs/link-protocol.md): requests, responses and events.

They are plain data (JSON-serialisable dicts) so the embedded link and the wire links (FC serial, CANopen)
exchange exactly the same things. A request names an operation and its arguments; the controller side
answers with a value or an error; events (PRINT output, errors, program state, streamed signals) flow the
other way without being asked for.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

PROTOCOL_VERSION = 1

# Operations a link understands: name → argument names (all values are JSON types).
OPERATIONS: dict[str, tuple[str, ...]] = {
    "identify": (),                                  # → {"product", "firmware", "protocol", "name"}
    "set_name": ("name",),                           # Parameters → Name: up to 8 upper-case characters
    "status": (),                                    # → Status
    "read_parameter": ("key",),                      # key: "32-60" | 3260 | "KPROP" → int
    "write_parameter": ("key", "value"),
    "list_arrays": (),                               # → [{"index", "name", "size"}]
    "read_array": ("index",),                        # 0-based DIM position → [int]
    "write_array": ("index", "values"),
    "restore_arrays": ("arrays",),                   # [{"name", "values"}] in DIM order: replaces the array memory
    "download": ("image", "number", "name", "source", "stack_size"),  # image: base64 of ProgramImage.to_bytes();
                                                     # number None = temporary; source {file: text} (Include
                                                     # Sourcecode); stack_size (Settings → Compiler)
    "list_programs": (),                             # → [{"number", "name", "autostart", "source", "stored_at"}]
    "upload_source": ("number",),                    # → {"files": {file: text}, "main", "stored_at"}
    "upload_program": ("number",),                   # → image (base64), for Download's Verify
    "delete_program": ("number",),
    "set_autostart": ("number",),                    # Autostart on (number) / off (None)
    "power_on": (),                                  # simulated controllers: off and on (Autostart runs)
    "start": ("number", "step", "inputs"),           # None = the temporary program; step: stop before statement 1;
                                                     # inputs [[N, V, T ms after the start]] (Test-inputs)
    "break": (),                                     # [Esc]
    "continue": (),
    "set_input": ("number", "value"),                # simulated controllers only
    "schedule_input": ("number", "value", "time_ms"),
    "stream": ("signals", "interval_ms"),            # start streaming (free-run scope); [] stops
    "read_signals": ("signals",),                    # one-off poll (polling scope) → [values]
    "list_recordings": (),
    "upload_recording": ("index",),                  # → {"name", "interval_ms", "indices", "names", "samples"}
    "start_recording": ("signals", "interval_ms", "destination", "cyclic", "count"),  # Single Shot scope
    "recording_status": (),                          # → {"running", "samples", "limit", "taken"} | None
    "stop_recording": (),                            # → {"signals", "time_ms", "samples", …} and forget it
    "error_history": (),                             # → [{"time_ms", "number", "text", "line", "detail"}] oldest first
    "clear_error": (),                               # ERRCLR
    "clear_error_history": (),                       # Error History → Clear
    "save_memory": ("what",),                        # Memory ▸: "ram" (Save RAM), "user", "arrays", "app", "option"
    "delete_eprom": (),                              # Memory ▸ Delete EPROM: factory settings at the next power on
    "reset": ("what",),                              # "parameters" | "user" | "arrays" | "all" (Controller → Reset)
    "advance": ("ms",),                              # virtual time, simulated controllers only
    "set_breakpoints": ("lines",),                   # debugger: source lines of the main file (debug builds)
    "step": (),                                      # run to the next statement and stop there
    "read_variables": ("names",),                    # → [value]; "name" or "array[i]"
    "write_variable": ("name", "value"),
}


@dataclass
class Request:
    op: str
    args: dict[str, Any] = field(default_factory=dict)
    id: int = 0

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass
class Response:
    id: int
    ok: bool
    value: Any = None
    error: str = ""
    error_number: int = 0

    def to_dict(self) -> dict:
        return asdict(self)

    def result(self) -> Any:
        """The value, or the controller's error raised as LinkError."""
        if not self.ok:
            raise LinkError(self.error, self.error_number)
        return self.value


@dataclass
class Status:
    time_ms: int
    program_state: str          # idle | running | break | ended | error
    program: str
    error: int                  # pending error number, 0 = none
    line: int | None
    apos: int
    cpos: int
    axend: int

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass
class LinkEvent:
    kind: str                   # "print" | "error" | "program" | "message" | "samples" | "connection"
    time_ms: int
    text: str = ""
    number: int = 0
    line: int | None = None
    data: Any = None            # samples: {"signals": [...], "time_ms": [...], "values": [[...]]}

    def to_dict(self) -> dict:
        return asdict(self)


class LinkError(Exception):
    """A request the controller refused; `number` is the controller error number when there is one."""

    def __init__(self, message: str, number: int = 0):
        super().__init__(message)
        self.number = number


class ConnectionLost(LinkError):
    """The controller did not answer (timeouts after every retry, a closed port or socket): the link is down,
    as opposed to a request the controller refused."""
