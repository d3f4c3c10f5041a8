"""The typed controller client: one method per operation of comms/operations.py, answers as dataclasses.

Everything on the IDE's side (dialogs, the scope, the CAM editor's transfer, the CLI) asks a controller through
these methods, so a reader or a type checker can follow a value from a dialog to the operation that answers it.
`ControllerClient.call` is the one untyped door: every Link implements it (comms/link.py) and nothing outside
comms/ uses it (tests/comms/test_operations.py). The method names and arguments are the operations' own, except
`break_program` and `continue_program` (`break` and `continue` are Python keywords).
"""

from __future__ import annotations

import base64
import dataclasses
from abc import ABC, abstractmethod
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, TypeVar

from motiontool.comms.protocol import Status

T = TypeVar("T")


def _make(cls: type[T], value: dict) -> T:
    """A dataclass from an answer's dict; keys a newer controller adds are left out, as JSON readers do."""
    names = {f.name for f in dataclasses.fields(cls)}  # type: ignore[arg-type]
    return cls(**{k: v for k, v in value.items() if k in names})


@dataclass(frozen=True)
class Identity:
    product: str
    firmware: str = ""
    protocol: int = 0
    name: str = ""                      # Parameters → Name
    kind: str = "MCO"                   # "APC" for the Unidrive SP's SM-Applications
    node: int | None = None             # a virtual drive's node (or FC address)
    clock: str = ""                     # a virtual drive's: "virtual" moves only on advance
    drive: str = ""
    boot: int = 0                       # a virtual drive's boot id: a new one after a restart
    pos_period_us: int = 0              # the APC's position loop period


@dataclass(frozen=True)
class ArrayInfo:
    index: int                          # 0-based DIM position
    name: str
    size: int


@dataclass(frozen=True)
class ProgramInfo:
    number: int | None                  # None: the APC's one DPL program
    name: str
    autostart: bool = False
    source: bool = False                # stored with its source (Include Sourcecode)
    stored_at: str = ""


@dataclass(frozen=True)
class StoredSource:
    files: dict[str, str]               # file → text, the program first
    main: str
    stored_at: str = ""


@dataclass(frozen=True)
class SignalInfo:
    name: str                           # what stream, read_signals and the recordings take
    group: str                          # "Axis", "Parameters", "Process data (SYSVAR)", "APC read parameters" …
    text: str = ""


@dataclass(frozen=True)
class RecordingInfo:
    index: int
    name: str
    samples: int = 0
    indices: list[int] = field(default_factory=list)
    running: bool = False


@dataclass(frozen=True)
class Recording:
    """A TESTSETP recording as uploaded."""
    name: str
    interval_ms: int
    start_ms: int
    indices: list[int]
    names: list[str]
    samples: list[list[float]]
    first_ms: int                       # time of the first kept set


@dataclass(frozen=True)
class RecordingStatus:
    running: bool
    samples: int
    limit: int
    taken: int
    interval_ms: int = 1


@dataclass(frozen=True)
class SingleShot:
    """A stopped Single Shot recording (stop_recording)."""
    name: str
    interval_ms: int
    start_ms: int
    signals: list[str]
    time_ms: list[int]
    samples: list[list[float]]
    taken: int = 0


@dataclass(frozen=True)
class ErrorRecord:
    time_ms: int
    number: int
    text: str = ""
    line: int | None = None
    detail: str = ""
    kind: str = ""                      # the APC's: which part reported it


