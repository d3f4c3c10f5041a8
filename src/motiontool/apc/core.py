"""The APC tick core: one POS sample of sources → POS0 → kernel → POS1 → output channel (seed 004 §3.9
L645-651, §4.2-4.3 L777-996, Fig 3-7 text).

Per sample, at time t_k:

1. the plant has run up to t_k with the output channel's values (one POS period plus 250 µs late, L2112-2120);
2. the sources are read (drive encoder, slot encoders, user-program words);
3. POS0 runs (a DPL VM's task, or any callable);
4. the sources are refreshed again, so POS0 edits act in this sample (V01.03.03, L7219-7222); freeze and
   marker events since t_(k−1) are latched at their interpolated positions; a reference freeze may select CAM
   or digital lock;
5. the kernel runs in its run mode: 0 off (not called), 1 disabled (counters and following error only), 2
   enabled — a change to 2 spends one sample disabled first, [4] reports the enable at the end of the kernel
   (L928-930); APCReset costs one disabled sample and pulses [5] (L2432-2444);
6. POS1 runs; the output channel latches; modes 3 and 4 write their parameter at the start of the next sample,
   before its POS0 (L2109, L4259).

Resets (Table 4-2, L975-996): the reference integrator to 0 (relative) or its source (absolute) plus [6], the
feedback integrator to 0 or its source plus [2]; the profile generator output from the feedback integrator and
its input likewise, except in digital lock where the input is the reference integrator.
"""

from __future__ import annotations

from collections.abc import Callable

from motiontool.apc import fused
from motiontool.apc.cam import Cam, CamError
from motiontool.apc.camlaws import ERR_SIZE_ZERO
from motiontool.apc.diglock import DigitalLock
from motiontool.apc.driveparams import MAX_SPEED, DriveParameters
from motiontool.apc.intmath import wrap32
from motiontool.apc.loop import OutputChannel, PositionLoop
from motiontool.apc.plant import Plant, PlantConfig, SlotEncoder
from motiontool.apc.profile import ProfileGenerator
from motiontool.apc.sources import UNCONFIGURED, USER_PROGRAM, Source
from motiontool.apc.units import POS_RATE_US, UserUnits, rpm_to_speed, speed_to_rpm_x10

STOP, POSITION, SPEED, CAM, DIG_LOCK = range(5)
PROFILED_STOP, INSTANT_STOP, LINEAR_STOP, SPEED_STOP = range(4)
APC_VERSION = 10404        # [15]: the firmware generation the simulation follows (V01.04.04, user units)
assert (fused.STOP, fused.CAM) == (STOP, CAM)


class Slots(dict):
    """The three option slots {1, 2, 3} → a position module's encoder or None; `fitted` lists the modules."""

    def __init__(self) -> None:
        super().__init__({1: None, 2: None, 3: None})
        self.fitted: list[SlotEncoder] = []

    def __setitem__(self, slot: int, encoder: SlotEncoder | None) -> None:
        if slot not in (1, 2, 3):
            raise KeyError(f"slot {slot}: the Unidrive SP has slots 1, 2 and 3")
        super().__setitem__(slot, encoder)
        self.fitted = [e for e in self.values() if e is not None]


