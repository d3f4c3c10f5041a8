"""The APC read parameters `[n]` (seed 004 §11.2 L7701-7875, aliases §11.5.9 L8038-8199): number, alias,
description and unit kind. The values live in the kernel's state and are read on demand
(`ApcDrive.APCReadPar`), so nothing here costs time in the POS tick.

Unit kinds: ``pos`` (counts or user units, with a remainder), ``speed``, ``accel``, ``jerk`` (converted in
user-unit mode), ``counts`` (always raw: [31] [51] [170]–[176] [178] [180]–[184], L2207-2209, and the CAM's own
counters, L2199), ``none`` (flags, modes, ratios).

The alias list of the manual gives APC_OFF_ACCEL and APC_OFF_DECEL twice: to the offset ramp rates [150]/[151]
(L8145) and to the offset accelerating/decelerating flags [164]/[165] (L8159-8160). The aliases name the rates
here and the flags have none (docs/decisions.md A12). [112] and [152] (jerks) have no alias in the manual.
"""

from __future__ import annotations

from dataclasses import dataclass

RAW_OFFSET = 1000   # [n + 1000] reads the raw APC value in user-unit mode (L2203-2205)


@dataclass(frozen=True)
class ReadParameter:
    number: int
    alias: str
    description: str
    kind: str = "none"


def _table(rows) -> dict[int, ReadParameter]:
    return {n: ReadParameter(n, alias, text, kind) for n, alias, text, kind in rows}


