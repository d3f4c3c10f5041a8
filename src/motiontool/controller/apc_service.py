"""The controller side of the link protocol for the APC (Unidrive SP + SM-Applications): the same requests as
the MCO 305's ControllerService (docs/link-protocol.md), answered by an `ApcDrive` — or every drive of a CTSync
line, one service per node — so the scope, the watch and the array editor work unchanged (docs/apc.md "Link").

* Inputs (`set_input`, `schedule_input`): DIGIN0 (number 0, the freeze input; #81.42 passes it to the freeze
  counters, #81.43 picks the edge) and the marker pulses "REF_MARKER", "FB_MARKER" (`apc_input`).
* `identify` names the kind: ``{"product", "kind": "APC", "firmware", "protocol", "pos_period_us"}``.
* `read_parameter` / signals: an APC read parameter by number (48), "[48]", "1048" (raw) or alias
  ("APC_FB_POS"), or a drive parameter written with a dot ("18.11", "#1.06"); `write_parameter` writes drive
  parameters (the read parameters change only through the APC calls). The scope's time stamp, SYSVAR sys_clock
  "4119", reads the service's clock in ms, so polled curves work as on the MCO.
* `status`: apos = [48], cpos = [142] (the position loop's reference), axend = [120]; error = 90.49.
* Arrays belong to the DPL program: a program host (the DPL runtime) fills `arrays` with (name, list) pairs.
* Programs: the ops `download`, `start`, `break`, `continue`, `list_programs`, `delete_program`,
  `set_autostart`, `power_on`, `set_breakpoints`, `step`, `read_variables`, `write_variable` go to the attached
  program host (`attach_program`: any object with `op_<name>` methods; its `slice()`, if it has one, runs the
  Initial/Background time slice before each POS sample; it reports errors and program state through
  `publish(LinkEvent)`, which the service gives it); without one they are refused.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from motiontool.apc.clock import PosClock
from motiontool.apc.drive import ApcDrive
from motiontool.apc.readpars import parameter_number
from motiontool.comms.operations import OPERATIONS
from motiontool.comms.protocol import PROTOCOL_VERSION, LinkEvent, Request, Response, Status
from motiontool.controller import sampling
from motiontool.controller.embedded import EmbeddedLink
from motiontool.controller.signal_catalogue import apc_signals

PROGRAM_OPS = ("download", "start", "break", "continue", "list_programs", "delete_program", "set_autostart",
               "power_on", "set_breakpoints", "step", "read_variables", "write_variable", "restore_arrays",
               "list_recordings", "upload_recording")


def apc_reader(drive: ApcDrive, key) -> Callable[[], int]:
    """A reader for a signal or parameter key: drive parameter if it has a dot, else an APC read parameter."""
    text = str(key).strip()
    if "." in text:
        drive.params.read(text)                       # refuse a bad key now
        return lambda: drive.params.read(text)
    number = parameter_number(key)
    if drive.read_parameter(number) is None:
        raise ValueError(f"no APC read parameter [{number}]")

    def read() -> int:
        value = drive.read_parameter(number)
        assert value is not None  # the read parameters are a fixed set: checked above
        return value[0]
    return read


SYS_CLOCK = "4119"   # SYSVAR sys_clock (docs/sysvar.md)
INPUT_NAMES = {"0": "DIGIN0", "DIGIN0": "DIGIN0", "REF_MARKER": "REF_MARKER", "FB_MARKER": "FB_MARKER"}


def apc_input(number, value) -> str:
    """The input `number` names (0 or "DIGIN0", "REF_MARKER", "FB_MARKER", any case), else ValueError saying which
    the simulated drive has; a marker is a pulse, so its value must be 1."""
    name = INPUT_NAMES.get(str(number).strip().upper())
    if name is None:
        raise ValueError(f"input {number}: the simulated SM-Applications takes DIGIN0 (0, the freeze input T10) and "
                         "the encoders' marker pulses REF_MARKER and FB_MARKER")
    if name != "DIGIN0" and int(value) != 1:
        raise ValueError(f"{name}={value}: a marker is a pulse, give {name}=1")
    if int(value) not in (0, 1):
        raise ValueError(f"DIGIN0={value}: a digital input is 0 or 1")
    return name


class ApcService:
    """Executes link requests on one APC drive (module docstring)."""

    kind = "APC"

    def __init__(self, drive: ApcDrive | None = None, *, advance: Callable[[], None] | None = None,
                 runs_samples: bool = True):
        """`advance` runs one POS sample of the whole machine (a CTSync line ticks every node); by default the
        drive's own tick. `runs_samples=False`: something else (ApcLineBus) runs the samples and the time slices;
        the service keeps its clock and streams."""
        self.drive = drive or ApcDrive()
        self._run_sample = advance or self.drive.tick
        self._runs_samples = runs_samples
        self._clock = PosClock()
        self.listeners: list[Callable[[LinkEvent], object]] = []
        self.program: Any = None                      # the DPL program host, if any
        self.arrays: list[tuple[str, list]] = []      # the program's arrays, in declaration order
        self.errors: list[dict] = []
        self.time_ms = 0
        self.stream: sampling.Sampler | None = None          # Free Run (op_stream)
        self._packets: sampling.PacketSink | None = None
        self.digin0 = 0                               # DIGIN0's level (the freeze input)
        self._inputs_due: list[tuple[int, int, str, int]] = []   # (time ms, order, input, value) of schedule_input
        self.drive.listeners.append(self._drive_event)

    @property
    def controller(self) -> ApcDrive:
        return self.drive

    def attach_program(self, program: Any) -> None:
        """Attach the DPL program host: it gets `publish` for its LinkEvents (errors, program state)."""
        self.program = program
        if program is not None:
            program.publish = self.publish

    def slice(self) -> None:
        """The program's time between POS samples (Initial, Background), if a host is attached."""
        program = self.program
        if program is not None and hasattr(program, "slice"):
            program.slice()

    def _drive_event(self, kind: str, details: dict) -> None:
        number = details.get("code", 0) if kind == "error" else 81 if details.get("trip") == "Tr81" else 44
        self.errors.append({"time_ms": self.time_ms, "kind": kind, "number": number, "text": details.get("text", "")})
        self._publish(LinkEvent("error", self.time_ms, details.get("text", ""), number))

    def publish(self, event: LinkEvent) -> None:
        for listener in self.listeners:
            listener(event)

    _publish = publish

    # --- time ------------------------------------------------------------------------------------------------------
    def tick(self) -> None:
        """One millisecond: as many POS samples as fall into it (four at 250 µs, one every 2nd ms at 2 ms), each
        after its time slice; the period is read before each sample (apc/clock.py)."""
        self.time_ms += 1
        while self._inputs_due and self._inputs_due[0][0] <= self.time_ms:
            at, _, name, value = self._inputs_due.pop(0)
            self._apply_input(name, value, at * 1000)
        if self._runs_samples:
            self._clock.run_until(self.time_ms * 1_000_000, self.drive, self.slice, self._run_sample)
        if self.stream is not None:
            self.stream.tick(self.time_ms)

    def flush_stream(self) -> None:
        if self._packets is not None:
            self._packets.flush()

    def _publish_samples(self, data: dict) -> None:
        self._publish(LinkEvent("samples", self.time_ms, data=data))

    # --- requests --------------------------------------------------------------------------------------------------
    def handle(self, request: Request) -> Response:
        if request.op not in OPERATIONS:
            return Response(request.id, False, error=f"unknown operation '{request.op}'")
        try:
            if request.op in PROGRAM_OPS and not hasattr(self, "op_" + request.op):
                if self.program is None or not hasattr(self.program, "op_" + request.op):
                    raise ValueError(f"'{request.op}': the APC controller runs DPL programs and none is attached")
                return Response(request.id, True, getattr(self.program, "op_" + request.op)(**request.args))
            return Response(request.id, True, getattr(self, "op_" + request.op)(**request.args))
        except AttributeError:
            return Response(request.id, False, error=f"'{request.op}' is not available on the APC controller")
        except (ValueError, KeyError, TypeError, IndexError, RuntimeError) as exc:
            return Response(request.id, False, error=str(exc))
        except Exception as exc:  # noqa: BLE001 - a request never takes the controller down
            return Response(request.id, False, error=f"internal error: {type(exc).__name__}: {exc}")

    def op_identify(self) -> dict:
        from motiontool import __version__

        return {"product": "Unidrive SP + SM-Applications APC (simulated)", "kind": self.kind,
                "firmware": f"motiontool {__version__}", "protocol": PROTOCOL_VERSION,
                "pos_period_us": self.drive.period_us}

    def op_status(self) -> dict:
        d = self.drive
        program = self.program.status() if self.program is not None and hasattr(self.program, "status") else {}
        return Status(self.time_ms, program.get("program_state", "idle"), program.get("program", ""),
                      d.error_id, program.get("line"), d.fb.integrated, d.loop.position_ref,
                      d.pg.flags() & 1).to_dict()

    def op_read_parameter(self, key) -> int:
        return apc_reader(self.drive, key)()

    def op_write_parameter(self, key, value) -> None:
        text = str(key).strip()
        if "." not in text:
            raise ValueError(f"{key!r}: APC read parameters change only through the APC calls; write drive "
                             f"parameters as menu.parameter (e.g. 18.11)")
        self.drive.params.write(text, int(value))

    def op_list_arrays(self) -> list[dict]:
        return [{"index": i, "name": name, "size": len(data)} for i, (name, data) in enumerate(self.arrays)]

    def _array(self, index) -> list:
        if not isinstance(index, int) or not 0 <= index < len(self.arrays):
            raise ValueError(f"no array {index} (the program has {len(self.arrays)})")
        return self.arrays[index][1]

    def op_read_array(self, index) -> list:
        return list(self._array(index))

    def op_write_array(self, index, values) -> None:
        data = self._array(index)
        if len(values) > len(data):
            raise ValueError(f"{len(values)} values for {self.arrays[index][0]}[{len(data)}]")
        data[:len(values)] = [int(v) for v in values]

    def op_stream(self, signals, interval_ms=1) -> None:
        interval_ms = max(1, int(interval_ms))  # a bad interval or signal leaves the running stream as it was
        readers = [self.signal(name) for name in signals]
        self.flush_stream()
        self.stream, self._packets = None, None
        if readers:
            self.stream, self._packets = sampling.stream([str(name) for name in signals], readers, interval_ms,
                                                         self._publish_samples)

    def signal(self, name) -> Callable[[], int]:
        """A reader for a scope signal: the MCO's SYSVAR sys_clock (4119, ms), which the scope reads with every
        poll to time-stamp it, is the service's clock here (decision A76); anything else `apc_reader`."""
        if str(name).strip() == SYS_CLOCK:
            return lambda: self.time_ms
        return apc_reader(self.drive, name)

    def op_list_signals(self) -> list[dict]:
        return apc_signals()

    def op_read_signals(self, signals) -> list:
        return [self.signal(name)() for name in signals]

    def op_set_input(self, number, value) -> None:
        """An input of the simulated drive now (`apc_input`): DIGIN0 (T10, the freeze input, L629-643) as a level,
        or a marker pulse on the reference or feedback encoder."""
        self._apply_input(apc_input(number, value), int(value), self.drive.time_ns / 1000)

    def op_schedule_input(self, number, value, time_ms) -> None:
        """The same at `time_ms` of the service's clock (applied in the millisecond that ends there)."""
        name = apc_input(number, value)
        time_ms = int(time_ms)
        if time_ms < 0:
            raise ValueError(f"time {time_ms} ms is before the start")
        self._inputs_due.append((time_ms, len(self._inputs_due), name, int(value)))
        self._inputs_due.sort()

    def _apply_input(self, name: str, value: int, time_us: float) -> None:
        drive = self.drive
        time_us = max(time_us, drive.time_ns / 1000 + 0.001)     # events come after the last sample
        if name != "DIGIN0":
            drive.schedule("reference" if name == "REF_MARKER" else "feedback", "marker", time_us)
            return
        level, self.digin0 = self.digin0, 1 if value else 0
        edge = 1 if self.digin0 > level else -1 if self.digin0 < level else 0
        falling = drive.params.values.get((81, 43), 0) == 1       # 0 rising, 1 falling edge (L1076)
        # the freeze counters see DIGIN0 only with #81.42 = 1, "to enable the freeze hardware" (L1076, A72)
        if drive.params.values.get((81, 42), 0) == 1 and edge == (-1 if falling else 1):
            for side in ("reference", "feedback"):
                drive.schedule(side, "freeze", time_us)

    def op_error_history(self) -> list[dict]:
        return [dict(e) for e in self.errors]

    def op_clear_error(self) -> None:
        """A drive reset: the trip and 90.49 clear."""
        self.drive.trip = ""
        self.drive.error_id = 0

    def op_reset(self, what) -> None:
        if what not in ("parameters", "user", "arrays", "all"):
            raise ValueError(f"reset {what!r}: choose one of parameters, user, arrays, all")
        if what in ("parameters", "all"):
            from motiontool.apc.driveparams import DEFAULTS

            self.drive.params.values = dict(DEFAULTS)
        if what in ("user", "all"):
            for key in [k for k in self.drive.params.values if 18 <= k[0] <= 20]:
                del self.drive.params.values[key]
        if what in ("arrays", "all"):
            for _, data in self.arrays:
                data[:] = [0] * len(data)

    def op_advance(self, ms) -> None:
        for _ in range(int(ms)):
            self.tick()

    def op_recording_status(self) -> None:
        return None


def embedded_apc_link(drive: ApcDrive | None = None, *, realtime_factor: float | None = None) -> EmbeddedLink:
    """An embedded link to a simulated APC: synchronous (advance) by default, paced with `realtime_factor`."""
    return EmbeddedLink(realtime_factor=realtime_factor, service=ApcService(drive))
