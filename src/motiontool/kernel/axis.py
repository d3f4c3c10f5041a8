"""The axis: profile generator → position controller → drive/motor plant → encoder → monitoring.

Positions inside are quad counts (qc) in the axis frame (raw encoder count minus the origin); the program
sees user units through units.Scaling. The position law is ours (kernel-spec p.1, docs/plant.md):
every TIMER ms  e = CPOS − APOS,  ref = BANDWIDTH/1000 · (KPROP/1000 · e + I) + FFVEL/1000 · v_cmd
− KDER/1000 · v_act + FFACC/1000 · a_cmd · 1 ms,  I = KINT/1e6 · Σe limited to ±KILIM/1000 · VELMAX,
clipped to the drive's speed limit. With FFVEL = KDER the velocity terms are a D term on the error
(DG 8736: "FFVEL must equal the D factor to get the typical D damping").
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from motiontool.kernel.cam import CamMotion
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.plant import Plant, PlantConfig
from motiontool.kernel.profile import Limits, ProfileGenerator
from motiontool.kernel.units import Scaling

if TYPE_CHECKING:
    from motiontool.kernel.homing import Homing
    from motiontool.kernel.sync import SyncMotion

IDLE, POSITIONING, SPEED, STOPPING, HOMING, SYNC = "idle", "positioning", "speed", "stopping", "homing", "sync"
CAM = "cam"  # SYNCC: axis.sync is a cam.CamMotion
_TO_TARGET = (POSITIONING, STOPPING)  # modes that end when the profile is done


@dataclass(frozen=True)
class Gains:
    """The position controller's parameters (replaced as a whole when parameters are applied)."""

    kprop: float = 30.0
    kder: float = 0.0
    kint: float = 0.0
    kilim: float = 1000.0
    bandwidth: float = 1000.0
    ffvel: float = 0.0
    ffacc: float = 0.0
    timer: int = 1
    poserr: int = 20000
    poserrtime: int = 0
    regwmax: int = 0
    regwmin: int = 0
    # derived in __post_init__: not arguments, not compared (a field without a default: no class attribute)
    kprop_1000: float = field(init=False, repr=False, compare=False)
    kder_1000: float = field(init=False, repr=False, compare=False)
    bandwidth_1000: float = field(init=False, repr=False, compare=False)
    ffvel_1000: float = field(init=False, repr=False, compare=False)
    ffacc_1000: float = field(init=False, repr=False, compare=False)
    window: bool = field(init=False, repr=False, compare=False)
    integrating: bool = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        # the per-mille factors of the position law (kprop_1000 = KPROP/1000 …), divided once instead of every
        # tick: the same floats
        setattr_ = object.__setattr__
        setattr_(self, "kprop_1000", self.kprop / 1000.0)
        setattr_(self, "kder_1000", self.kder / 1000.0)
        setattr_(self, "bandwidth_1000", self.bandwidth / 1000.0)
        setattr_(self, "ffvel_1000", self.ffvel / 1000.0)
        setattr_(self, "ffacc_1000", self.ffacc / 1000.0)
        setattr_(self, "window", bool(self.regwmin or self.regwmax))  # the control window applies
        setattr_(self, "integrating", bool(self.kint and self.kilim))  # the I term applies


