"""The simulated MCO 305: one control tick per millisecond of virtual time (spec §0, issue 4).

Each tick: scripted inputs → machine switches → axis (profile, control, plant, encoder, monitoring) →
recording → interrupt detection and entry → a slice of the program. Nothing here reads the wall clock,
so the same program and inputs always give the same trace. The tick itself is kernel/tick.py (fused, issue 30).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

from motiontool.aposs.image import CommandCall, ProgramImage
from motiontool.kernel import commands, objdict
from motiontool.kernel import io as iomod
from motiontool.kernel.arrays import ArrayMemory
from motiontool.kernel.axis import Axis, Gains
from motiontool.kernel.cam import CamMotion
from motiontool.kernel.canport import CanPort
from motiontool.kernel.command_base import motion_limits
from motiontool.kernel.errors import AXIS_ERRORS, ControllerError, error_text
from motiontool.kernel.interrupts import Interrupts, interrupt_readings
from motiontool.kernel.markers import Markers
from motiontool.kernel.master import Master, MasterConfig
from motiontool.kernel.parameters import ParameterStore, is_axis_parameter
from motiontool.kernel.plant import PlantConfig
from motiontool.kernel.recorder import Recorder
from motiontool.kernel.sync import SyncMotion
from motiontool.kernel.sysvars import read_sysvar
from motiontool.kernel.tick import controller_tick
from motiontool.kernel.units import Scaling
from motiontool.kernel.vm import VM, ArrayRef

ERROR_HISTORY = 50           # DG 11350
PRINT_BUFFER_LINES = 100     # the PRINT output buffer: a full one makes PRINT wait (decisions K82)
RECENT_EVENTS = 10_000       # events kept in Controller.events (an hour of PRINTs would be gigabytes)


@dataclass
class ErrorRecord:
    time_ms: int
    number: int
    text: str
    line: int | None
    detail: str = ""


@dataclass
class Event:
    """What the controller reports to a link: kind "print" | "error" | "program" | "message"."""

    kind: str
    time_ms: int
    text: str
    number: int = 0
    line: int | None = None


@dataclass
class ProgramData:
    """What a program leaves in the controller and the next program must not inherit (CVEL value, PID
    function state, LINKGPAR links, print device)."""

    speed_value: int = 0
    pid_gains: dict = field(default_factory=lambda: {"KPROP": 0, "KDER": 0, "KINT": 0, "KILIM": 0, "TIMER": 1})
    pid_state: list = field(default_factory=lambda: [0, 0])
    linked: dict = field(default_factory=dict)
    print_device: int = 0
    sync_shift: int = 0                       # Σ MOVESYNCORIGIN (master qc): shifts the curve master position
    next_sync_shift: int = 0                  # Σ MOVESYNCORIGIN given while no SYNCP/SYNCM ran: for the next one
    sync_origin: tuple[int, int] | None = None  # DEFSYNCORIGIN (master, slave) for the next SYNCP
    syncstat_flags: int = 0                   # latched SYNCSTAT bits (marker hits/errors), SYNCSTATCLR
    cam: object | None = None                 # cam.CamState of the last SETCURVE
    mc_ref: tuple = (0, 0)                    # DEFMCPOS: curve master position p (MU) at MAPOS a (qc)
    mc_defined: bool = False                  # a DEFMCPOS was given (ON MCPOS without SETCURVE)


@dataclass
class MotionSettings:
    """VEL/ACC/DEC as the program set them (None = not set: DFLTVEL/DFLTACC, CR 179-180, 3456-3458)."""

    vel: int | None = None
    acc: int | None = None
    dec: int | None = None


class Controller:
    def __init__(self, plant: PlantConfig | None = None, master: MasterConfig | None = None):
        self.time_ms = 0
        self.master = Master(master)
        self.params = ParameterStore()
        self.arrays = ArrayMemory()
        self.io = iomod.IO()
        self.axis = Axis(plant)
        self.interrupts = Interrupts()
        self.recorder = Recorder(self._read_sysvar_for_recording)
        self.vm: VM | None = None
        self.program_state = "idle"    # idle | running | break | ended | error
        self.events: deque[Event] = deque(maxlen=RECENT_EVENTS)
        self.output: deque[tuple[int, str]] = deque()  # PRINT lines the link has not taken yet (time, text)
        self.output_per_tick: int | None = None  # lines the link takes each ms; None: all (an in-process link)
        self.listeners: list[Callable[[Event], None]] = []
        self.error: int = 0            # the pending error (ERRNO)
        self.error_history: list[ErrorRecord] = []
        self.motion = MotionSettings()
        self.program_data = ProgramData()
        self.sysvar_memory: dict[int, int] = {}
        self._switch_state = {}
        self.limit_blocked_direction = 0  # +1/-1 after a limit error: moving that way again is error 198
        self.stopped_line: int | None = None  # the line a breakpoint or single step stopped before
        self.breakpoints: set[int] = set()   # source lines (of the main file) where a debug build stops
        self.single_step = False
        self.pcd: dict[int, int] = {}
        self.apply_parameters()
        self.params.on_change = self._parameter_changed
        self._install_readouts()
        self.markers = Markers(self)  # master/slave markers, MIPOS/IPOS, SYNCM (kernel/markers.py)
        self.can = CanPort(self)      # its CAN controller: mailboxes, PDOs, SDO (kernel/canport.py)
        self._commands = commands.COMMANDS

    # --- parameters → models ---------------------------------------------------------------------------
    def apply_parameters(self) -> None:
        p = self.params
        self.axis.scaling = Scaling.from_params(p)
        self.axis.gains = Gains(p["KPROP"], p["KDER"], p["KINT"], p["KILIM"], p["BANDWIDTH"], p["FFVEL"],
                                p["FFACC"], max(1, p["TIMER"]), max(1, p["POSERR"]), p["POSERRTIME"],
                                p["REGWMAX"], p["REGWMIN"])
        self.axis.target_window = (p["TESTTIM"], p["TESTVAL"], p["TESTWIN"])
        self.soft_limits = (p["NEGLIMIT"] if p["SWNEGLIMACT"] else None,
                            p["POSLIMIT"] if p["SWPOSLIMACT"] else None)

    def _parameter_changed(self, index: int, value: int, source: str) -> None:
        self._functions = None
        if index // 100 in (32, 33):
            self.apply_parameters()
            # DG 9199-9200: with HOME_FORCE "after changing axis parameters" the home run must be repeated
            if self.homed and is_axis_parameter(index) and value != self._homed_with.get(index, value):
                self.homed = False
            if index in (3310, 3311) and self.axis.mode == "sync":  # SYNCFACTM / SYNCFACTS online (K21)
                sync = self.axis.sync
                assert isinstance(sync, SyncMotion)  # Axis.synchronise() sets the mode and the motion together
                sync.regear(self.params["SYNCFACTS"], self.params["SYNCFACTM"])
        if source != "program":  # CR 2779-2810: ON PARAM fires for LCP/SDO/PDO writes, not program writes
            self.interrupts.fire_param(index)

    def _install_readouts(self) -> None:
        s = self
        readouts = {3450: lambda: s.uu(s.axis.apos), 3451: lambda: s.uu(s.axis.cpos),
                    3456: lambda: s.uu(s.axis.tracking_error), 3458: lambda: s.avel(),
                    3440: lambda: s.io.input_word(), 3441: lambda: s.io.output_word(),
                    3461: lambda: s.axis.axend(), 3462: lambda: s.stat(),
                    3452: lambda: s.master.mapos, 3459: lambda: s.master.mavel,
                    3457: lambda: s.syncerr(), 3460: lambda: s.syncstat()}
        self.params.readouts.update(readouts)

    # --- units ------------------------------------------------------------------------------------------
    def uu(self, qc: float) -> int:
        """Axis qc → user units relative to the temporary zero (SETORIGIN)."""
        return self.axis.scaling.qc_to_uu(qc) - self.temp_origin

    temp_origin = 0  # SETORIGIN value in UU

    def qc(self, uu: int) -> int:
        """User units relative to the temporary zero → axis qc (truncating, DG 300-304)."""
        return self.axis.scaling.uu_to_qc(uu + self.temp_origin)

    def avel(self) -> int:
        return self.axis.scaling.velocity_uu_per_s(self.axis.measured_velocity())

    def syncerr(self) -> int:
        """SYNCERR (34-57) in UU: master-derived target − APOS; absolute unless SYNCACCURACY < 0 (DG 9430-9460)."""
        sync = self.axis.sync
        if sync is None:
            return 0
        err = self.axis.scaling.qc_to_uu(sync.error_qc(self.axis.apos))
        return err if sync.accuracy < 0 else abs(err)

    def syncstat(self) -> int:
        """SYNCSTAT (34-60): latched flags plus ACCURACY (4) while a SYNCP is inside SYNCACCURACY."""
        sync = self.axis.sync
        live = sync.status(self.axis.apos) if sync is not None else 0
        return self.program_data.syncstat_flags | live

    def stat(self) -> int:
        """CR 4054-4085: byte 3 MOVING/POSFLOAT, byte 2 control off / position reached, byte 0 switches."""
        a = self.axis
        bits = 0
        if a.moving:
            bits |= 1 << 24
        if a.posfloat:
            bits |= 1 << 27
        if not a.control_on:
            bits |= (1 << 23) | (1 << 2)
        if a.mode == "idle":
            bits |= 1 << 18
        functions = self.input_functions()
        if any(self._function_input(f, functions) for f in (iomod.NEG_LIMIT, iomod.POS_LIMIT)):
            bits |= 1 << 7
        if self._function_input(iomod.HOME_SWITCH, functions):
            bits |= 1 << 6
        return bits

    def _function_input(self, name: str, functions) -> bool:
        entry = functions.get(name)
        if entry is None:
            return False
        number, nc = entry
        return bool(self.io.inputs.get(number, 0)) != nc

    # --- programs ----------------------------------------------------------------------------------------
    @property
    def current_line(self) -> int | None:
        if self.program_state == "break" and self.stopped_line is not None:
            return self.stopped_line
        return self.vm.line if self.vm is not None else None

    def load(self, image: ProgramImage) -> None:
        """Download a (temporary) program: it replaces the current one and is ready to start."""
        if self.program_state == "running":
            raise RuntimeError("a program is running; break it first")
        self.image = image
        self.program_state = "idle"

    def start(self) -> None:
        self.interrupts.reset()
        self.motion = MotionSettings()
        self.program_data = ProgramData()
        self.recorder.reset_settings()
        self.can.program_started()
        self.vm = None
        self.program_state = "running"
        try:
            self.vm = VM(self.image, self)
        except ControllerError as exc:
            self.raise_error(exc)
            if self.program_state == "running":
                self._end_program("error")
            return
        except Exception as exc:  # noqa: BLE001 - a fault of the simulator itself (decisions K81)
            self.internal_fault(exc)
            return
        self._emit(Event("program", self.time_ms, f"program {self.image.name} started"))

    def break_program(self) -> None:
        """[Esc]: stop the program, the axis stops with maximum deceleration (DG 2054-2062, ESCCOND)."""
        if self.program_state != "running":
            return
        self.program_state = "break"
        self._esc_stop()
        self._restore_parameters()  # CR 3896-3899: after an abort the original values are back
        self._emit(Event("program", self.time_ms, "program stopped by break"))

    def continue_program(self, step: bool = False) -> None:
        """Continue after a break or breakpoint; with `step`, stop again before the next statement."""
        if self.program_state == "break" and self.vm is not None and not self.vm.ended:
            self.single_step = step
            self.program_state = "running"
            self.stopped_line = None
            if self.axis.stopped_motion is not None and not step:
                self._commands["CONTINUE"](self, self.vm, [])

    def statement_stop(self, vm: VM, line_index: int) -> bool:
        """Debug builds: stop before a statement with a breakpoint, or the next one when single-stepping."""
        entry = vm.image.lines[line_index]
        if not (self.single_step or (entry.file == 0 and entry.line in self.breakpoints)):
            return False
        self.single_step = False
        self.program_state = "break"
        self.stopped_line = entry.line
        if self.axis.mode != "idle":  # DG 3352-3354: a breakpoint stops the drive like [Esc]
            self._esc_stop()
        self._emit(Event("program", self.time_ms, f"stopped at line {entry.line}", line=entry.line))
        return True

    def _esc_stop(self) -> None:
        a = self.axis
        fast = a.limits(a.scaling.vmax, a.scaling.amax, a.scaling.amax, 0, (0, 0, 0, 0))
        a.stop(fast)
        self.master.stop_virtual()  # DG 10782: [Esc] stops the master simulation
        if self.params["ESCCOND"] in (1, 2):
            level = 0 if self.params["ESCCOND"] == 1 else 1
            for n in iomod.OUTPUTS:
                self.io.outputs[n] = level
        self._brake(True)

    def _restore_parameters(self) -> None:
        self.params.restore()
        self._functions = None
        self.apply_parameters()

    def _end_program(self, state: str) -> None:
        self.program_state = state
        self._motion_at_program_end()
        self._restore_parameters()
        self.interrupts.reset()
        self.recorder.active = None
        self._emit(Event("program", self.time_ms, f"program {state}"))

    def _motion_at_program_end(self) -> None:
        """A program ends (its last statement, EXIT, an error without handler; decision K49): a motion with a target
        runs to it (CR 1340-1342: EXIT "ends a program where active positioning procedures are being carried out to
        the end"); CAM disengages with the second start/stop pair (DG 4054), speed mode and SYNCV/SYNCP/SYNCM stop
        with DEC: no program keeps them going (DG 1488: "Empty main loop so that program will not be terminated")."""
        axis = self.axis
        if axis.mode == "cam":
            assert isinstance(axis.sync, CamMotion)  # Axis.synchronise() sets the mode and the motion together
            if axis.sync.program_ended():
                self.message("the program ended in CAM mode: the slave disengages to the Slave Stop Position")
        elif axis.mode in ("sync", "speed"):

            what = "speed mode" if axis.mode == "speed" else "the synchronisation"
            axis.stop(motion_limits(self), remember=False)
            self.message(f"the program ended: {what} stops with DEC")

    # --- time ------------------------------------------------------------------------------------------
    tick = controller_tick  # kernel/tick.py: one millisecond, fused (issue 30)

    def run_for(self, ms: int, until: Callable[[], bool] | None = None) -> None:
        for _ in range(ms):
            self.tick()
            if until is not None and until():
                return

    _functions: dict | None = None
    _last_inputs: dict | None = None
    _switch_state: dict = {}

    def input_functions(self) -> dict:
        """33-5x input functions, recomputed only when a parameter changes."""
        if self._functions is None:
            self._functions = iomod.input_functions(self.params)
        return self._functions

    def _machine_inputs(self) -> None:
        functions = self.input_functions()
        if not functions:
            return
        plant = self.axis.plant
        home = functions.get(iomod.HOME_SWITCH)
        if home:
            self.io.inputs[home[0]] = int(plant.home_switch() != home[1])
        neg, pos = plant.limit_switches()
        for name, active in ((iomod.NEG_LIMIT, neg), (iomod.POS_LIMIT, pos)):
            entry = functions.get(name)
            if entry and (plant.config.neg_limit_switch_qc is not None or
                          plant.config.pos_limit_switch_qc is not None):
                self.io.inputs[entry[0]] = int(active != entry[1])
        for name in (iomod.NEG_LIMIT, iomod.POS_LIMIT):
            active = self._function_input(name, functions)
            was = self._switch_state.get(name, False)
            self._switch_state[name] = active
            if not active or self.error or not self.axis.control_on:
                continue
            direction = -1 if name == iomod.NEG_LIMIT else 1
            # DG 11618-11628: 125 when the switch comes on, or when the axis is driven further into it;
            # after ERRCLR it may stand on the switch and move away (the other way is 198).
            if not was or self.axis.profile.velocity * direction > 0:
                self.limit_blocked_direction = direction
                raise ControllerError(125, f"{name.replace('_', ' ')} switch")
        # DG 10336-10418: error clear, break and continue inputs act on their rising edge
        now = {name: self._function_input(name, functions)
               for name in (iomod.ERROR_CLEAR, iomod.BREAK, iomod.CONTINUE) if name in functions}
        last = self._last_inputs or {}
        self._last_inputs = now
        if now.get(iomod.ERROR_CLEAR) and not last.get(iomod.ERROR_CLEAR) and self.error:
            self.clear_error()
        if now.get(iomod.BREAK) and not last.get(iomod.BREAK):
            self.break_program()
        if now.get(iomod.CONTINUE) and not last.get(iomod.CONTINUE):
            self.continue_program()

    def _soft_limits_while_moving(self) -> None:
        """DG 10213: in speed (and sync) modes a software limit is found when the axis reaches it."""
        low, high = self.soft_limits
        apos = self.axis.apos + self.axis.limit_offset
        v = self.axis.plant.velocity
        if self.error:
            return
        if low is not None and apos <= low and v < 0:
            self.limit_blocked_direction = -1
            raise ControllerError(111, "actual position reached NEGLIMIT")
        if high is not None and apos >= high and v > 0:
            self.limit_blocked_direction = 1
            raise ControllerError(111, "actual position reached POSLIMIT")

    def _inside_soft_limits(self) -> bool:
        low, high = self.soft_limits
        apos = self.axis.apos + self.axis.limit_offset
        return (low is None or apos > low) and (high is None or apos < high) and not any(
            self._function_input(n, self.input_functions()) for n in (iomod.NEG_LIMIT, iomod.POS_LIMIT))

    def _read_sysvar_for_recording(self, index: int) -> int:
        value = read_sysvar(self, index)
        return 0 if value is None else value

    def _serve_interrupts(self, vm: VM) -> None:
        actions = self.interrupts.detect(self.time_ms, *interrupt_readings(self)) if self.interrupts.sources else []
        for out, level in actions:
            self.io.outputs[out] = level
        if self.error and self.interrupts.error_sub is not None and not any(
                s.interrupt == "ERROR" for s in vm.subs):
            vm.enter_interrupt(self.interrupts.error_sub, "ERROR")
            return
        if vm.in_interrupt:
            return
        source = self.interrupts.next_ready()
        if source is not None:
            source.pending = False
            vm.enter_interrupt(source.sub, source.kind)

    def interrupt_returned(self, vm: VM, kind: str) -> None:
        """CR 2657-2660: an error handler that returns with the error still pending is called again."""
        if kind == "ERROR" and self.error and self.interrupts.error_sub is not None:
            vm.enter_interrupt(self.interrupts.error_sub, "ERROR")

    def statbits(self) -> int:
        st = self.stat()
        # CR 3021-3040: byte 3 = MOVING …, byte 4 = SYNCSTAT (bit 25 SYNCREADY … bit 31 SYNCSMERR)
        return (((st >> 24) & 0xFF) << 16) | ((self.syncstat() & 0x7F) << 24)

    # --- errors --------------------------------------------------------------------------------------------
    def raise_error(self, exc: ControllerError) -> None:
        line = self.vm.line if self.vm is not None else None
        number = exc.number
        self.error_history.append(ErrorRecord(self.time_ms, number, error_text(number), line, exc.detail))
        del self.error_history[:-ERROR_HISTORY]
        first = not self.error
        if first:
            self.error = number
        self._emit(Event("error", self.time_ms, f"error {number}: {error_text(number)}", number, line))
        if number == 108:  # DG 8752-8786: the position control is switched off
            self.axis.motor_off()
        if number in AXIS_ERRORS or number == 105:
            self._error_reaction(number)
        if self.program_state == "running" and self.interrupts.error_sub is None:
            self._fail(exc, already_reported=True)

    def internal_fault(self, exc: Exception) -> None:
        """A fault of the simulator while a program runs (never of the program): error 199 Internal MCO fault
        (DG 11403); the program ends whatever ON ERROR says, since its state can no longer be trusted, and the axis
        reacts per ERRCOND. It never stays "running"."""
        self.raise_error(ControllerError(199, f"{type(exc).__name__}: {exc}"))
        if self.program_state == "running":
            self._end_program("error")

    def _fail(self, exc: ControllerError, already_reported: bool = False) -> None:
        if not already_reported:
            line = self.vm.line if self.vm is not None else None
            self.error = self.error or exc.number
            self._emit(Event("error", self.time_ms, f"error {exc.number}: {error_text(exc.number)}",
                             exc.number, line))
            self._error_reaction()
        self._end_program("error")

    def _error_reaction(self, number: int = 0) -> None:
        """33-83 ERRCOND (DG 10730-10758): 0 coast, 1 coast + brake, 2/3 stop with max. deceleration. A hardware limit
        switch (125) with 33-40 ENDSWMOD 1 "Controlled stop" stops with the stop ramp instead of coasting (K13)."""
        mode = self.params["ERRCOND"]
        if number == 125 and self.params["ENDSWMOD"] == 1 and mode in (0, 1):
            mode += 2
        a = self.axis
        if mode in (0, 1):
            a.motor_off()
        elif mode in (2, 3):
            fast = a.limits(a.scaling.vmax, a.scaling.amax, a.scaling.amax, 0, (0, 0, 0, 0))
            a.stop(fast)
        if mode in (1, 3):
            self._brake(True)

    def _brake(self, on: bool) -> None:
        for n, index in iomod.OUTPUT_FUNCTION_PARAMETERS.items():
            code = self.params.values.get(index, 0)
            if code in (5, 6):
                self.io.outputs[n] = int(on) if code == 5 else int(not on)

    def clear_error(self) -> None:
        """ERRCLR: clears the pending error and switches position control on where the axis is."""
        self.error = 0
        self.axis.motor_on()

    # --- host interface for the VM ------------------------------------------------------------------------
    def command(self, vm: VM, call: CommandCall, args: list):
        impl = self._commands.get(call.command)
        if impl is None:
            raise ControllerError(110, f"{call.command} is not simulated")
        return impl(self, vm, args)

    def dim_array(self, index: int, name: str, dims: list[int]) -> ArrayRef:
        return self.arrays.dim(index, name, dims)

    def print_text(self, text: str) -> None:
        if self.program_data.print_device == -1:  # CR 3535-3550: PRINTDEV -1 = "no output after that line"
            return
        self.output.append((self.time_ms, text))

    def print_room(self) -> bool:
        """Room in the PRINT output buffer; the VM's PRINT waits while it is full (decisions K82)."""
        return len(self.output) < PRINT_BUFFER_LINES

    def send_output(self, limit: int | None = None) -> None:
        """Hand up to ``limit`` buffered PRINT lines (all with None) to the listeners, oldest first."""
        output = self.output
        for _ in range(len(output) if limit is None else min(limit, len(output))):
            time_ms, text = output.popleft()
            self._deliver(Event("print", time_ms, text))

    def define_interrupt(self, vm: VM, index: int, operands: list[int]) -> None:
        info = vm.image.interrupts[index]
        self.interrupts.define(info.kind, info.sign, info.subprogram, operands, self.time_ms, info.has_value,
                               info.setout, info.toin, info.delete)
        # the new source starts from the state at its definition, so a change in the next tick fires it
        self.interrupts.prime(*interrupt_readings(self))

    def read_pseudo(self, which: int, index: int) -> int:
        if which == 0:
            value = read_sysvar(self, index)
            return 0 if value is None else value
        return self.pcd.get(index, 0) if which == 1 else self.can.pdo.read_element(index)

    def write_pseudo(self, which: int, index: int, value: int) -> None:
        if which == 0 and index == 4105:  # simulated master position (DG 8370)
            self.master.write_position(value)
            return
        if which == 2:
            self.can.pdo.write_element(index, value)
            return
        if which == 0 and objdict.write_sysvar(self, index, value):  # an object of the dictionary (CR 2039)
            return
        target = self.sysvar_memory if which == 0 else self.pcd
        target[index] = value

    def _homing_finished(self) -> None:
        homing = self.axis.homing
        assert homing is not None  # called when the running homing has finished
        self.axis.homing = None
        self.axis.mode = "idle"
        if not homing.index_only:
            self.axis.shift_origin(round(self.axis.cpos))
            self.axis.limit_offset = 0
            self.homed = True
            self._homed_with = {i: v for i, v in self.params.values.items() if is_axis_parameter(i)}

    homed = False             # a HOME completed since power on and no axis parameter changed since (HOME_FORCE)
    _homed_with: dict = {}    # the axis parameters of that HOME

    # --- events ------------------------------------------------------------------------------------------
    def message(self, text: str, line: int | None = None) -> None:
        """A notice for the user (Communication window, `motiontool run`'s stderr) that is not an error."""
        self._emit(Event("message", self.time_ms, text, line=line))

    def _emit(self, event: Event) -> None:
        if self.output:  # what the program printed before comes first
            self.send_output()
        self._deliver(event)

    def _deliver(self, event: Event) -> None:
        self.events.append(event)
        for listener in self.listeners:
            listener(event)
