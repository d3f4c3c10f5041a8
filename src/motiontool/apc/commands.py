"""The APC's DPL function calls, part 1: control and access, encoders, CTSync, position loop, output channel,
conversion (seed 004 §5.2.1-5.2.3 L2364-3288, §5.2.6 L4052-4316, §5.3 L4317-4495; quick reference L7502-7699).

Names and argument orders are the manual's. Every call returns its Status% (1 ok, 0 failed, −4 an argument out
of range — APC_INVALID_ARGU, L8005-8013; which calls answer −4 rather than 0 is **inferred**, docs/decisions.md
A6) unless the manual prints other outputs; several outputs come back as a tuple in the printed order.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from motiontool.apc import core
from motiontool.apc.driveparams import RS485_MODE
from motiontool.apc.intmath import INT32_MAX, INT32_MIN
from motiontool.apc.readpars import RAW_OFFSET, READ_PARAMETERS
from motiontool.apc.sources import user_word
from motiontool.apc.units import (
    SPEED_LIMIT,
    UserUnits,
    speed_to_rpm_x10,
)

if TYPE_CHECKING:
    from motiontool.apc.cam import Cam
    from motiontool.apc.diglock import DigitalLock
    from motiontool.apc.driveparams import DriveParameters
    from motiontool.apc.loop import OutputChannel, PositionLoop
    from motiontool.apc.profile import ProfileGenerator
    from motiontool.apc.sources import Source
    from motiontool.apc.units import EmbeddedConverter, UserDefinedConverter

OK, FAIL, ACCESS_DENY, INVALID = 1, 0, -3, -4


def outputs(*names: str):
    """Mark a call's DPL outputs (default: Status% only)."""
    def mark(fn):
        fn.apc_outputs = names
        return fn
    return mark


def _in(value: int, lo: int, hi: int) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and lo <= value <= hi


class KernelState:
    """What the calls read and write of the kernel's state: KernelCore and ApcDrive create it. Declarations for
    the type checker only (ApcDrive is the calls' mixins on top of KernelCore): nothing here exists at run time."""

    ref: Source
    fb: Source
    pg: ProfileGenerator
    opg: ProfileGenerator
    cam: Cam
    dl: DigitalLock
    loop: PositionLoop
    channel: OutputChannel
    params: DriveParameters
    slots: core.Slots
    samples: int
    task: str | None
    run_mode: int
    enabled: int
    reset_status: int
    reference: int
    user_units: UserUnits | None
    turns_bits: int
    _was_enabled: bool
    _reset_request: bool
    _active: int | None
    _cam_selected_pass: tuple[int, str] | None
    # ApcDrive's
    converter: EmbeddedConverter
    user_converter: UserDefinedConverter
    ctsync_out: tuple[int, int, int] | None
    ctsync_received: tuple[int, int, int, int]
    _readers: dict[int, Callable[[], int]]

    if TYPE_CHECKING:  # KernelCore's methods; defined here at run time they would hide those
        def apc_error(self, code: int, text: str) -> None: ...
        def trip_drive(self, trip: str, text: str = "") -> None: ...
        def stop_position(self) -> int: ...
        def _set_offsets(self, select: int) -> None: ...


class Conversions(KernelState):
    """User-unit conversions at the API boundary: the kernel always works in counts (L2197-2209)."""

    def _pos_in(self, value: int, rem: int = 0) -> tuple[int, int]:
        """(counts, internal remainder) of a position the program gives."""
        return self.user_units.to_counts(value, rem) if self.user_units else (value, 0)

    def _rate_in(self, value: int, order: int) -> int:
        return self.user_units.to_apc_rate(value, order) if self.user_units else value

    def _pos_out(self, counts: int) -> tuple[int, int]:
        return self.user_units.to_user(counts) if self.user_units else (counts, 0)

    def _rate_out(self, value: int, order: int) -> int:
        return self.user_units.to_user_rate(value, order) if self.user_units else value


