"""The controller side of the link protocol: executes requests on a kernel Controller and turns its
events into LinkEvents. The embedded link runs it in-process; the virtual drive runs it behind a wire."""

from __future__ import annotations

import base64
import time
from collections.abc import Callable
from functools import partial
from typing import Any

from motiontool.aposs.image import ImageError, ProgramImage
from motiontool.comms.operations import OPERATIONS
from motiontool.comms.protocol import PROTOCOL_VERSION, LinkEvent, Request, Response, Status
from motiontool.controller import sampling, scope_recording
from motiontool.controller.signal_catalogue import mco_signals
from motiontool.kernel import fc300
from motiontool.kernel.arrays import MAX_ARRAY_ELEMENTS
from motiontool.kernel.controller import Controller, Event
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.fc300_table import link_number
from motiontool.kernel.io import ANALOG_INPUTS, FC_INPUTS, MCO_INPUTS

# the signals for streaming and traces are the drive's CANopen object 0x2510: one table, kept with the dictionary
from motiontool.kernel.objdict import SIGNALS
from motiontool.kernel.programs import ProgramStore
from motiontool.kernel.sysvars import read_sysvar, sysvar_name
from motiontool.kernel.vm import DEFAULT_STACK_SIZE

RESETS = ("parameters", "user", "arrays", "all")  # Controller → Reset (op_reset)


def signal_reader(name: str) -> Callable[[Controller], float]:
    """A signal by name: one of SIGNALS, a parameter ("32-60", "KPROP") or a SYSVAR index ("4097")."""
    key = name.strip()
    if key.upper() in SIGNALS:
        return SIGNALS[key.upper()]
    if key.isdigit() or key.lower().startswith("0x"):
        index = int(key, 0)
        return lambda c: read_sysvar(c, index) or 0
    return lambda c: c.params.get(key)


# A downloaded program's image, inflated: some 200 000 lines of APOSS (~70 bytes a line). A controller's program
# memory is finite (DG 2639, 2669); a 2 kB download inflating to a file's limit made the drive hold 300 MB.
PROGRAM_MEMORY_BYTES = 16 << 20


