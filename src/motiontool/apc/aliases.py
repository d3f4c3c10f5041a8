"""The APC definitions (seed 004 §11.5, L7942-8199): aliases for command values and read-parameter numbers.

A DPL program may write either the number or the alias. The read-parameter aliases live with the
read-parameter table (`readpars.py`); this module holds the value aliases and merges both into ALIASES.
"""

from __future__ import annotations

from motiontool.apc.readpars import READ_PARAMETERS

VALUE_ALIASES: dict[str, int] = {
    # 11.5.1 run modes (L7946-7951)
    "APC_OFF": 0, "APC_DISABLE": 1, "APC_ENABLE": 2,
    # 11.5.2 sources (L7953-7962); 5 (unconfigured) has no alias in the manual
    "APC_DRIVE_ENC": 0, "APC_SLOT1_ENC": 1, "APC_SLOT2_ENC": 2, "APC_SLOT3_ENC": 3, "APC_USER_ENC": 4,
    # 11.5.3 references (L7964-7984)
    "APC_LINEAR_CAM": 0, "APC_COSINE_CAM": 1, "APC_ARRAY_CAM": -1,
    "APC_UNLOCKED": 0, "APC_LOCKED": 1, "APC_NEVER_LOCK": 2,
    "APC_PROF_STOP": 0, "APC_FAST_STOP": 1,
    "APC_STOP_REF": 0, "APC_POSITION_REF": 1, "APC_SPEED_REF": 2, "APC_CAM_REF": 3, "APC_DIG_LOCK_REF": 4,
    "APC_NO_ACT_FRZ": 0, "APC_DIG_LOCK_FRZ": 1, "APC_CAM_ON_FRZ": 2,
    # 11.5.4 offset selector (L7986-7991)
    "APC_OFF_DISABLED": 0, "APC_OFF_POS": 1, "APC_OFF_SPD": 2,
    # 11.5.5 output channel modes (L7993-8004). APC_SPEED_REF is printed twice with two values: 2 here for
    # the output channel, 2 above for APCSelectReference — the same number, so no conflict.
    "APC_HARD_SPD_REF": 0, "APC_PARAMETER": 3, "APC_USER_REF": 4, "APC_QUIET": 5,
    "APC_HARD_SPD_REF_I": 10, "APC_SPEED_REF_I": 12, "APC_PARAMETER_I": 13, "APC_USER_REF_I": 14,
    # 11.5.6 status (L8005-8013)
    "APC_FAIL": 0, "APC_OK": 1, "APC_ACCESS_DENY": -3, "APC_INVALID_ARGU": -4,
    # 11.5.7 output channel status (L8015-8026)
    "CHAN_SUCCESS": 1, "CHAN_NOT_SET": 0, "CHAN_INVALID": -1, "CHAN_NOT_MAST": -2, "CHAN_ACCESS_DENY": -3,
    "CHAN_INVALID_PAR": -4, "CHAN_INVALID_OP": -5,
    # 11.5.8 CTSync user status (L8028-8036)
    "USR_VALUE_OK": 1, "USR_VAL_UNCONFD": 0, "USR_INVALID_CHAN": -1, "USR_NOT_MASTER": -2,
    "USR_ACCESS_DENY": -3, "USR_PAR_INVALID": -4, "USR_INVALID": -5,
}

# Read-parameter aliases (11.5.9, L8038-8199) come from the read-parameter table.
PARAMETER_ALIASES: dict[str, int] = {p.alias: p.number for p in READ_PARAMETERS.values() if p.alias}

ALIASES: dict[str, int] = {**PARAMETER_ALIASES, **VALUE_ALIASES}

APC_OK = 1
APC_FAIL = 0
APC_ACCESS_DENY = -3
APC_INVALID_ARGU = -4
