"""The APC's DPL function calls, part 2: references (Stop, Position, Speed, CAM, Digital Lock) and the profile
generators (seed 004 §5.2.4-5.2.5 L3290-4050; quick reference L7574-7645). Conventions as in commands.py.
"""

from __future__ import annotations

from motiontool.apc import core
from motiontool.apc.commands import INVALID, OK, Conversions, _in
from motiontool.apc.intmath import INT32_MAX, INT32_MIN
from motiontool.apc.units import ACCEL_LIMIT, SPEED_LIMIT


class ReferenceCommands(Conversions):
    # --- reference selection, Stop, Position, Speed (L3290-3433) --------------------------------------------------
    def APCSelectReference(self, Reference: int) -> int:
        if not _in(Reference, 0, 4):
            return INVALID
        if Reference == core.CAM and self.cam.size == 0:
            self.apc_error(3, "CAM size 0 selects Stop (90.49 = 3)")      # L3514-3516
            return OK
        self.reference = Reference
        if Reference == core.CAM and self.task in ("pos0", "pos1"):
            self._cam_selected_pass = (self.samples, self.task)
        return OK

    def APCSelectActionOnFreeze(self, Action: int) -> int:
        """1 = digital lock, 2 = CAM on the next reference freeze (L1148-1150, [101] L7781; the quick
        reference's swapped codes at L7578 are a slip, spec §9.1)."""
        if not _in(Action, 0, 2):
            return INVALID
        self.action_on_freeze = Action
        return OK

    def APCSetStopMode(self, Mode: int) -> int:
        if not _in(Mode, 0, 3):
            return INVALID
        self.stop_mode = Mode
        return OK

    def APCTransferStopPosToPosSetPoint(self) -> int:
        """[91] and its remainder [178] into [92]/[172] (L3367-3376): no creep when Stop gives way to Position."""
        self.position_setpoint = self.stop_position()
        self.setpoint_rem = 0
        self.setpoint_user_rem = self._pos_out(self.position_setpoint)[1]
        return OK

    def APCSetSetPointRem(self, Remainder: int) -> int:
        """Set before the value: writing the value converts (L2211-2230)."""
        self.setpoint_user_rem = Remainder
        return OK

    def APCSetPositionSetPoint(self, Position: int) -> int:
        if not _in(Position, INT32_MIN, INT32_MAX):
            return INVALID
        self.position_setpoint, self.setpoint_rem = self._pos_in(Position, self.setpoint_user_rem)
        return OK

    def APCSetSpeedSetPoint(self, Speed: int) -> int:
        speed = self._rate_in(Speed, 1)
        if not _in(speed, -SPEED_LIMIT, SPEED_LIMIT):
            return INVALID
        self.speed_setpoint = speed
        return OK

    # --- CAM (L3435-3697) -----------------------------------------------------------------------------------
    def APCCamInitialise(self, InArray, OutArray1, OutArray2, InterpolationArray) -> int:
        self.cam.initialise(InArray, OutArray1, OutArray2, InterpolationArray)
        return OK

    def APCCamInitialise1(self, InArray, OutArray1) -> int:
        self.cam.initialise(InArray, OutArray1)
        return OK

    def APCCamInitialise2(self, InArray, OutArray1, InterpolationArray) -> int:
        self.cam.initialise(InArray, OutArray1, None, InterpolationArray)
        return OK

    def APCCamInitialise3(self, InArray, OutArray1, OutArray2) -> int:
        self.cam.initialise(InArray, OutArray1, OutArray2)
        return OK

    def APCSetCAMStartIndex(self, StartIndex: int) -> int:
        """Clamped to 0..65535 (L3500-3503); a running CAM, or one selected in the same POS task, takes it at its
        next wrap (L3505-3508)."""
        self._cam_window_written()
        self.cam.start_index = max(0, min(65535, StartIndex))
        return OK

    def APCSetCAMSize(self, Size: int) -> int:
        """As the start index (L3517-3520)."""
        self._cam_window_written()
        self.cam.size = max(0, min(65535, Size))
        if self.cam.size == 0 and self.reference == core.CAM:
            self.apc_error(3, "CAM size set to 0 while the CAM runs (90.49 = 3)")
        return OK

    def _cam_window_written(self) -> None:
        """Keep the window that held before this POS task pass, for a CAM selected in the same pass."""
        cam = self.cam
        if self.task in ("pos0", "pos1") and cam.window_pass != (self.samples, self.task):
            cam.window_pass = (self.samples, self.task)
            cam.window_before = (cam.start_index, cam.size)

    def APCSetCAMDeltaSegLimit(self, DeltaLimit: int) -> int:
        """Clamped to 0..65535 (L3525), then "Operation successful" (decision A6)."""
        self.cam.seg_limit = max(0, min(65535, DeltaLimit))
        return OK

    def APCSetCAMInterpolationMode(self, InterpolationMode: int) -> int:
        if not _in(InterpolationMode, -1, 1):
            return INVALID
        self.cam.mode = InterpolationMode
        return OK

    def APCSetCAMOutRatioNumerator(self, Ratio: int) -> int:
        """Negative values clamped at zero (L3568), then "Operation successful" (decision A6)."""
        self.cam.ratio.numerator = max(0, min(INT32_MAX, Ratio))
        return OK

    def APCSetCAMOutRatioDenominator(self, Ratio: int) -> int:
        if not _in(Ratio, 1, INT32_MAX):
            return INVALID
        self.cam.ratio.denominator = Ratio
        return OK

    def _cam_reset_settable(self) -> bool:
        """Absolute-reset settings only while CAM is not selected or the APC is disabled (L3608-3657)."""
        return self.reference != core.CAM or self.run_mode != 2

    def APCSelectCAMAbsoluteReset(self) -> int:
        self.cam.absolute_reset = True
        return OK

    def APCSelectCAMZeroReset(self) -> int:
        self.cam.absolute_reset = False
        return OK

    def APCSetCAMAbsResetIndex(self, Index: int) -> int:
        if not _in(Index, 0, 65535):
            return INVALID
        if not self._cam_reset_settable():
            return 0
        self.cam.reset_index = Index
        return OK

    def APCSetCAMAbsResetPositionInSeg(self, Position: int) -> int:
        if not _in(Position, 0, INT32_MAX):
            return INVALID
        if not self._cam_reset_settable():
            return 0
        self.cam.reset_position = Position
        return OK

    def APCEnableCAMSingleShot(self) -> int:
        """Selected while the CAM runs, the present cycle is finished (L1567-1569); re-enabled after a finished
        single shot, the CAM restarts (L1561-1565)."""
        cam = self.cam
        if not cam.single_shot and self._active == core.CAM:
            if cam.complete:
                self._active = None
            else:
                cam.finish_cycle()
        cam.single_shot = True
        return OK

    def APCDisableCAMSingleShot(self) -> int:
        self.cam.single_shot = False
        return OK

    def APCEnableCAMFreezeRearm(self) -> int:
        self.cam.rearm = True
        return OK

    def APCDisableCAMFreezeRearm(self) -> int:
        self.cam.rearm = False
        return OK

    # --- digital lock (L3699-3800) -----------------------------------------------------------------------------
    def APCSetDigLockMode(self, Mode: int) -> int:
        if not _in(Mode, 0, 2):
            return INVALID
        self.dl.mode = Mode
        return OK

    def APCSetDigLockRatioNumerator(self, Numerator: int) -> int:
        if not _in(Numerator, 0, INT32_MAX):
            return INVALID
        self.dl.ratio.numerator = Numerator
        return OK

    def APCSetDigLockRatioDenominator(self, Denominator: int) -> int:
        if not _in(Denominator, 1, INT32_MAX):
            return INVALID
        self.dl.ratio.denominator = Denominator
        return OK

    def APCSetDigLockLockingSpeed(self, Speed: int) -> int:
        speed = self._rate_in(Speed, 1)
        if not _in(speed, 0, INT32_MAX):
            return INVALID
        self.dl.lock_speed = speed
        return OK

    def APCSetDigLockLockingPosition(self, Position: int) -> int:
        position = self._pos_in(Position)[0]
        if not _in(position, 0, INT32_MAX):
            return INVALID
        self.dl.lock_position = position
        return OK

    def APCEnableRigidLock(self) -> int:
        """Mid-acquisition, rigid lock aims at the relative position of this moment (L1818-1821)."""
        if not self.dl.rigid and self._active == core.DIG_LOCK and self.dl.mode != 1:
            self.dl.rebase(self.pg.position)
        self.dl.rigid = True
        return OK

    def APCDisableRigidLock(self) -> int:
        self.dl.rigid = False
        return OK

    # --- main profile generator (L3803-3890) ------------------------------------------------------------------
    def _pg_set(self, pg, attr: str, value: int, hi: int) -> int:
        if not _in(value, 0, hi):
            return INVALID
        pg.set_limit(attr, value)
        return OK

    def APCEnableProfile(self) -> int:
        self.pg.disabled = False
        return OK

    def APCDisableProfile(self) -> int:
        self.pg.disabled = True
        return OK

    def APCSetProfileAccelRate(self, AccelRate: int) -> int:
        return self._pg_set(self.pg, "accel", self._rate_in(AccelRate, 2), ACCEL_LIMIT)

    def APCSetProfileDecelRate(self, DecelRate: int) -> int:
        return self._pg_set(self.pg, "decel", self._rate_in(DecelRate, 2), ACCEL_LIMIT)

    def APCSetProfileJerk(self, Jerk: int) -> int:
        return self._pg_set(self.pg, "jerk", self._rate_in(Jerk, 3), ACCEL_LIMIT)

    def APCSetProfileMaxSpeedClamp(self, MaxSpeed: int) -> int:
        return self._pg_set(self.pg, "max_speed", self._rate_in(MaxSpeed, 1), SPEED_LIMIT)

    # --- offset profile generator (L3903-4050) ----------------------------------------------------------------
    def APCEnableOffsetProfile(self) -> int:
        self.opg.disabled = False
        return OK

    def APCDisableOffsetProfile(self) -> int:
        self.opg.disabled = True
        return OK

    def APCSelectOffset(self, OffSelect: int) -> int:
        """0 none, 1 position [93], 2 speed [95]; forced to 0 while Stop is selected (L3930-3944)."""
        if not _in(OffSelect, 0, 2):
            return INVALID
        if self.reference == core.STOP:
            OffSelect = 0
        self._set_offsets(OffSelect)
        return OK

    def APCSetOffsetRem(self, Remainder: int) -> int:
        self.offset_user_rem = Remainder
        return OK

    def APCSetPositionOffset(self, Position: int) -> int:
        if not _in(Position, INT32_MIN, INT32_MAX):
            return INVALID
        self.position_offset, self.offset_rem = self._pos_in(Position, self.offset_user_rem)
        return OK

    def APCSetSpeedOffset(self, Speed: int) -> int:
        speed = self._rate_in(Speed, 1)
        if not _in(speed, -SPEED_LIMIT, SPEED_LIMIT):
            return INVALID
        self.speed_offset = speed
        return OK

    def APCSetOffProfileAccelRate(self, AccelRate: int) -> int:
        return self._pg_set(self.opg, "accel", self._rate_in(AccelRate, 2), ACCEL_LIMIT)

    def APCSetOffProfileDecelRate(self, DecelRate: int) -> int:
        return self._pg_set(self.opg, "decel", self._rate_in(DecelRate, 2), ACCEL_LIMIT)

    def APCSetOffProfileJerk(self, Jerk: int) -> int:
        return self._pg_set(self.opg, "jerk", self._rate_in(Jerk, 3), ACCEL_LIMIT)

    def APCSetOffProfileMaxSpeedClamp(self, MaxSpeed: int) -> int:
        return self._pg_set(self.opg, "max_speed", self._rate_in(MaxSpeed, 1), SPEED_LIMIT)
