"""The `[fc300]` section of a configuration file (format 3): the FC 300 drive's parameters that differ from their
defaults, so that one file holds the drive's and the option's settings as MCT 10 keeps them side by side (issue 25
item 2, decision C19; docs/formats/zbc.md).  Qt-free.

A line is `4-13 = 1800`: the LCP number and the value as it crosses the link, GETVLT's integer scaled by the
conversion index (`1-24 = 820` is 8.20 A; docs/fc300.md).  Integers keep the round trip exact.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from motiontool.comms.protocol import LinkError
from motiontool.kernel.fc300_table import FC_PARAMETERS, FCParam

DRIVE_FORMAT = 3
SECTION = "fc300"
_KEY_RE = re.compile(r"([0-9]{1,2})-([0-9]{2})")
_INT_RE = re.compile(r"[-+]?[0-9]{1,10}")


def savable() -> list[FCParam]:
    """The settings a file holds: every parameter but the readouts (16-**, DG 7594: read only)."""
    return [p for p in FC_PARAMETERS.values() if not p.read_only]


def _parameter(key: str) -> FCParam:
    m = _KEY_RE.fullmatch(key.strip())
    p = FC_PARAMETERS.get(int(m[1]) * 100 + int(m[2])) if m else None
    if p is None:
        raise ValueError(f"unknown FC 300 parameter {key.strip()!r} (the simulated drive's list: docs/fc300.md)")
    if p.read_only:
        raise ValueError(f"{p.label} {p.name}: read-only readout, not a setting")
    return p


def checked(key: str, value: int) -> tuple[str, int]:
    """(label, value) for a setting; ValueError names the parameter.  The range checked is the table's own; an end
    that is another parameter (4-13 from 4-11) is the drive's to check when the file is restored."""
    p = _parameter(key)
    if isinstance(value, bool) or not isinstance(value, int) or not p.low <= value <= p.high:
        raise ValueError(f"{p.label} {p.name}: {value!r} is outside {p.low}..{p.high}")
    return p.label, value


def read_line(drive: dict[str, int], key: str, value: str, line: int, lines: dict[str, int],
              error: Callable[[str, int], Exception]) -> None:
    """One `[fc300]` line into `drive`; `error(message, line)` for a bad one."""
    text = value.strip()
    if not _INT_RE.fullmatch(text):
        raise error(f"FC 300 parameter {key.strip()}: {text!r} is not an integer (the value as it crosses the "
                    "link)", line)
    try:
        label, number = checked(key, int(text))
    except ValueError as exc:
        raise error(str(exc), line) from None
    if label in drive:
        raise error(f"{label} given twice (first on line {lines[label]})", line)
    drive[label], lines[label] = number, line


def section_lines(drive: dict[str, int]) -> list[str]:
    """The section's lines, sorted by parameter number; ValueError for a value that cannot be saved."""
    rows = sorted(checked(key, value) for key, value in drive.items())
    rows.sort(key=lambda row: _parameter(row[0]).number)
    return [f"[{SECTION}]", *(f"{label} = {value}" for label, value in rows), ""]


def write_settings(link, values: dict[str, int]) -> None:
    """Write drive settings over `link` (Restore from file, the Drive dialog's OK).  A range may end at another
    parameter (4-13 from 4-11 up, docs/fc300.md), so a value the drive refuses now is tried again after the others
    moved its bounds; what no order makes fit raises LinkError naming the parameter."""
    left = dict(values)
    while left:
        refused: dict[str, LinkError] = {}
        for label, value in left.items():
            try:
                link.write_parameter(label, value)
            except LinkError as exc:
                refused[label] = exc
        if len(refused) == len(left):
            label, first = next(iter(refused.items()))
            raise LinkError(f"FC 300 parameter {label}: the controller refused {left[label]}: {first}", first.number)
        left = {label: left[label] for label in refused}