class ControllerService:
    def __init__(self, controller: Controller | None = None):
        self.controller = controller or Controller()
        self.store = ProgramStore()          # programs saved on the controller, Autostart and Restart
        self.temporary: ProgramImage | None = None
        self.name = ""                          # Parameters → Name (DG 2870-2882)
        self.sources: dict[int, dict] = {}      # program number → {"files", "main", "stored_at"} (Include Sourcecode)
        self.stack_sizes: dict[int | None, int] = {}  # program (None = temporary) → its Settings → Compiler stack size
        self.wipe_at_power_on = False           # Memory ▸ Delete EPROM (DG 2908-2946)
        self.listeners: list[Callable[[LinkEvent], object]] = []
        self.controller.listeners.append(self._forward)
        self.stream: sampling.Sampler | None = None          # Free Run (op_stream)
        self._packets: sampling.PacketSink | None = None
        self.recording: scope_recording.ScopeRecording | None = None  # the Single Shot scope's

    def _forward(self, event: Event) -> None:
        self._publish(LinkEvent(event.kind, event.time_ms, event.text, event.number, event.line))

    def _publish(self, event: LinkEvent) -> None:
        for listener in self.listeners:
            listener(event)

    # --- time ------------------------------------------------------------------------------------------
    def tick(self) -> None:
        c = self.controller
        c.tick()
        store = self.store
        if store.waiting_for_input or c.program_state != store.seen_state:  # else store.tick has nothing to do
            store.tick(c)
        if self.recording is not None:
            self.recording.sampler.tick(c.time_ms)
        if self.stream is not None:
            self.stream.tick(c.time_ms)

    def adds_nothing(self) -> bool:
        """tick() is the controller's tick alone now (Simulation.set_ticker's `steady`): nothing streams or
        records and the program store has nothing to follow."""
        store = self.store
        return (self.recording is None and self.stream is None and not store.waiting_for_input
                and self.controller.program_state == store.seen_state)

    def flush_stream(self) -> None:
        if self._packets is not None:
            self._packets.flush()

    def _publish_samples(self, data: dict) -> None:
        self._publish(LinkEvent("samples", self.controller.time_ms, data=data))

    # --- requests ------------------------------------------------------------------------------------------
    def handle(self, request: Request) -> Response:
        if request.op not in OPERATIONS:
            return Response(request.id, False, error=f"unknown operation '{request.op}'")
        try:
            value = getattr(self, "op_" + request.op)(**request.args)
            return Response(request.id, True, value)
        except ControllerError as exc:
            return Response(request.id, False, error=str(exc), error_number=exc.number)
        except (ValueError, KeyError, TypeError, IndexError, RuntimeError, ImageError) as exc:
            return Response(request.id, False, error=str(exc))
        except Exception as exc:  # noqa: BLE001 - a request never takes the controller down
            return Response(request.id, False, error=f"internal error: {type(exc).__name__}: {exc}")

    def op_identify(self) -> dict:
        from motiontool import __version__

        return {"product": "MCO 305 (simulated)", "firmware": f"motiontool {__version__}",
                "protocol": PROTOCOL_VERSION, "name": self.name}

    def op_set_name(self, name) -> None:
        """Parameters → Name (DG 2870-2882): "Names cannot be longer than 8 characters and must be uppercase"."""
        name = str(name)
        if len(name) > 8 or name != name.upper():
            raise ValueError(f"controller name {name!r}: at most 8 characters, upper case")
        self.name = name

    def op_status(self) -> dict:
        c = self.controller
        image = getattr(c, "image", None)
        return Status(c.time_ms, c.program_state, image.name if image else "", c.error, c.current_line,
                      c.uu(c.axis.apos), c.uu(c.axis.cpos), c.axis.axend()).to_dict()

    def op_read_parameter(self, key) -> int:
        number = link_number(key)   # "4-13": the FC 300's own parameter, as GETVLT reads it (docs/fc300.md)
        if number is not None:
            return fc300.read(self.controller, number)
        return self.controller.params.get(key)

    def op_write_parameter(self, key, value) -> None:
        number = link_number(key)
        if number is not None:
            fc300.write(self.controller, number, 0, int(value))
            return
        self.controller.params.set(key, int(value), source="link")

    def op_list_arrays(self) -> list[dict]:
        return [{"index": i, "name": a.name, "size": len(a)} for i, a in enumerate(self.controller.arrays.arrays)]

    def _array(self, index):
        arrays = self.controller.arrays.arrays
        if not isinstance(index, int) or not 0 <= index < len(arrays):
            raise ValueError(f"no array {index} (the controller has {len(arrays)})")
        return arrays[index]

    def op_read_array(self, index) -> list:
        return list(self._array(index).data)

    def op_write_array(self, index, values) -> None:
        array = self._array(index)
        if len(values) > len(array):
            raise ControllerError(171, f"{len(values)} values for {array.name}[{len(array)}]")
        array.data[:len(values)] = [int(v) for v in values]

    def op_restore_arrays(self, arrays) -> None:
        """Replace the controller's array memory (Restore from file / .zbc download, DG 2886-2900): arrays
        [{"name", "values"}] in DIM order; a program's DIMs then find them by position (C:1024-1041)."""
        if self.controller.program_state == "running":
            raise ValueError("stop the program before restoring arrays (a running program uses them)")
        memory = self.controller.arrays
        if sum(len(a["values"]) for a in arrays) > MAX_ARRAY_ELEMENTS:
            raise ControllerError(175, f"{len(arrays)} arrays do not fit the array memory")
        memory.delete()
        for i, entry in enumerate(arrays):
            values = [int(v) for v in entry["values"]]
            memory.dim(i, str(entry["name"]), [len(values)]).data[:] = values

    def op_download(self, image, number=None, name="", source=None, stack_size=None) -> None:
        program = ProgramImage.from_bytes(base64.b64decode(image), max_body=PROGRAM_MEMORY_BYTES)
        if name:
            program.name = name
        if number is None:
            self.temporary = program
        else:
            self.store.save(number, program)
            self.sources.pop(number, None)
            if source:  # Include Sourcecode (DG 2643-2669): the program and all its include files
                files = {str(k): str(v) for k, v in source.items()}
                self.sources[number] = {"files": files, "main": next(iter(files)),
                                        "stored_at": time.strftime("%Y-%m-%d %H:%M:%S")}
        self.stack_sizes[number] = int(stack_size) if stack_size else DEFAULT_STACK_SIZE

    def op_upload_source(self, number) -> dict:
        """Upload (DG 2671-2675): only programs stored with their source."""
        if number not in self.sources:
            raise ValueError(f"program {number} was stored without its source")
        return dict(self.sources[number])

    def op_upload_program(self, number) -> str:
        if number not in self.programs:
            raise ValueError(f"no program {number}")
        return base64.b64encode(self.programs[number].to_bytes()).decode("ascii")

    @property
    def programs(self) -> dict[int, ProgramImage]:
        return self.store.programs

    def op_list_programs(self) -> list[dict]:
        return [{**p, "source": p["number"] in self.sources,
                 "stored_at": self.sources.get(p["number"], {}).get("stored_at", "")} for p in self.store.listing()]

    def op_delete_program(self, number) -> None:
        self.store.delete(number)
        self.sources.pop(number, None)

    def op_set_autostart(self, number) -> None:
        self.store.set_autostart(number)

    def op_power_on(self) -> None:
        """Simulated controllers: switch off and on (DG 2699-2788): the program stops, the axis stands,
        errors are gone, SET values revert; parameters, arrays and saved programs stay; Autostart runs. The error
        history starts empty (DG 2996: "The list is cleared each time that the controller is powered on")."""
        c = self.controller
        if c.program_state in ("running", "break"):
            c.break_program()
        if c.error:
            c.clear_error()
        c.error_history.clear()  # before Autostart: an error of the autostarted program is the new list's first
        c.program_state = "idle"
        self.recording = None  # a Single Shot recording lives in RAM
        if self.wipe_at_power_on:  # Delete EPROM: the factory settings from this power on (DG 2916-2930)
            self.wipe_at_power_on = False
            self.op_reset("all")
            self.name = ""
        c.can.power_on()       # the CAN interface boots up again (kernel/canport.py)
        self.store.power_on(c)
        self._set_stack_size(self.store.running)

    def op_start(self, number=None, step=False, inputs=()) -> None:
        """`inputs`: [[N, V, T], ...] set T ms after this start (a program header's Test-inputs applied by the IDE,
        decision I23): timed from the start on the controller, so a paced simulator runs them as `run --input`."""
        inputs = [(*_checked_input(n, v), int(t)) for n, v, t in inputs or ()]  # refused before anything starts
        if any(t < 0 for _n, _v, t in inputs):
            raise ValueError("an input time is before the start")
        self._start(number, step)
        for n, v, t in inputs:
            self.controller.io.schedule(self.controller.time_ms + t, n, v)

    def _start(self, number, step) -> None:
        program = self.temporary if number is None else self.programs.get(number)
        if program is None:
            raise ValueError("no program downloaded" if number is None else f"no program {number}")
        c = self.controller
        if c.program_state == "running":
            raise RuntimeError("the controller is executing a program")
        if number is not None:
            self.store.start(c, number)  # by hand: an ordinary program, no Restart afterwards
        else:
            c.load(program)
            c.start()
        self._set_stack_size(number)
        if step:  # Prepare Singlestep (DG 2432-2434): loaded, stopped before the first statement
            c.single_step = True

    def _set_stack_size(self, number) -> None:
        """The program's stack size (Settings → Compiler, DG 3078-3080; error 193 beyond it)."""
        vm = self.controller.vm
        if vm is not None and number in self.stack_sizes:
            vm.stack_size = self.stack_sizes[number]

    def op_break(self) -> None:
        self.controller.break_program()

    def op_continue(self) -> None:
        self.controller.continue_program()

    def op_set_input(self, number, value) -> None:
        """Simulated controllers: a digital input 0/1, or an analog input 53/54 (the I/O panel, decision I23)."""
        number, value = int(number), int(value)
        io = self.controller.io
        if number in ANALOG_INPUTS:
            io.analog[number] = value
        else:  # any number, as before: a scope test drives bit 16 of INPUTS
            io.inputs[number] = 1 if value else 0

    def op_schedule_input(self, number, value, time_ms) -> None:
        number, value = _checked_input(number, value)
        time_ms = int(time_ms)
        if time_ms < 0:
            raise ValueError(f"time {time_ms} ms is before the start")
        self.controller.io.schedule(time_ms, number, value)

    def op_stream(self, signals, interval_ms=1) -> None:
        interval_ms = max(1, int(interval_ms))  # a bad interval leaves the running stream as it was
        self.flush_stream()
        readers = [(name, signal_reader(name)) for name in signals]
        for name, read in readers:  # refuse an unknown signal here, not in the middle of a tick
            try:
                read(self.controller)
            except ControllerError:
                raise ValueError(f"unknown signal '{name}'") from None
        self.stream, self._packets = None, None
        if readers:
            c = self.controller
            self.stream, self._packets = sampling.stream([n for n, _ in readers], [partial(r, c) for _, r in readers],
                                                         interval_ms, self._publish_samples)

    def op_read_signals(self, signals) -> list:
        c = self.controller
        return [signal_reader(name)(c) for name in signals]

    def op_list_signals(self) -> list[dict]:
        return mco_signals()

    def op_list_recordings(self) -> list[dict]:
        return [{"index": i, "name": r.name, "samples": len(r.samples), "indices": r.indices,
                 "running": r.running} for i, r in enumerate(self.controller.recorder.recordings)]

    def op_upload_recording(self, index) -> dict:
        r = self.controller.recorder.recordings[index]
        return {"name": r.name, "interval_ms": r.interval_ms, "start_ms": r.start_ms, "indices": r.indices,
                "names": [sysvar_name(i) for i in r.indices], "samples": [list(s) for s in r.samples],
                # the first kept set: sampling starts on the tick after TESTSTART; cyclic drops the oldest
                "first_ms": r.start_ms + 1 + (r.taken - len(r.samples)) * r.interval_ms}

    def op_start_recording(self, signals, interval_ms=1, destination="DYNMEM", cyclic=False, count=0) -> dict:
        """Single Shot (DG 5287-5324): the scope sets up and starts a recording; a new one replaces the old."""
        readers = [signal_reader(str(name)) for name in signals]
        for name, read in zip(signals, readers, strict=True):
            try:
                read(self.controller)
            except ControllerError:
                raise ValueError(f"unknown signal '{name}'") from None
        self.recording = scope_recording.configure(self.controller, [str(s) for s in signals], readers,
                                                   interval_ms, destination, cyclic, int(count))
        return self.recording.status()

    def op_recording_status(self) -> dict | None:
        return None if self.recording is None else self.recording.status()

    def op_stop_recording(self) -> dict:
        if self.recording is None:
            raise ValueError("no Single Shot recording was started")
        data = self.recording.upload()
        self.recording = None
        return data

    def op_error_history(self) -> list[dict]:
        return [vars(e).copy() for e in self.controller.error_history]

    def op_clear_error(self) -> None:
        self.controller.clear_error()

    def op_clear_error_history(self) -> None:
        """Error History → Clear (DG 3027)."""
        self.controller.error_history.clear()

    def op_save_memory(self, what) -> None:
        """Memory ▸ (DG 2908-2946): copy RAM to EPROM. The simulated MCO 305 keeps saved programs and arrays
        through a power cycle anyway; parameters keep what was last saved (SET values revert, decision K12)."""
        groups = {"ram": (19, 32, 33), "user": (19,), "arrays": (), "app": (19, 32, 33), "option": (32, 33)}
        if what not in groups:
            raise ValueError(f"save_memory {what!r}: choose one of {', '.join(groups)}")
        keep = groups[what]
        if keep:
            self.controller.params.save(lambda index: index // 100 in keep)

    def op_delete_eprom(self) -> None:
        self.wipe_at_power_on = True

    def op_reset(self, what) -> None:
        """Controller → Reset (DG 2948-2980): "parameters" (global and axis to their defaults), "user"
        (19-xx), "arrays" (like DELETE ARRAYS), "all" (a factory reset: also the stored programs)."""
        if what not in RESETS:
            raise ValueError(f"reset {what!r}: choose one of {', '.join(RESETS)}")
        c = self.controller
        if c.program_state == "running":
            raise ValueError("stop the program before a reset")
        groups = {"parameters": (32, 33), "user": (19,), "arrays": (), "all": (19, 32, 33)}[what]
        params = c.params
        for p in params.db:
            if p.index // 100 in groups and not p.read_only:
                params.values[p.index] = params.saved[p.index] = p.to_raw(p.default)
        if what in ("arrays", "all"):
            c.arrays.delete()
            self.recording = None  # it may have been writing into a user array
        if what == "all":
            self.store.delete_all()
            self.temporary = None

    def op_advance(self, ms) -> None:
        for _ in range(int(ms)):
            self.tick()

    # --- debugger -----------------------------------------------------------------------------------------
    def op_set_breakpoints(self, lines) -> None:
        if len(lines) > 10:  # DG 3430: at most 10 breakpoints
            raise ValueError("at most 10 breakpoints")
        self.controller.breakpoints = {int(n) for n in lines}

    def op_step(self) -> None:
        self.controller.continue_program(step=True)

    def op_read_variables(self, names) -> list:
        values = []
        for name in names:
            container, index = self._variable(str(name))
            values.append(container[index])
        return values

    def op_write_variable(self, name, value) -> None:
        container, index, type_ = self._variable(name, with_type=True)
        container[index] = float(value) if type_ == "double" else int(value)

    def _variable(self, name: str, with_type: bool = False):
        vm = self.controller.vm
        if vm is None:
            raise ValueError("no program is loaded")
        text = name.strip()
        base, _, rest = text.partition("[")
        key = base.strip().upper()
        if rest:
            index = int(rest.rstrip("]").strip(), 0)
            arrays = {a.name.upper(): a for a in vm.dims + vm.arrays}
            if key not in arrays:
                raise ValueError(f"no array '{base.strip()}'")
            array = arrays[key]
            if not 1 <= index <= len(array.data):
                raise ControllerError(171, f"{text} outside 1..{len(array.data)}")
            result = (array.data, index - 1, array.type)
        else:
            slots = {v.name.upper(): i for i, v in enumerate(vm.image.globals)}
            if key not in slots:
                raise ValueError(f"no variable '{text}'")
            result = (vm.globals, slots[key], vm.image.globals[slots[key]].type)
        return result if with_type else result[:2]

    def state(self) -> Any:
        return self.controller



def _checked_input(number, value) -> tuple[int, int]:
    """(input, value) a simulated controller can take: digital 0/1 on MCO 1-12 and FC 300 18-33; an analog input
    53/54 takes any value (as `run --input` always let it: a wiring fault may read beyond INAD's range)."""
    number, value = int(number), int(value)
    if number in ANALOG_INPUTS:
        pass
    elif number not in MCO_INPUTS and number not in FC_INPUTS:
        raise ValueError(f"no digital input {number} (MCO 305: 1-12, FC 300: 18-33; analog: 53, 54)")
    elif value not in (0, 1):
        raise ValueError(f"a digital input is 0 or 1, not {value}")
    return number, value