READ_PARAMETERS: dict[int, ReadParameter] = _table([
    (0, "APC_POS_CTRL_EN", "Position controller enable (requested)", "none"),
    (1, "APC_ABS_MODE", "Absolute position reset mode select", "none"),
    (2, "APC_POS_RST_OFF", "Feedback position offset applied during APC reset", "pos"),
    (3, "APC_SRC_RST_DIS", "Reset the sources on position control disable", "none"),
    (4, "APC_ENABLE_STATUS", "APC enable status (set at the end of the kernel)", "none"),
    (5, "APC_RESET_STATUS", "APC reset status (falling edge = reset complete)", "none"),
    (6, "APC_REF_POS_RST_OFF", "Reference position offset applied during APC reset", "pos"),
    (13, "APC_SAMPLE_TIME", "POS task sample time (0: 0.25 … 5: 8 ms)", "none"),
    (14, "APC_NO_TURN_BITS", "Number of turns bits", "none"),
    (15, "APC_VERSION_NUM", "Version number of the position controller", "none"),
    (20, "APC_RFSRC_POS", "Reference source position", "pos"),
    (21, "APC_RFSRC_FRZPOS", "Reference source freeze position", "pos"),
    (22, "APC_RFSRC_FRZFLG", "Reference source freeze flag", "none"),
    (23, "APC_RFSRC_MRKPOS", "Reference source marker position", "pos"),
    (24, "APC_RFSRC_MRKFLG", "Reference source marker flag", "none"),
    (25, "APC_RFSRC_MRKACT", "Reference source is affected by marker (marker reset)", "none"),
    (26, "APC_RFSRC_SPD", "Reference source speed", "speed"),
    (27, "APC_RFSRC_INV", "Reference source invert", "none"),
    (28, "APC_RF_POS", "Integrated reference position", "pos"),
    (29, "APC_RF_FRZPOS", "Integrated reference position on freeze", "pos"),
    (30, "APC_RF_MRKPOS", "Integrated reference position on marker", "pos"),
    (31, "APC_REF_IN", "Reference input", "counts"),
    (32, "APC_REF_IN_DIS", "Reference input disable", "none"),
    (40, "APC_FBSRC_POS", "Feedback source position", "pos"),
    (41, "APC_FBSRC_FRZPOS", "Feedback source freeze position", "pos"),
    (42, "APC_FBSRC_FRZFLG", "Feedback source freeze flag", "none"),
    (43, "APC_FBSRC_MRKPOS", "Feedback source marker position", "pos"),
    (44, "APC_FBSRC_MRKFLG", "Feedback source marker flag", "none"),
    (45, "APC_FBSRC_MRKACT", "Feedback source is affected by marker (marker reset)", "none"),
    (46, "APC_FBSRC_SPD", "Feedback source speed", "speed"),
    (47, "APC_FBSRC_INV", "Feedback source invert", "none"),
    (48, "APC_FB_POS", "Integrated feedback position", "pos"),
    (49, "APC_FB_FRZPOS", "Integrated feedback position on freeze", "pos"),
    (50, "APC_FB_MRKPOS", "Integrated feedback position on marker", "pos"),
    (51, "APC_FBCK_IN", "Feedback input", "counts"),
    (52, "APC_FBCK_IN_DIS", "Feedback input disable", "none"),
    (60, "APC_RIGID_LOCK", "Rigid digital lock select", "none"),
    (61, "APC_DIGLCK_MODE", "Digital lock mode (0 unlocked, 1 locked, 2 never lock)", "none"),
    (62, "APC_DIGLCK_NUM", "Digital lock ratio numerator", "none"),
    (63, "APC_DIGLCK_DEN", "Digital lock ratio denominator", "none"),
    (64, "APC_DIGLCK_SPD", "Digital lock locking speed", "speed"),
    (65, "APC_DIGLCK_POS", "Digital lock locking position", "pos"),
    (74, "APC_CAM_STRT_IDX", "Start index of active CAM", "none"),
    (75, "APC_CAM_SIZE", "Number of index values used by the active CAM", "none"),
    (76, "APC_CAM_SEG_LIM", "Maximum change of segments allowed per sample", "none"),
    (77, "APC_CAM_INT_MODE", "CAM interpolation type (-1 array, 0 linear, 1 cosine)", "none"),
    (78, "APC_CAM_SGL_SHOT", "CAM single shot mode select", "none"),
    (79, "APC_CAM_ABS_RST", "CAM absolute reset mode", "none"),
    (80, "APC_CAM_OUT_NUM", "CAM output ratio numerator", "none"),
    (81, "APC_CAM_OUT_DEN", "CAM output ratio denominator", "none"),
    (82, "APC_CAM_INDEX", "Current segment of active CAM", "none"),
    (83, "APC_CAM_POS_SEG", "Delta input position from start of current segment", "counts"),
    (84, "APC_CAM_ARR_SIZE", "Size of CAM arrays", "none"),
    (85, "APC_CAM_RST_IDX", "CAM absolute mode index reset value", "none"),
    (86, "APC_CAM_RST_POS", "CAM absolute mode position in segment reset value", "counts"),
    (87, "APC_CAM_SS_COMPLETE", "The CAM has completed a single shot cycle", "none"),
    (88, "APC_CAM_SS_FRZ_REARM", "Single shot freeze re-arm selected", "none"),
    (89, "APC_CAM_WRAP_THIS_CYCLE", "The CAM has wrapped this sample", "none"),
    (90, "APC_STOP_MODE", "Stopping mode", "none"),
    (91, "APC_STOP_POS", "Position the axis will stop at when Stop is selected", "pos"),
    (92, "APC_POS_SETPOINT", "Position set point", "pos"),
    (93, "APC_POS_OFFSET", "Position offset", "pos"),
    (94, "APC_SPD_SETPOINT", "Speed set point", "speed"),
    (95, "APC_SPEED_OFFSET", "Speed offset", "speed"),
    (96, "APC_USER_CONV_N", "APC internal converter numerator", "none"),
    (97, "APC_USER_CONV_D", "APC internal converter denominator", "none"),
    (100, "APC_REF_SELECT", "Currently selected reference", "none"),
    (101, "APC_ACT_ON_FRZ", "Action on freeze (0 none, 1 digital lock, 2 CAM)", "none"),
    (102, "APC_OFF_SELECT", "Offset selector", "none"),
    (110, "APC_ACCEL_RAMP", "Profile acceleration rate", "accel"),
    (111, "APC_DECEL_RAMP", "Profile deceleration rate", "accel"),
    (112, "", "Profile jerk", "jerk"),
    (113, "APC_PRF_MAX_SPD", "Profile maximum speed", "speed"),
    (114, "APC_PROF_DISABLE", "Profile disable", "none"),
    (115, "APC_PROF_IN_POS", "Profile input position", "pos"),
    (116, "APC_PROF_IN_SPD", "Profile input speed", "speed"),
    (117, "APC_PROF_OUT_POS", "Profile output position", "pos"),
    (118, "APC_PROF_OUT_SPD", "Profile output speed", "speed"),
    (119, "APC_PROF_OUT_ACC", "Profile output acceleration", "accel"),
    (120, "APC_AT_POS", "At target position flag", "none"),
    (121, "APC_AT_SPD", "At target speed flag", "none"),
    (122, "APC_POS_JERK", "Positive jerk flag", "none"),
    (123, "APC_NEG_JERK", "Negative jerk flag", "none"),
    (124, "APC_ACCEL", "Accelerating flag", "none"),
    (125, "APC_DECEL", "Decelerating flag", "none"),
    (126, "APC_CONST_POSITION_SPD_POS", "Constant positive positioning speed flag", "none"),
    (127, "APC_CONST_POSITION_SPD_NEG", "Constant negative positioning speed flag", "none"),
    (128, "APC_CROSS_0_SPD", "Crossed 0 speed this sample flag", "none"),
    (129, "APC_MAIN_PROFILING", "Main profile generator profiling flag", "none"),
    (130, "APC_POS_ERROR", "Position error", "pos"),
    (131, "APC_KV", "Position controller proportional gain", "none"),
    (132, "APC_PGAIN_CLAMP", "P gain maximum speed", "speed"),
    (133, "APC_OUTPUT_NUM", "Position controller output ratio numerator", "none"),
    (134, "APC_OUTPUT_DEN", "Position controller output ratio denominator", "none"),
    (135, "APC_OUTPUT_SPEED", "Position controller output speed", "speed"),
    (136, "APC_EXTREFPOSSEL", "External position reference select", "none"),
    (137, "APC_EXT_REF_POS", "External reference position", "pos"),
    (138, "APC_EXTREFSPDSEL", "External speed reference select", "none"),
    (139, "APC_EXT_REF_SPD", "External speed reference", "speed"),
    (140, "APC_OUTSPD_CLAMP", "Output speed clamp", "speed"),
    (141, "APC_SPD_FF_CLAMP", "Speed feed forward gain", "none"),
    (142, "APC_TOT_POS_REF", "Final position reference after the external selector", "pos"),
    (143, "APC_TOT_SPD_REF", "Final speed reference after the external selector", "speed"),
    (144, "APC_TOT_PROF_POS_REF", "Total profile position reference [117]+[157]", "pos"),
    (145, "APC_TOT_PROF_ACCEL_REF", "Total acceleration output [119]+[159]", "accel"),
    (150, "APC_OFF_ACCEL", "Offset profile acceleration rate", "accel"),
    (151, "APC_OFF_DECEL", "Offset profile deceleration rate", "accel"),
    (152, "", "Offset profile jerk", "jerk"),
    (153, "APC_OFF_S_CLAMP", "Offset profile max speed clamp", "speed"),
    (154, "APC_OFF_PROF_DISABLE", "Offset profile disabled", "none"),
    (155, "APC_OFF_IN_POS", "Offset profile input position", "pos"),
    (156, "APC_OFF_IN_SPD", "Offset profile input speed", "speed"),
    (157, "APC_OFF_OUT_POS", "Offset profile output position", "pos"),
    (158, "APC_OFF_OUT_SPD", "Offset profile output speed", "speed"),
    (159, "APC_OFF_OUT_ACC", "Offset profile output acceleration", "accel"),
    (160, "APC_OFF_AT_POS", "At offset target position", "none"),
    (161, "APC_OFF_AT_SPD", "At offset target speed", "none"),
    (162, "APC_OFF_POS_JERK", "Offset positive jerk flag", "none"),
    (163, "APC_OFF_NEG_JERK", "Offset negative jerk flag", "none"),
    (164, "", "Offset accelerating flag", "none"),
    (165, "", "Offset decelerating flag", "none"),
    (166, "APC_OFF_CONST_POSITION_SPD_POS", "Offset constant positive positioning speed flag", "none"),
    (167, "APC_OFF_CONST_POSITION_SPD_NEG", "Offset constant negative positioning speed flag", "none"),
    (168, "APC_OFF_CROSS_0_SPD", "Offset crossed 0 speed this sample flag", "none"),
    (169, "APC_OFF_PROFILING", "Offset profile generator profiling flag", "none"),
    (170, "APC_INT_POS_SETPOINT", "Internal position set point (counts)", "counts"),
    (171, "APC_INT_POS_SETPOINT_REM", "Internal position set point remainder", "counts"),
    (172, "APC_POS_SETPOINT_REM", "Position set point remainder", "counts"),
    (173, "APC_OFF_INT_POS_SETPOINT", "Internal offset position set point (counts)", "counts"),
    (174, "APC_OFF_INT_POS_SETPOINT_REM", "Internal offset position remainder", "counts"),
    (175, "APC_OFF_POS_SETPOINT_REM", "Offset position remainder", "counts"),
    (176, "APC_INT_STOP_POS", "Internal stop position (counts)", "counts"),
    (178, "APC_STOP_REM", "Stop position remainder", "counts"),
    (180, "APC_INT_PROF_IN_POS", "Internal profile input position", "counts"),
    (181, "APC_INT_PROF_OUT_POS", "Internal profile output position", "counts"),
    (182, "APC_OFF_INT_PROF_IN_POS", "Internal offset profile input position", "counts"),
    (183, "APC_OFF_INT_PROF_OUT_POS", "Internal offset profile output position", "counts"),
    (184, "APC_OFF_INT_OUT_POS", "Internal final profile position", "counts"),
    (185, "APC_TOT_INT_PROF_OUT_POS", "Internal total profile position reference", "counts"),
    (186, "APC_COMBINED_PROF_FLAGS", "Combined profile flags (main bits 0-9, offset bits 16-25)", "none"),
    (187, "APC_PROF_OUT_JERK", "Main profile output jerk", "jerk"),
    (189, "APC_OFF_PROF_OUT_JERK", "Offset profile output jerk", "jerk"),
])

BY_ALIAS: dict[str, int] = {p.alias: p.number for p in READ_PARAMETERS.values() if p.alias}


def parameter_number(key: int | str) -> int:
    """A read-parameter number from 48, "48", "[48]", "1048" (raw), or an alias ("APC_FB_POS", any case).
    ValueError names the key when it is none of these."""
    if isinstance(key, bool):
        raise ValueError(f"no APC read parameter {key!r}")
    if isinstance(key, int):
        number = key
    else:
        text = str(key).strip()
        inner = text[1:-1].strip() if text.startswith("[") and text.endswith("]") else text
        if inner.lstrip("-").isdigit():
            number = int(inner)
        elif inner.upper() in BY_ALIAS:
            number = BY_ALIAS[inner.upper()]
        else:
            raise ValueError(f"no APC read parameter {key!r} (give a number such as 48 or an alias such as "
                             f"APC_FB_POS)")
    base = number - RAW_OFFSET if number >= RAW_OFFSET else number
    if base not in READ_PARAMETERS:
        raise ValueError(f"no APC read parameter [{number}]")
    return number