class KernelCore:
    """State and tick of one SM-Applications APC with its drive (see ApcDrive for the public API)."""

    # The attributes of the tick as slots: a drive has more attributes than CPython keeps in an instance's
    # compact layout (30), so in its dictionary each of these would cost a hashed look-up, some 40 per sample.
    # The rest live in __dict__.
    __slots__ = ("__dict__", "__weakref__", "samples", "time_ns", "period_ns", "quarters", "plant", "slots", "ref",
                 "fb", "pg", "opg", "cam", "loop", "channel", "params", "turns_bits", "pos0", "pos1", "task",
                 "run_mode", "enabled", "reset_status", "_was_enabled", "_reset_request", "reference", "_active",
                 "_ref_last", "offset_select", "stop_mode", "trip", "drive_enabled", "_demand3", "_demand2",
                 "_demand1", "_limit_rpm", "_limit", "ctsync_received", "ctsync_counts", "ctsync_out", "_held")

    def __init__(self, plant: PlantConfig | None = None, *, pos_rate: int | None = None):
        self.params = DriveParameters()
        if pos_rate is not None:
            self.params.values[(81, 12)] = pos_rate
        self.plant = Plant(plant)
        self.slots = Slots()
        self.ref = Source("reference")
        self.fb = Source("feedback")
        self.pg = ProfileGenerator()
        self.opg = ProfileGenerator()
        self.cam = Cam()
        self.dl = DigitalLock()
        self.loop = PositionLoop()
        self.channel = OutputChannel()
        self.turns_bits = 16                 # [14]
        self.user_units: UserUnits | None = None
        self.time_ns = 0
        self.samples = 0
        self.pos0: Callable[[], object] | None = None     # user tasks run inside the tick
        self.pos1: Callable[[], object] | None = None
        self.task: str | None = None         # which DPL task is calling (set by a VM; None = outside)
        self.listeners: list[Callable[[str, dict], None]] = []   # ("error" | "trip", details)
        # control and access
        self.run_mode = 0                    # [0] is "mode 2 requested"
        self.enabled = 0                     # [4]
        self.reset_status = 0                # [5]
        self.absolute_mode = False           # [1]
        self.position_reset_offset = 0       # [2]
        self.reset_sources_on_disable = True  # [3]
        self.ref_reset_offset = 0            # [6]
        self._reset_request = False
        self._was_enabled = False
        # references
        self.reference = STOP                # [100]
        self.action_on_freeze = 0            # [101]
        self.offset_select = 0               # [102]
        self.stop_mode = PROFILED_STOP       # [90]
        self.position_setpoint = 0           # [170] counts
        self.setpoint_rem = 0                # [171] internal remainder, [172] the user's
        self.setpoint_user_rem = 0
        self.speed_setpoint = 0              # [94]
        self.position_offset = 0             # [173]
        self.offset_rem = 0                  # [174] / [175]
        self.offset_user_rem = 0
        self.speed_offset = 0                # [95]
        self.stop_target = 0                 # [176] while Stop is active
        self._active: int | None = None      # the reference the kernel ran last sample
        self._stop_valid = False
        self._cam_selected_pass: tuple[int, str] | None = None   # the POS task pass that selected the CAM
        self._freeze_since: int | None = None
        self._ref_last = 0                   # [28] when the kernel last ran
        self._after_reset = False
        self._bypass_rem = 0                 # speed reference with the generator bypassed: remainder
        # errors and the drive
        self.error_id = 0                    # 90.49
        self.trip = ""                       # "" | "Tr81" | "Tr44"
        self.drive_enabled = True            # the drive's enable and run command (→ #1.11)
        # the drive speed demands (APC units) latched 3, 2 and 1 samples ago: the output channel's pipeline
        self._demand3 = self._demand2 = self._demand1 = 0
        self._held: tuple[tuple[int, int], int] | None = None   # the output channel's holder (modes 3, 4)
        self._limit_rpm: int | None = None   # #1.06 and its speed, cached
        self._limit = 0
        self._install_virtual_parameters()
        self.reinit()

    # --- configuration ----------------------------------------------------------------------------------------
    def reinit(self) -> None:
        """REINIT: take the POS rate from #81.12 (L4678-4723)."""
        code = self.params.values.get((81, 12), 3)
        if code not in POS_RATE_US:
            raise ValueError(f"#81.12 = {code}: the POS task must run (1 = 0.25 ms … 6 = 8 ms)")
        self.period_us = POS_RATE_US[code]
        self.quarters = self.period_us // 250
        self.period_ns = self.period_us * 1000
        self.plant.configure(self.quarters)

    @property
    def time_ms(self) -> float:
        return self.time_ns / 1_000_000

    def get_parameter(self, menu: int, par: int) -> int:
        """#menu.par (0 for anything not modelled)."""
        return self.params.read((menu, par))

    def set_parameter(self, menu: int, par: int, value: int) -> None:
        self.params.write((menu, par), value)

    @property
    def reference_on(self) -> int:
        """#1.11: the drive is healthy, enabled and running (L5078-5080)."""
        return int(self.drive_enabled and not self.trip)

    def _install_virtual_parameters(self) -> None:
        p = self.params

        # factories: each closure keeps its own key, source and attribute
        def channel_reader(k: tuple[int, int]) -> Callable[[], int]:
            return lambda: self._channel_parameter(k)

        def value_writer(k: tuple[int, int]) -> Callable[[int], None]:
            return lambda v: p.values.__setitem__(k, v)

        def source_reader(s: Source, a: str) -> Callable[[], int]:
            return lambda: int(getattr(s, a))

        def source_writer(s: Source, a: str) -> Callable[[int], None]:
            return lambda v: setattr(s, a, v if a == "selector" else bool(v))

        for key in ((1, 21), (3, 22)):
            p.readers[key] = channel_reader(key)
            p.writers[key] = value_writer(key)
        p.readers[(1, 11)] = lambda: self.reference_on
        p.writers[(1, 11)] = lambda v: setattr(self, "drive_enabled", bool(v))   # the run command (A45)
        p.readers[(3, 48)] = lambda: 1          # encoder initialised (L434-437): the simulated one is at once
        p.readers[(3, 34)] = lambda: self.plant.encoder_cpr // 4   # drive encoder lines per revolution (A74)
        p.writers[(3, 34)] = self._set_encoder_lines
        p.readers[(90, 1)] = lambda: self.fb.position
        p.readers[(90, 3)] = lambda: self.ref.position
        p.readers[(90, 18)] = lambda: self.fb.freeze_flag
        p.readers[(90, 19)] = lambda: self.fb.freeze_position
        p.readers[(90, 28)] = lambda: self.ref.freeze_flag
        p.readers[(90, 29)] = lambda: self.ref.freeze_position
        p.readers[(90, 25)] = lambda: self.fb.marker_position
        p.readers[(90, 35)] = lambda: self.ref.marker_position
        p.readers[(90, 41)] = lambda: self.ref.marker_flag
        p.readers[(90, 42)] = lambda: self.fb.marker_flag
        p.readers[(90, 49)] = lambda: self.error_id
        for key, source, attr in (((90, 43), self.ref, "selector"), ((90, 44), self.fb, "selector"),
                                  ((90, 45), self.ref, "marker_enabled"), ((90, 46), self.fb, "marker_enabled"),
                                  ((90, 47), self.ref, "freeze_enabled"), ((90, 48), self.fb, "freeze_enabled")):
            p.readers[key] = source_reader(source, attr)
            p.writers[key] = source_writer(source, attr)

    def _set_encoder_lines(self, lines: int) -> None:
        """#3.34: a quadrature encoder gives 4 counts per line (1024 ppr → 4096 counts, L463-469)."""
        if not 1 <= lines <= 50000:
            raise ValueError(f"#3.34 = {lines}: drive encoder lines per revolution, 1 to 50000")
        self.plant.set_encoder_cpr(4 * lines)

    # --- events ------------------------------------------------------------------------------------------------
    def _emit(self, kind: str, **details) -> None:
        for listener in list(self.listeners):
            listener(kind, details)

    def apc_error(self, code: int, text: str) -> None:
        """An APC runtime error: 90.49 = code, Stop is selected, Tr81 when #81.38 = 1 (L2307-2331)."""
        self.error_id = code
        self.reference = STOP
        self._emit("error", code=code, text=text, time_us=self.time_ns / 1000)
        if self.params.values.get((81, 38), 0) == 1:
            self.trip_drive("Tr81", text)

    def trip_drive(self, trip: str, text: str = "") -> None:
        if not self.trip:
            self.trip = trip
            self._emit("trip", trip=trip, text=text, time_us=self.time_ns / 1000)

    def schedule(self, side: str, kind: str, time_us: float) -> None:
        """A freeze or marker event on the reference or feedback side at `time_us`, after the last sample; it is
        latched in the sample that follows it (decision A13)."""
        if side not in ("reference", "feedback"):
            raise ValueError(f"side {side!r}: reference or feedback")
        if kind not in ("freeze", "marker"):
            raise ValueError(f"event {kind!r}: freeze or marker")
        when = round(time_us * 1000)
        if when <= self.time_ns:
            raise ValueError(f"{kind} at {time_us} µs: the last sample was at {self.time_ns / 1000} µs")
        (self.ref if side == "reference" else self.fb).events.append((when, kind))

    # --- the tick ----------------------------------------------------------------------------------------------
    def _source_word(self, source: Source, drive_word: int) -> int:
        sel = source.selector
        if sel == 0:
            return drive_word
        if sel == USER_PROGRAM:
            return source.user_word
        if sel == UNCONFIGURED:
            return 0
        slot = self.slots.get(sel)
        return slot.word if slot is not None else 0

    def tick(self) -> None:
        """One POS sample (module docstring). Written for speed: it runs 1000-4000 times per simulated second; the
        common state of a CAM or CTSync line runs fused (apc/fused.py), with the same steps."""
        if fused.steady_tick(self):
            return
        self.samples += 1
        t_prev = self.time_ns
        self.time_ns = t_prev + self.period_ns
        if self._held is not None:   # what the channel latched last sample reaches its parameter now (L2109)
            key, value = self._held
            self.params.values[key] = value
            self._held = None
        plant = self.plant
        before = plant.position
        if plant.step(self._demand3, self._demand2, self.drive_enabled and not self.trip):
            self._markers_passed(before, t_prev)
        if self.slots.fitted:
            for slot in self.slots.fitted:
                slot.advance(self.quarters)
        pos0 = self.pos0
        if self.run_mode:
            ref, fb, tb = self.ref, self.fb, self.turns_bits
            # the sample's first reads; the two common sources without a call (what _first_read does)
            if ref.selector == USER_PROGRAM and pos0 is not None:
                ref.sample_start_position, ref.sample_start_integrated = ref.position, ref.integrated
            else:
                self._first_read(ref, pos0, tb)
            if fb.selector == 0:
                fb.refresh(plant.word, tb, True)
            else:
                self._first_read(fb, pos0, tb)
            if pos0 is not None:
                self.task = "pos0"
                pos0()
                # what POS0 wrote counts in this sample (user-program words, filtered inputs, L7219-7222)
                if ref.selector == USER_PROGRAM:
                    ref.refresh(ref.user_word, tb, False)
                elif ref.input_disabled:
                    ref.refresh(ref.word, tb, False)
                if fb.selector == USER_PROGRAM:
                    fb.refresh(fb.user_word, tb, False)
                elif fb.input_disabled:
                    fb.refresh(fb.word, tb, False)
            if ref.events or fb.events:
                self._capture(t_prev)
            if self.run_mode == 2 and self._was_enabled and not self._reset_request:
                self._enabled_sample()
            else:
                self._kernel()
        elif pos0 is not None:
            self.task = "pos0"
            pos0()
        if self.pos1 is not None:
            self.task = "pos1"
            self.pos1()
        self.task = None
        self._latch_output()

    def _channel_parameter(self, key: tuple[int, int]) -> int:
        """#1.21 / #3.22: what the output channel wrote there (rpm×10), computed when read."""
        channel = self.channel
        if channel.enabled and channel.mode == 2 and key == (1, 21):
            return speed_to_rpm_x10(channel.sent)
        return self.params.values.get(key, 0)

    def _first_read(self, source: Source, pos0, tb: int) -> None:
        """The sample's first read of a source. A user-program source is written in POS0 (L3107-3110), so with a
        POS0 it is read after it only."""
        sel = source.selector
        if sel == 0:
            source.refresh(self.plant.encoder_word(), tb, True)
        elif sel != USER_PROGRAM or pos0 is None:
            source.refresh(self._source_word(source, 0), tb, True)
        else:
            source.sample_start_position, source.sample_start_integrated = source.position, source.integrated

    def _markers_passed(self, before: float, t_prev: int) -> None:
        plant = self.plant
        plant.update_marker_window()
        for frac in plant.marker_crossings(before, plant.position):
            self.fb.events.append((t_prev + round(frac * self.period_ns), "marker"))

    def _capture(self, t_prev: int) -> None:
        """Latch the events of (t_(k-1), t_k] now that this sample's positions are known, also those a
        user-program source received in POS0 (decision A13); a reference freeze may select DL or CAM."""
        t_now, tb = self.time_ns, self.turns_bits
        for kind, main in self.ref.capture_events(t_prev, t_now, tb):
            if kind == "freeze" and self.action_on_freeze and self.run_mode == 2:
                self.reference = DIG_LOCK if self.action_on_freeze == 1 else CAM
                self._freeze_since = main
                self._active = None
        self.fb.capture_events(t_prev, t_now, tb)

    def _latch_output(self) -> None:
        channel = self.channel
        speed = self.loop.output if self.enabled else 0
        values = self.params.values
        rpm = values.get(MAX_SPEED, 3000)
        if rpm != self._limit_rpm:
            self._limit_rpm, self._limit = rpm, rpm_to_speed(rpm)
        limit = self._limit
        if channel.enabled and channel.mode == 2:          # the examples' mode: #1.21 and the speed shortcut
            speed = self._clamp_output(speed, limit)
            channel.sent = speed                           # #1.21 shows it (read on demand, _channel_parameter)
        else:
            shortcut, target, value = channel.latch(speed)
            if shortcut is not None:                       # #1.21 / #3.22 hold the clamped value (L2148, A46)
                shortcut = self._clamp_output(shortcut, limit)
                value = speed_to_rpm_x10(shortcut)
            if shortcut is None:
                # modes 3, 4: the holder writes at the start of the next sample (L2109, L4259), as fast as the
                # shortcut reaches the drive; a held #1.21/#3.22 is the speed the drive gets then
                key = (3, 22) if values.get((3, 23), 0) == 1 else (1, 21)
                self._held = (target, value) if target is not None else None
                raw = value if target == key else values.get(key, 0)
                shortcut = self._clamp_output(rpm_to_speed(raw) // 10, limit)
            elif target is not None:
                values[target] = value
            speed = shortcut
        self._demand3, self._demand2, self._demand1 = self._demand2, self._demand1, speed

    def _clamp_output(self, speed: int, limit: int) -> int:
        """#1.06 clamps the speed reference sent to the drive; Tr44 with #81.17 = 1 (L2148)."""
        if speed > limit or speed < -limit:
            if self.params.values.get((81, 17), 0) == 1:
                self.trip_drive("Tr44", "output channel over range (#1.06)")
            return limit if speed > 0 else -limit
        return speed

    # --- the kernel ----------------------------------------------------------------------------------------------
    def _kernel(self) -> None:
        mode = self.run_mode
        if mode == 1 or not self._was_enabled or self._reset_request:
            resetting = self._reset_request and self._was_enabled
            enabling = mode == 2 and not self._was_enabled
            self._disabled_sample(reset=self.reset_sources_on_disable)
            self._was_enabled = mode == 2
            self._reset_request = False
            if enabling and self.reset_sources_on_disable:
                # mode 2 sets the integrators as Table 4-2 (L2381), as APCReset does: a digital lock selected
                # now aims at the reset reference integrator too (L2597, L2616; decision A18)
                self._after_reset = True
            if resetting:
                # APCReset: one disabled sample inside run mode 2 ([4] stays 1, **inferred**); [5] falls at the
                # end of the next kernel run; the references restart (a single-shot CAM, L3664), and a
                # digital lock aims at the reset reference integrator (Table 4-2: rigid lock then shows the
                # reset offset as following error, L2602-2606)
                self.enabled = 1
                self.reset_status = 1
                self._after_reset = True
            return
        self._enabled_sample()

    def _reset_values(self) -> tuple[int, int]:
        """Integrator reset values (Table 4-2): 0 or the source, plus the offsets."""
        if self.absolute_mode:
            return (wrap32(self.ref.input + self.ref_reset_offset), wrap32(self.fb.input + self.position_reset_offset))
        return wrap32(self.ref_reset_offset), wrap32(self.position_reset_offset)

    def _disabled_sample(self, reset: bool) -> None:
        self.enabled = 0
        if reset:
            self.ref.integrated, self.fb.integrated = self._reset_values()
        self.pg.reset(self.fb.integrated)
        self.opg.reset(0)
        self.loop.idle(self.pg.position, self.fb.integrated)
        self._ref_last = self.ref.integrated
        self._active = None

    def _enter(self, reference: int) -> None:
        """The reference changed (or restarts): bumpless set-up of the new one."""
        pg = self.pg
        if reference == STOP:
            self._set_offsets(0)
            self.stop_target = pg.stop_position(linear=self.stop_mode == LINEAR_STOP)
            self._stop_valid = True
        elif reference == CAM:
            cam, selected = self.cam, self._cam_selected_pass
            self._cam_selected_pass = None
            # start index and size written in the pass that selected the CAM wait for its wrap (L3505, L3517)
            window = cam.window_before if selected is not None and cam.window_pass == selected else None
            try:
                cam.engage(window)
            except CamError as exc:
                text = str(exc)
                if window is not None and exc.code == ERR_SIZE_ZERO:
                    text += (": the start index and size set in the POS task that selects the CAM act from its wrap"
                             " on; set them a sample before (L3517-3520)")
                self.apc_error(exc.code, text)
                return self._enter(STOP)
        elif reference == DIG_LOCK:
            if self._after_reset and self.dl.rigid:
                self.dl.engage(0)
                self.dl.rebase(self.dl.ratio.step(self._ref_last))    # the reset reference integrator
            else:
                self.dl.engage(pg.position)
        self._after_reset = False
        self._active = reference

    def _set_offsets(self, select: int) -> None:
        if select == 0 and (self.opg.position or self.opg.speed):
            self.pg.take_over(self.opg)
        self.offset_select = select

    def _enabled_sample(self) -> None:
        pg, q = self.pg, self.quarters
        ref_now = self.ref.integrated
        if self._active != self.reference:
            since = self._freeze_since
            self._freeze_since = None
            self._enter(self.reference)
            d_ref = ref_now - (self._ref_last if since is None else since)
        else:
            d_ref = ref_now - self._ref_last
        if (d_ref + 0x80000000) >> 32:          # outside int32: the reference wrapped
            d_ref = wrap32(d_ref)
        self._ref_last = ref_now
        active = self._active
        if active == CAM:
            try:
                pg.bypass(pg.position + self.cam.step(d_ref), q)
            except CamError as exc:
                self.apc_error(exc.code, str(exc))
            else:
                if self.cam.complete and self.cam.rearm:     # single-shot freeze re-arm (L1605-1622)
                    self.reference = STOP
                    self.ref.reset_freeze()
        elif active == DIG_LOCK:
            self.dl.step(d_ref, pg, q)
        elif pg.disabled or (active == STOP and self.stop_mode == INSTANT_STOP):
            if active == POSITION:
                pg.bypass(self.position_setpoint, q)
            elif active == SPEED:   # no ramps: the speed set point integrated exactly
                step, self._bypass_rem = divmod(self.speed_setpoint * q + self._bypass_rem, 1 << self.turns_bits)
                pg.bypass(wrap32(pg.position + step), q)
            else:
                pg.bypass(pg.position, q)
        elif active == POSITION:
            pg.to_position(self.position_setpoint, q)
        elif active == SPEED:
            pg.to_speed(self.speed_setpoint, q)
        elif self.stop_mode == SPEED_STOP:
            pg.to_speed(0, q)
        else:
            pg.to_position(self.stop_target, q, linear=self.stop_mode == LINEAR_STOP)
        opg, tb = self.opg, self.turns_bits
        if self.offset_select or opg.position or opg.speed:
            self._run_offsets(q)
            self.loop.run(wrap32(pg.position + opg.position), round((pg.speed + opg.speed) * (1 << tb)),
                          self.fb.integrated, tb)
        else:
            self.loop.run(pg.position, round(pg.speed * (1 << tb)), self.fb.integrated, tb)
        self.enabled = 1
        self.reset_status = 0

    def _run_offsets(self, q: int) -> None:
        opg = self.opg
        if self.reference == STOP and self.offset_select:
            self._set_offsets(0)
        select = self.offset_select
        if select == 0:
            if opg.position or opg.speed:
                opg.reset(0)
            return
        if opg.disabled:
            if select == 1:
                opg.bypass(self.position_offset, q)
            else:
                opg.bypass(wrap32(opg.position + self.speed_offset * q // (1 << self.turns_bits)), q)
        elif select == 1:
            opg.to_position(self.position_offset, q)
        else:
            opg.to_speed(self.speed_offset, q)

    # --- helpers for the commands --------------------------------------------------------------------------------
    def stop_position(self) -> int:
        """[91]: the stop target while Stop runs, else where a stop selected now would end (L3367-3376)."""
        if self._active == STOP and self._stop_valid and self.stop_mode != INSTANT_STOP:
            return self.stop_target
        if self.stop_mode == INSTANT_STOP:
            return self.pg.position
        return self.pg.stop_position(linear=self.stop_mode == LINEAR_STOP)
