"""What a controller can record (the `list_signals` operation): the names the scope's Add Curve offers in its
signal browser, each with its group and a line of text. Every name is one `stream`, `read_signals` and the
Single Shot recording take (docs/link-protocol.md "Signals")."""

from __future__ import annotations

from motiontool.apc.readpars import READ_PARAMETERS
from motiontool.kernel.objdict import SIGNALS
from motiontool.kernel.sysvars import AXIS_BASE, AXIS_PROCESS_DATA
from motiontool.paramdb import database

# the axis signals of kernel/objdict.py SIGNALS, in words (CR: APOS, CPOS, AVEL …; DG 5227-5236)
MCO_SIGNAL_TEXT = {
    "APOS": "actual position (UU)", "CPOS": "command position (UU)", "TRACKERR": "tracking error (UU)",
    "AVEL": "actual velocity (UU/s)", "CVEL": "command velocity (UU/s)", "AXEND": "axis status bits (AXEND)",
    "STAT": "controller status bits (STAT)", "ERRNO": "pending error number", "SPEEDREF": "speed reference (‰)",
    "INPUTS": "digital inputs as a word", "OUTPUTS": "digital outputs as a word",
    "MAPOS": "master position (master qc)", "MAVEL": "master velocity (master qc/s)",
}


def mco_signals() -> list[dict]:
    signals = [{"name": name, "group": "Axis", "text": MCO_SIGNAL_TEXT.get(name, name)} for name in SIGNALS]
    signals += [{"name": str(AXIS_BASE + n), "group": "Process data (SYSVAR)", "text": f"{name} ({unit})" if unit
                 else name} for n, (name, unit, _read) in sorted(AXIS_PROCESS_DATA.items())]
    signals += [{"name": p.name or p.number, "group": "Parameters", "text": f"{p.number} {p.description}"}
                for p in database()]
    return signals


def apc_signals() -> list[dict]:
    """The APC's read parameters by alias (or [n]), as the APC scope takes them (docs/apc.md "Link")."""
    return [{"name": p.alias or f"[{p.number}]", "group": "APC read parameters",
             "text": f"[{p.number}] {p.description}"} for p in READ_PARAMETERS.values()]