class ControllerClient(ABC):
    """One typed method per operation; subclasses (every Link) carry them with `call`."""

    @abstractmethod
    def call(self, op: str, **args: Any) -> Any:
        """Send operation `op` with `args` and return its answer (JSON values); raise LinkError if refused."""

    # --- the controller -------------------------------------------------------------------------------------
    def identify(self) -> Identity:
        return _make(Identity, self.call("identify"))

    def set_name(self, name: str) -> None:
        self.call("set_name", name=name)

    def status(self) -> Status:
        return Status(**self.call("status"))

    def read_parameter(self, key: str | int) -> int:
        return self.call("read_parameter", key=key)

    def write_parameter(self, key: str | int, value: int) -> None:
        self.call("write_parameter", key=key, value=value)

    # --- arrays ---------------------------------------------------------------------------------------------
    def list_arrays(self) -> list[ArrayInfo]:
        return [_make(ArrayInfo, a) for a in self.call("list_arrays")]

    def read_array(self, index: int) -> list[int]:
        return self.call("read_array", index=index)

    def write_array(self, index: int, values: Sequence[int]) -> None:
        self.call("write_array", index=index, values=list(values))

    def restore_arrays(self, arrays: Sequence[tuple[str, Sequence[int]]]) -> None:
        """(name, values) in DIM order replace the array memory."""
        self.call("restore_arrays", arrays=[{"name": name, "values": list(values)} for name, values in arrays])

    # --- programs -------------------------------------------------------------------------------------------
    def download(self, image: bytes, number: int | None = None, name: str = "", *,
                 source: dict[str, str] | None = None, stack_size: int | None = None) -> None:
        """Download a program image; `source` (file → text, the program first) stores its source with it
        (Include Sourcecode), `stack_size` is the Settings → Compiler stack size. Both only when given, so a link
        whose controller does not know them still downloads."""
        extra = {key: value for key, value in (("source", source), ("stack_size", stack_size)) if value}
        self.call("download", image=base64.b64encode(image).decode("ascii"), number=number, name=name,
                  **extra)

    def list_programs(self) -> list[ProgramInfo]:
        return [_make(ProgramInfo, p) for p in self.call("list_programs")]

    def upload_source(self, number: int) -> StoredSource:
        return _make(StoredSource, self.call("upload_source", number=number))

    def upload_program(self, number: int) -> bytes:
        return base64.b64decode(self.call("upload_program", number=number))

    def delete_program(self, number: int) -> None:
        self.call("delete_program", number=number)

    def set_autostart(self, number: int | None) -> None:
        self.call("set_autostart", number=number)

    def power_on(self) -> None:
        self.call("power_on")

    def start(self, number: int | None = None, step: bool = False,
              inputs: Sequence[tuple[int, int, int]] | None = None) -> None:
        """Start a program; with `step` (Prepare Singlestep) it stops before its first statement; `inputs`
        (N, V, T) are set T ms after the start (sent only when given, so every controller still starts)."""
        extra = {"inputs": [list(i) for i in inputs]} if inputs else {}
        self.call("start", number=number, step=step, **extra)

    def break_program(self) -> None:
        self.call("break")

    def continue_program(self) -> None:
        self.call("continue")

    # --- inputs ---------------------------------------------------------------------------------------------
    def set_input(self, number: int | str, value: int) -> None:  # the APC names its inputs
        self.call("set_input", number=number, value=value)

    def schedule_input(self, number: int | str, value: int, time_ms: int) -> None:
        self.call("schedule_input", number=number, value=value, time_ms=time_ms)

    # --- signals and the scope --------------------------------------------------------------------------------
    def stream(self, signals: Sequence[str], interval_ms: int = 1) -> None:
        self.call("stream", signals=list(signals), interval_ms=interval_ms)

    def read_signals(self, signals: Sequence[str]) -> list[float]:
        return self.call("read_signals", signals=list(signals))

    def list_signals(self) -> list[SignalInfo]:
        return [_make(SignalInfo, s) for s in self.call("list_signals")]

    def list_recordings(self) -> list[RecordingInfo]:
        return [_make(RecordingInfo, r) for r in self.call("list_recordings")]

    def upload_recording(self, index: int) -> Recording:
        return _make(Recording, self.call("upload_recording", index=index))

    def start_recording(self, signals: Sequence[str], interval_ms: int = 1, destination: str = "DYNMEM",
                        cyclic: bool = False, count: int = 0) -> RecordingStatus:
        return _make(RecordingStatus, self.call("start_recording", signals=list(signals), interval_ms=interval_ms,
                                                destination=destination, cyclic=cyclic, count=count))

    def recording_status(self) -> RecordingStatus | None:
        status = self.call("recording_status")
        return None if status is None else _make(RecordingStatus, status)

    def stop_recording(self) -> SingleShot:
        return _make(SingleShot, self.call("stop_recording"))

    # --- errors, memory, reset ------------------------------------------------------------------------------
    def error_history(self) -> list[ErrorRecord]:
        return [_make(ErrorRecord, e) for e in self.call("error_history")]

    def clear_error(self) -> None:
        self.call("clear_error")

    def clear_error_history(self) -> None:
        self.call("clear_error_history")

    def save_memory(self, what: str) -> None:
        self.call("save_memory", what=what)

    def delete_eprom(self) -> None:
        self.call("delete_eprom")

    def reset(self, what: str) -> None:
        self.call("reset", what=what)

    def advance(self, ms: int) -> None:
        self.call("advance", ms=ms)

    # --- the debugger ---------------------------------------------------------------------------------------
    def set_breakpoints(self, lines: Sequence[int]) -> None:
        self.call("set_breakpoints", lines=list(lines))

    def step(self) -> None:
        self.call("step")

    def read_variables(self, names: Sequence[str]) -> list[int | float]:
        return self.call("read_variables", names=list(names))

    def write_variable(self, name: str, value: int | float) -> None:
        self.call("write_variable", name=name, value=value)


# the client method of each operation whose name is a Python keyword
METHOD_NAMES = {"break": "break_program", "continue": "continue_program"}
