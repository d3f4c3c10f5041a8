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

# The operations themselves are declared in comms/operations.py.


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