class Axis:
    def __init__(self, plant: PlantConfig | None = None):
        self.plant = Plant(plant or PlantConfig())
        self.scaling = Scaling()
        self.gains = Gains()
        self.origin = 0                   # raw qc that is axis position 0 (DEFORIGIN, HOME)
        self.profile = ProfileGenerator(0.0)
        self.control_on = True            # 33-81 power-up state 1 = motor on
        self.mode = IDLE
        self.stopped_motion: tuple | None = None  # what MOTOR STOP / an error interrupted (for CONTINUE)
        self.motor_stop_state = False     # AXEND bit 3
        self.ready_again = False          # AXEND bit 7
        self.posfloat = False
        self.open_loop_reference = 0.0    # OUTAN with MOTOR OFF
        self.integral = 0.0
        self.reference = 0.0
        self._tick = 0
        self._poserr_count = 0
        self.apos = math.floor(self.plant.position)
        self.raw_history: deque[int] = deque([self.apos], maxlen=21)  # AVEL measures over 20 ms (CR 295-296)
        self.target_window: tuple[int, int, int] = (0, 1, 0)  # TESTTIM, TESTVAL, TESTWIN
        self._window_history: list[int] = []
        self.homing: Homing | None = None  # while HOME / INDEX runs
        self.limit_offset = 0             # DEFORIGIN shifts the software limits with the origin (DG 10158)
        self.sync: SyncMotion | CamMotion | None = None  # while SYNCV / SYNCP (mode "sync") or SYNCC ("cam") runs

    # --- readouts (axis frame, qc) ------------------------------------------------------------------
    @property
    def cpos(self) -> float:
        return self.profile.position

    @property
    def tracking_error(self) -> float:
        return self.profile.position - self.apos

    @property
    def raw(self) -> int:
        return math.floor(self.plant.position)

    def measured_velocity(self) -> float:
        """AVEL in qc/ms: the encoder's counts over the measuring time (20 ms, or _GETVEL's), less right after start."""
        h = self.raw_history
        return (h[-1] - h[0]) / (len(h) - 1) if len(h) > 1 else 0.0

    @property
    def moving(self) -> bool:
        return self.mode != IDLE or abs(self.plant.velocity) > 1e-3

    # --- one control tick -----------------------------------------------------------------------------
    def tick(self) -> None:
        # kernel/tick.py repeats the CAM case (steady_cam_tick) operation for operation: change both
        pg = self.profile
        control_on = self.control_on
        if control_on:
            mode = self.mode
            if mode == CAM:
                sync = self.sync
                assert isinstance(sync, CamMotion)  # synchronise() sets the mode and the motion together
                sync.step(pg)
                if sync.finish is not None:  # disengaged: position to the slave stop position
                    self.move_to(*sync.finish)
            elif mode == SYNC:
                sync = self.sync
                assert sync is not None  # synchronise() sets the mode and the motion together
                sync.step(pg)
            elif pg.mode != "idle":
                pg.step()
            if self.homing is not None:
                self.homing.tick(self)
            g = self.gains
            ticks = self._tick + 1
            if ticks >= g.timer:  # the position law (module docstring), every TIMER ms
                self._tick = 0
                e = pg.position - self.apos
                if g.window and self._posfloat(pg, e):
                    reference = 0.0
                else:
                    reference = g.bandwidth_1000 * (g.kprop_1000 * e + (self._integral_term(e) if g.integrating
                                                                         else 0.0))
                    if g.ffvel:
                        reference += g.ffvel_1000 * pg.velocity
                    if g.kder:
                        reference -= g.kder_1000 * self.plant.velocity
                    if g.ffacc:
                        reference += g.ffacc_1000 * pg.acceleration
                self.reference = reference
            else:
                self._tick = ticks
                reference = self.reference
        else:
            self.reference = reference = self.open_loop_reference
        plant = self.plant
        plant.step(reference, self.scaling.vmax)
        self.apos = apos = math.floor(plant.position) - self.origin
        self.raw_history.append(apos + self.origin)
        mode = self.mode
        if mode in _TO_TARGET and pg.done:
            if mode == STOPPING:
                self.motor_stop_state = self.stopped_motion is not None
            self.mode = IDLE
        if self.control_on:  # _monitor, its common case inline (one call less per tick)
            if abs(pg.position - apos) > self.gains.poserr:
                self._monitor()
            else:
                self._poserr_count = 0

    def _posfloat(self, pg: ProfileGenerator, e: float) -> bool:
        """Control window (REGWMIN/REGWMAX set, DG 8855-8887): POSFLOAT inside REGWMIN at standstill, left beyond
        REGWMAX; while it holds the speed reference is 0."""
        g = self.gains
        if self.posfloat and abs(e) > g.regwmax:
            self.posfloat = False
        elif not self.posfloat and pg.mode == "idle" and abs(e) <= g.regwmin:
            self.posfloat = True
        return self.posfloat

    def _integral_term(self, e: float) -> float:
        """I = KINT/1e6 · Σe, limited to ±KILIM/1000 · VELMAX (KINT and KILIM set)."""
        g = self.gains
        self.integral += e
        integral_term = g.kint * self.integral / 1e6
        limit = g.kilim / 1000.0 * self.scaling.vmax
        if abs(integral_term) > limit:
            integral_term = math.copysign(limit, integral_term)
            self.integral = integral_term * 1e6 / g.kint
        return integral_term

    def _monitor(self) -> None:
        """The tracking error is beyond POSERR this tick (tick() tests that inline): error 108 now or after
        POSERRTIME ms of it."""
        g = self.gains
        if g.poserrtime <= 0:
            raise ControllerError(108, f"tracking error {self.profile.position - self.apos:.0f} qc > POSERR "
                                       f"{g.poserr}")
        self._poserr_count += 1  # DG 8913-8933: checked every 20 ms; here every tick, scaled
        if self._poserr_count > g.poserrtime:
            raise ControllerError(108, f"tracking error above POSERR for {g.poserrtime} ms")

    # --- motion commands (targets in the axis frame, qc) -----------------------------------------------
    def limits(self, vel: float, acc: float, dec: float, ramp_type: int, jerk: tuple) -> Limits:
        return Limits(max(vel, 1e-9), max(acc, 1e-12), max(dec, 1e-12), ramp_type, jerk)

    def move_to(self, target: float, limits: Limits) -> None:
        self._leave_sync()
        self._start()
        self.profile.move_to(float(target), limits)
        self.mode = POSITIONING
        self.last_motion = ("position", float(target), limits)

    def run_at(self, velocity: float, limits: Limits) -> None:
        self._leave_sync()
        self._start()
        self.profile.run_at(velocity, limits)
        self.mode = SPEED
        self.last_motion = ("speed", velocity, limits)

    def synchronise(self, motion: SyncMotion | CamMotion, mode: str = SYNC) -> None:
        """SYNCV / SYNCP: from now on the sync motion drives the commanded position (RAMPTYPE does not
        apply, DG 8987)."""
        self._start()
        pos, vel = self.profile.position, self.profile.velocity
        self.profile.hold(pos)
        self.profile.velocity = vel
        self.profile.mode = "sync"
        self.sync = motion
        self.mode = mode
        self.homing = None

    def _leave_sync(self) -> None:
        if self.mode in (SYNC, CAM):
            self.profile.acceleration = 0.0
            self.profile.mode = "idle"
        self.sync = None

    def stop(self, limits: Limits, remember: bool = True) -> None:
        """MOTOR STOP / CSTOP / Esc: brake to standstill; CONTINUE can resume the interrupted motion (not a
        synchronisation, CR 574; MOTOR STOP ends it with DEC, CR 2367-2375)."""
        if remember and self.mode in (POSITIONING, SPEED):
            self.stopped_motion = self.last_motion
        self._leave_sync()
        if self.mode != IDLE or not self.profile.done:
            self.profile.stop(limits)
            self.mode = STOPPING
        self.homing = None

    def hold(self) -> None:
        """Stand still where the motor is (MOTOR ON, ERRCLR): CPOS := APOS, no tracking error."""
        self.sync = None
        self.profile.hold(float(self.apos))
        self.mode = IDLE
        self.integral = 0.0
        self.homing = None

    def motor_off(self) -> None:
        if self.mode in (POSITIONING, SPEED):  # CONTINUE resumes it after MOTOR ON / ERRCLR (CR 564-578)
            self.stopped_motion = self.last_motion
        self.control_on = False
        self.sync = None
        self.profile.hold(float(self.apos))
        self.mode = IDLE
        self.homing = None
        self.open_loop_reference = 0.0

    def motor_on(self) -> None:
        self.control_on = True
        self.hold()
        self.ready_again = True

    def _start(self) -> None:
        self.motor_stop_state = False
        self.posfloat = False
        self.stopped_motion = None  # a new motion replaces what CONTINUE would have resumed

    # --- origins ----------------------------------------------------------------------------------------
    def shift_origin(self, by_qc: int) -> None:
        """Make axis position `by_qc` the new 0 (DEFORIGIN/DEFCORIGIN/HOME); the tracking error is kept."""
        self.origin += by_qc
        self.apos -= by_qc
        if self.mode in (SYNC, CAM):  # the sync relation moves with the origin
            self.profile.position -= by_qc
            assert self.sync is not None  # synchronise() sets the mode and the motion together
            self.sync.shift(-by_qc)
        elif self.profile.done:
            self.profile.hold(self.profile.position - by_qc)
        else:
            self.profile.shift(-by_qc)  # the running plan moves with the origin

    def index_period(self) -> int:
        """Encoder index pulses: one per revolution, 4 × 32-01 ENCODER qc, unless the plant says otherwise."""
        return self.plant.config.index_period_qc or 4 * self.scaling.encoder_ppr

    # --- status -------------------------------------------------------------------------------------------
    def position_reached(self) -> bool:
        """DG 10295-10318: TESTWIN 0 → CPOS at the target; else APOS inside ±TESTWIN and slower than TESTVAL."""
        if self.mode != IDLE or not self.profile.done:
            return False
        testtim, testval, testwin = self.target_window
        if testwin <= 0:
            return True
        if abs(self.profile.position - self.apos) > testwin:
            return False
        history = self._window_history
        history.append(self.apos)
        if len(history) > testtim + 1:
            del history[0]
        return testtim <= 0 or (len(history) > testtim and abs(history[-1] - history[0]) < testval)

    def axend(self) -> int:
        """CR 311-345: 1 reached, 2 positioning, 4 speed mode, 8 MOTOR STOP state, 64 control off, 128 ready."""
        bits = 0
        if self.mode == IDLE and not self.motor_stop_state:
            bits |= 1
        if self.mode == POSITIONING or (self.motor_stop_state and self.stopped_motion
                                        and self.stopped_motion[0] == "position"):
            bits |= 2
        if self.mode == SPEED:
            bits |= 4
        if self.motor_stop_state:
            bits |= 8 | 1 | 64
        if not self.control_on:
            bits |= 64
        if self.ready_again:
            bits |= 128
        return bits
