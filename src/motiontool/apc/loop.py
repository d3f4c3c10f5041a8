"""The position loop and the output channel (seed 004 §4.9 L1855-2056, §4.11 L2103-2151, §5.2.6 L4052-4316).

Structure (the figures are lost; rebuilt from the text, spec §1.15, **inferred** order):

    error [130]   = [142] − [48]
    P path        = clamp(Kp·error, ±[132])                     Kp in 0.01 (rad/s)/rad (L744)
    FF path       = [143]·[141]/1000                            speed feed-forward gain (L4189-4199)
    output [135]  = clamp((FF + P)·[133]/[134], ±[140])          ratio before the clamp (L4201-4206)

The output channel latches [135] (or a user value) after POS1 and writes it at the start of the next sample;
the drive takes it 250 µs later, a fixed, jitter-free delay of one POS period plus 250 µs (L2103-2120).
"""

from __future__ import annotations

from motiontool.apc.intmath import wrap32
from motiontool.apc.units import speed_to_rpm_x10

# output channel modes (L4253-4316, aliases L7993-8004); 1 and 11 are not allocated
HARD_SPEED, SPEED_REF, PARAMETER, USER_REF, QUIET = 0, 2, 3, 4, 5
VALID_MODES = (0, 2, 3, 4, 5, 10, 12, 13, 14)


class PositionLoop:
    def __init__(self) -> None:
        self.kp = 2500                   # [131]
        self.p_clamp = 5368709           # [132] ≈ 300 rpm
        self.ratio_num = 1000            # [133]
        self.ratio_den = 1000            # [134]
        self.output_clamp = 53687091     # [140] ≈ 3000 rpm
        self.ff_gain = 1000              # [141]
        self.ext_pos_selected = False    # [136]
        self.ext_position = 0            # [137]
        self.ext_speed_selected = False  # [138]
        self.ext_speed = 0               # [139]
        self.position_ref = 0            # [142]
        self.speed_ref = 0               # [143]
        self.error = 0                   # [130]
        self.output = 0                  # [135]

    def run(self, profile_position: int, profile_speed: int, feedback: int, turns_bits: int) -> int:
        """One sample of the loop from the total profile references ([144], speed) and the feedback [48].
        Integer divisions truncate toward zero (decision A47)."""
        ref = self.position_ref = self.ext_position if self.ext_pos_selected else profile_position
        speed = self.speed_ref = self.ext_speed if self.ext_speed_selected else profile_speed
        error = ref - feedback
        if (error + 0x80000000) >> 32:      # outside int32
            error = wrap32(error)
        self.error = error
        if error:
            p = self.kp * error << turns_bits
            p = p // 400000 if p >= 0 else -(-p // 400000)
            clamp = self.p_clamp
            if p > clamp:
                p = clamp
            elif p < -clamp:
                p = -clamp
        else:
            p = 0
        gain = self.ff_gain
        if gain != 1000:
            speed *= gain
            speed = speed // 1000 if speed >= 0 else -(-speed // 1000)
        out = speed + p
        num, den = self.ratio_num, self.ratio_den
        if num != den:
            out *= num
            out = out // den if out >= 0 else -(-out // den)
        clamp = self.output_clamp
        if out > clamp:
            out = clamp
        elif out < -clamp:
            out = -clamp
        self.output = out
        return out

    def idle(self, profile_position: int, feedback: int) -> None:
        """Disabled: only the following error is updated (L779-785); no output."""
        self.position_ref = self.ext_position if self.ext_pos_selected else profile_position
        self.error = wrap32(self.position_ref - feedback)
        self.speed_ref = self.output = 0


class OutputChannel:
    """APCSetupOutputChannel / Enable / Disable / WriteOutputChannel (L4253-4316). Disabled and in mode 5 by
    default. `latch` is called after POS1 and returns what the drive receives: (parameter, value) writes."""

    def __init__(self) -> None:
        self.mode = QUIET
        self.menu = 0
        self.parameter = 0
        self.enabled = False
        self.user_value = 0
        self.sent = 0               # the last speed written in mode 2 (#1.21 reads it as rpm×10)

    def setup(self, mode: int, menu: int, parameter: int) -> bool:
        if mode not in VALID_MODES:
            return False
        self.mode, self.menu, self.parameter = mode, menu, parameter
        return True

    def latch(self, output_speed: int) -> tuple[int | None, tuple[int, int] | None, int]:
        """(speed for the drive's speed shortcut in APC units or None, (menu, par) or None, value to write).
        Modes 10-14 invert (L2136-2145; mode 10 read as inverted mode 0, spec §9.6)."""
        if not self.enabled or self.mode == QUIET:
            return None, None, 0
        base, sign = (self.mode - 10, -1) if self.mode >= 10 else (self.mode, 1)
        speed = sign * output_speed
        if base == HARD_SPEED:
            return speed, (3, 22), speed_to_rpm_x10(speed)
        if base == SPEED_REF:
            return speed, (1, 21), speed_to_rpm_x10(speed)
        if base == PARAMETER:
            return None, (self.menu, self.parameter), speed_to_rpm_x10(speed)
        return None, (self.menu, self.parameter), wrap32(sign * self.user_value)