class ControlCommands(Conversions):
    # --- control and access (L2364-2680) ---------------------------------------------------------------------
    def APCSetRunMode(self, Mode: int) -> int:
        if not _in(Mode, 0, 2):
            return INVALID
        if Mode == 2 and self.run_mode != 2:
            self._was_enabled = False          # one disabled sample first (L928-930)
            if self.reference == core.CAM:
                self._active = None            # leaving run mode 2 and coming back restarts the CAM (L1567)
        if Mode != 2:
            self.enabled = 0
        self.run_mode = Mode
        return OK

    def APCReset(self) -> int:
        """Only in run mode 2 (L2436); with APCDoNotResetSourcesOnDisable the counters stay and only a
        single-shot CAM restarts (L2437)."""
        if self.run_mode != 2:
            return FAIL
        self._reset_request = True
        self.reset_status = 1
        return OK

    @outputs("Speed%")
    def APCGetOutputSpeed(self) -> int:
        return self._rate_out(self.loop.output, 1)

    @outputs("Speed%")
    def APCGetOutputSpeedRpmx10(self) -> int:
        return speed_to_rpm_x10(self.loop.output)

    def APCSelectAbsoluteMode(self) -> int:
        self.absolute_mode = True
        return OK

    def APCSelectRelativeMode(self) -> int:
        self.absolute_mode = False
        return OK

    @outputs("Value%", "Status%")
    def APCReadPar(self, APCParameterNumber: int) -> tuple[int, int]:
        """[n] in counts or user units; n + 1000 reads the raw APC value (L2203-2209)."""
        value = self.read_parameter(APCParameterNumber)
        return (0, FAIL) if value is None else (value[0], OK)

    @outputs("Value%", "Remainder%", "Status%")
    def APCReadParWithRem(self, APCParameterNumber: int) -> tuple[int, int, int]:
        """With the signed remainder of a position in user units; not with +1000 (L2545-2552)."""
        if not isinstance(APCParameterNumber, int) or APCParameterNumber >= RAW_OFFSET:
            return 0, 0, FAIL
        value = self.read_parameter(APCParameterNumber)
        return (0, 0, FAIL) if value is None else (value[0], value[1], OK)

    def APCSetPositionResetOffset(self, Position: int) -> int:
        self.position_reset_offset = self._pos_in(Position)[0]
        return OK

    def APCSetRefPosResetOffset(self, Position: int) -> int:
        self.ref_reset_offset = self._pos_in(Position)[0]
        return OK

    def APCResetSourcesOnDisable(self) -> int:
        self.reset_sources_on_disable = True
        return OK

    def APCDoNotResetSourcesOnDisable(self) -> int:
        self.reset_sources_on_disable = False
        return OK

    # --- reference and feedback encoders (L2683-3240) ------------------------------------------------------------
    def _select_source(self, source, Source: int) -> int:
        if not _in(Source, 0, 5):
            return INVALID
        if Source in (1, 2, 3) and self.slots.get(Source) is None:
            # "The slot selected … does not contain a position option module" trips Tr81 (L2326-2327)
            source.selector = Source
            self.trip_drive("Tr81", f"no position module in slot {Source}")
            return FAIL
        previous = getattr(source, "set_by_task", None)
        if previous is not None and self.task is not None and previous != self.task:
            # changing a source from more than one task trips Tr81 (L2328-2331)
            self.trip_drive("Tr81", f"{source.name} source set from tasks {previous} and {self.task}")
        source.set_by_task = self.task
        source.selector = Source
        return OK

    def APCSetReferenceSource(self, Source: int) -> int:
        return self._select_source(self.ref, Source)

    def APCSetFeedbackSource(self, Source: int) -> int:
        return self._select_source(self.fb, Source)

    @outputs("Source%", "Status%")
    def APCGetReferenceStatus(self) -> tuple[int, int]:
        return self.ref.selector, OK

    @outputs("Source%", "Status%")
    def APCGetFeedbackStatus(self) -> tuple[int, int]:
        return self.fb.selector, OK

    def APCSetNumOfTurnsBits(self, TurnBits: int) -> int:
        if not _in(TurnBits, 1, 16):
            return INVALID
        self.turns_bits = TurnBits
        self.pg.turns_bits = self.opg.turns_bits = TurnBits
        if self.user_units:
            self.user_units = UserUnits(self.user_units.numerator, self.user_units.denominator, TurnBits)
        return OK

    def _flag(self, source, attr: str, value) -> int:
        setattr(source, attr, value)
        return OK

    def APCEnableRefSourceMarker(self) -> int:
        return self._flag(self.ref, "marker_reset", True)

    def APCDisableRefSourceMarker(self) -> int:
        return self._flag(self.ref, "marker_reset", False)

    def APCEnableFbckSourceMarker(self) -> int:
        return self._flag(self.fb, "marker_reset", True)

    def APCDisableFbckSourceMarker(self) -> int:
        return self._flag(self.fb, "marker_reset", False)

    def APCResetRefSourceMarkerFlag(self) -> int:
        return self._flag(self.ref, "marker_flag", 0)

    def APCResetFbckSourceMarkerFlag(self) -> int:
        return self._flag(self.fb, "marker_flag", 0)

    def APCResetRefSourceFreezeFlag(self) -> int:
        return self._flag(self.ref, "freeze_flag", 0)

    def APCResetFbckSourceFreezeFlag(self) -> int:
        return self._flag(self.fb, "freeze_flag", 0)

    def APCEnableReferenceMarker(self) -> int:
        return self._flag(self.ref, "marker_enabled", True)

    def APCDisableReferenceMarker(self) -> int:
        return self._flag(self.ref, "marker_enabled", False)

    def APCEnableFeedbackMarker(self) -> int:
        return self._flag(self.fb, "marker_enabled", True)

    def APCDisableFeedbackMarker(self) -> int:
        return self._flag(self.fb, "marker_enabled", False)

    def APCEnableReferenceFreeze(self) -> int:
        return self._flag(self.ref, "freeze_enabled", True)

    def APCDisableReferenceFreeze(self) -> int:
        return self._flag(self.ref, "freeze_enabled", False)

    def APCEnableFeedbackFreeze(self) -> int:
        return self._flag(self.fb, "freeze_enabled", True)

    def APCDisableFeedbackFreeze(self) -> int:
        return self._flag(self.fb, "freeze_enabled", False)

    def APCInvertRefSource(self) -> int:
        return self._flag(self.ref, "inverted", True)

    def APCDoNotInvertRefSource(self) -> int:
        return self._flag(self.ref, "inverted", False)

    def APCInvertFbckSource(self) -> int:
        return self._flag(self.fb, "inverted", True)

    def APCDoNotInvertFbckSource(self) -> int:
        return self._flag(self.fb, "inverted", False)

    def APCSetReferencePosition(self, Turns: int, Position: int, PositionFine: int) -> int:
        """User-program reference source: three 16-bit fields (L3093-3110)."""
        # user_word() written out, fewer operations on 48-bit numbers: the CTSync examples call this in every
        # sample with PositionFine 0
        word = ((Turns & 0xFFFF) << 16 | Position & 0xFFFF) << 16
        self.ref.user_word = word | PositionFine & 0xFFFF if PositionFine else word
        return OK

    def APCSetFeedbackPosition(self, Turns: int, Position: int, PositionFine: int) -> int:
        self.fb.user_word = user_word(Turns, Position, PositionFine)
        return OK

    def APCEnableRefInput(self) -> int:
        return self._flag(self.ref, "input_disabled", False)

    def APCDisableRefInput(self) -> int:
        return self._flag(self.ref, "input_disabled", True)

    def APCEnableFbckInput(self) -> int:
        return self._flag(self.fb, "input_disabled", False)

    def APCDisableFbckInput(self) -> int:
        return self._flag(self.fb, "input_disabled", True)

    def APCSetRefInput(self, RefIn: int) -> int:
        """Counts only, also in user-unit mode (L2289-2305); ignored while the input is enabled (L1160)."""
        if not _in(RefIn, INT32_MIN, INT32_MAX):
            return INVALID
        self.ref.user_input = RefIn
        return OK

    def APCSetFbckInput(self, FbckIn: int) -> int:
        if not _in(FbckIn, INT32_MIN, INT32_MAX):
            return INVALID
        self.fb.user_input = FbckIn
        return OK

    # --- CTSync (L3241-3288) ---------------------------------------------------------------------------------
    def CTSyncSetMasterReferences(self, Reference1: int, Reference2: int, AuxRef: int) -> int:
        """Master only (#81.06 = 25); the data reaches every node's CTSyncGetSlaveReferences next sample."""
        if self.params.values.get(RS485_MODE) != 25:
            return -2            # USR_NOT_MASTER (L8028-8036)
        self.ctsync_out = (Reference1, Reference2, AuxRef & 0xFF)
        return OK

    @outputs("Reference1%", "Reference2%", "AuxRef%", "Status%")
    def CTSyncGetSlaveReferences(self) -> tuple[int, int, int, int]:
        return self.ctsync_received

    # --- position loop (L4052-4252) -----------------------------------------------------------------------------
    def _loop_set(self, attr: str, value: int, lo: int, hi: int) -> int:
        if not _in(value, lo, hi):
            return INVALID
        setattr(self.loop, attr, value)
        return OK

    def APCSetPGain(self, Gain: int) -> int:
        return self._loop_set("kp", Gain, 0, 65535)

    def APCSetPGainSpeedClamp(self, PClamp: int) -> int:
        return self._loop_set("p_clamp", self._rate_in(PClamp, 1), 0, SPEED_LIMIT)

    def APCEnableExternalRefSpeed(self) -> int:
        self.loop.ext_speed_selected = True
        return OK

    def APCDisableExternalRefSpeed(self) -> int:
        self.loop.ext_speed_selected = False
        return OK

    def APCSetExternalRefSpeed(self, Speed: int) -> int:
        return self._loop_set("ext_speed", self._rate_in(Speed, 1), -SPEED_LIMIT, SPEED_LIMIT)

    def APCEnableExternalRefPosition(self) -> int:
        self.loop.ext_pos_selected = True
        return OK

    def APCDisableExternalRefPosition(self) -> int:
        self.loop.ext_pos_selected = False
        return OK

    def APCSetExternalRefPosition(self, Position: int) -> int:
        return self._loop_set("ext_position", self._pos_in(Position)[0], INT32_MIN, INT32_MAX)

    def APCSetSpeedFFwdGain(self, Gain: int) -> int:
        return self._loop_set("ff_gain", Gain, 0, 2000)

    def APCSetOutputRatioNumerator(self, Numerator: int) -> int:
        return self._loop_set("ratio_num", Numerator, 0, INT32_MAX)

    def APCSetOutputRatioDenominator(self, Denominator: int) -> int:
        """A divisor (the command page's "multiplied by the denominator" is a slip, spec §9.15)."""
        return self._loop_set("ratio_den", Denominator, 1, INT32_MAX)

    def APCSetOutputSpeedClamp(self, Clamp: int) -> int:
        return self._loop_set("output_clamp", self._rate_in(Clamp, 1), 0, SPEED_LIMIT)

    # --- output channel (L4253-4316) ---------------------------------------------------------------------------
    def APCSetupOutputChannel(self, Mode: int, Menu: int, Parameter: int) -> int:
        if Mode in (3, 4, 13, 14) and not (_in(Menu, 0, 99) and _in(Parameter, 0, 99)):
            return -4            # CHAN_INVALID_PAR
        return OK if self.channel.setup(Mode, Menu, Parameter) else -5    # CHAN_INVALID_OP

    def APCEnableOutputChannel(self) -> int:
        self.channel.enabled = True
        return OK

    def APCDisableOutputChannel(self) -> int:
        self.channel.enabled = False
        return OK

    def APCWriteOutputChannel(self, Value: int) -> int:
        self.channel.user_value = Value
        return OK

    # --- conversion (L4317-4495) ------------------------------------------------------------------------------
    def SetUPRNumeratorAndDenominator(self, Numerator: int, Denominator: int) -> int:
        why = UserUnits.check(Numerator, Denominator, self.turns_bits)
        if why:
            return INVALID
        self.user_units = UserUnits(Numerator, Denominator, self.turns_bits)
        self.converter.numerator, self.converter.denominator = Numerator, Denominator
        return OK

    @outputs("Numerator%", "Denominator%", "Status%")
    def GetUPRNumeratorAndDenominator(self) -> tuple[int, int, int]:
        u = self.user_units
        return (u.numerator, u.denominator, OK) if u else (1, 1, OK)

    def SetUPR(self, UPR: int) -> int:
        """The legacy single-value units per revolution of §8.3.1 (L6795) for the converter blocks only."""
        if not _in(UPR, 1, INT32_MAX):
            return INVALID
        self.converter.numerator, self.converter.denominator = UPR, 1
        return OK

    @outputs("APCPos%", "Status%")
    def UserToAPCPosition(self, UserPos: int) -> tuple[int, int]:
        return self.converter.user_to_apc_position(UserPos, self.turns_bits)

    @outputs("UserPos%", "Status%")
    def APCToUserPosition(self, APCPos: int) -> tuple[int, int]:
        return self.converter.apc_to_user_position(APCPos, self.turns_bits)

    @outputs("APCVel%", "Status%")
    def UserToAPCVelocity(self, UserVel: int) -> tuple[int, int]:
        return self.converter.user_to_apc_rate(UserVel, 1, self.turns_bits)

    @outputs("UserVel%", "Status%")
    def APCToUserVelocity(self, APCVel: int) -> tuple[int, int]:
        return self.converter.apc_to_user_rate(APCVel, 1, self.turns_bits)

    @outputs("APCAccel%", "Status%")
    def UserToAPCAcceleration(self, UserAccel: int) -> tuple[int, int]:
        return self.converter.user_to_apc_rate(UserAccel, 2, self.turns_bits)

    @outputs("UserAccel%", "Status%")
    def APCToUserAcceleration(self, APCAccel: int) -> tuple[int, int]:
        return self.converter.apc_to_user_rate(APCAccel, 2, self.turns_bits)

    def SetConverterNumerator(self, Numerator: int) -> int:
        self.user_converter.numerator = Numerator
        return OK

    def SetConverterDenominator(self, Denominator: int) -> int:
        self.user_converter.denominator = Denominator
        return OK

    @outputs("Output%")
    def ConvertForwards(self, Input: int) -> int:
        return self.user_converter.forwards(Input)

    @outputs("Output%")
    def ConvertBackwards(self, Input: int) -> int:
        return self.user_converter.backwards(Input)

    # --- the read-parameter store -------------------------------------------------------------------------------
    def read_parameter(self, number: int) -> tuple[int, int] | None:
        """([n] as APCReadPar reports it, remainder) or None for an unknown number."""
        if not isinstance(number, int) or isinstance(number, bool):
            return None
        raw = number >= RAW_OFFSET
        base = number - RAW_OFFSET if raw else number
        reader = self._readers.get(base)
        if reader is None:
            return None
        value = reader()
        kind = READ_PARAMETERS[base].kind
        if raw or self.user_units is None or kind in ("none", "counts"):
            return value, 0
        if kind == "pos":
            return self._pos_out(value)
        return self._rate_out(value, {"speed": 1, "accel": 2, "jerk": 3}[kind]), 0

