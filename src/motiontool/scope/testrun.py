"""Old Testrun .txt files (DG 5357-5376, ide-spec 6.55, 7.8).

The old layout is not in the manual (ide-spec 7.8 OPEN). Decision, documented in docs/formats/zbo.md: a file
is recognised when its first non-blank line starts with "Testrun" or "APOSS Testrun"; then come
"key: value" (or "key = value") test parameters, one header line naming the columns, and rows of numbers
separated by tabs, semicolons, commas or spaces. A first column named Time/t/ms (any case) is the time in
ms; otherwise the time is the row number × the "Interval" (or "Sample time") parameter, default 1 ms.
An unrecognised file raises NotTestrun, and the caller opens it as text instead.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from motiontool.fileio import MiB, read_bytes
from motiontool.scope.curves import Curve, Scope, Source

SIGNATURE = re.compile(r"^\s*(aposs\s+)?test\s*run\b", re.IGNORECASE)
TIME_NAMES = {"time", "t", "ms", "time[ms]", "time (ms)", "time_ms"}
MAX_ROWS = 10_000_000
MAX_BYTES = 512 * MiB  # decisions R4


class NotTestrun(ValueError):
    """The file is not an old Testrun file (open it as text)."""


class BadTestrunFile(ValueError):
    """A recognised Testrun file with a defect; the message names file:line."""


def _split(line: str) -> list[str]:
    for sep in ("\t", ";", ","):
        if sep in line:
            return [p.strip() for p in line.split(sep)]
    return line.split()


_DECIMAL = re.compile(r"[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?")  # ASCII digits only (not \d)


def _number(text: str) -> float:
    if not _DECIMAL.fullmatch(text.strip()):
        raise ValueError(text)
    value = float(text)
    if math.isnan(value) or math.isinf(value):
        raise ValueError(text)
    return value


def parse_testrun(text: str, name: str = "<testrun>") -> Scope:
    lines = text.splitlines()
    first = next((i for i, line in enumerate(lines) if line.strip()), None)
    if first is None or not SIGNATURE.match(lines[first]):
        raise NotTestrun(f"{name}: not an old Testrun file (no 'Testrun' title line)")
    params: dict[str, str] = {}
    header: list[str] | None = None
    header_line = 0
    rows: list[list[float]] = []
    for number, line in enumerate(lines[first + 1:], start=first + 2):
        stripped = line.strip()
        if not stripped or stripped.startswith(("#", "//")):
            continue
        if header is None:
            m = re.match(r"^([A-Za-z][\w .()/-]*?)\s*[:=]\s*(.*)$", stripped)
            if m and not re.search(r"[\t;,]", m.group(1)):
                params[m.group(1).strip()] = m.group(2).strip()
                continue
            header, header_line = _split(stripped), number
            if len(header) < 1 or any(not h for h in header):
                raise BadTestrunFile(f"{name}:{number}: a column header is empty")
            continue
        cells = _split(stripped)
        if len(cells) != len(header):
            raise BadTestrunFile(f"{name}:{number}: {len(cells)} values, the header (line {header_line}) names "
                               f"{len(header)} columns")
        try:
            rows.append([_number(c) for c in cells])
        except ValueError:
            bad = next(c for c in cells if not _is_number(c))
            raise BadTestrunFile(f"{name}:{number}: '{bad}' is not a number") from None
        if len(rows) > MAX_ROWS:
            raise BadTestrunFile(f"{name}:{number}: more than {MAX_ROWS} rows")
    if header is None:
        raise BadTestrunFile(f"{name}: no column header line")
    data = np.array(rows, dtype=float).reshape(len(rows), len(header))
    if header[0].strip().lower() in TIME_NAMES:
        t, columns, data = data[:, 0], header[1:], data[:, 1:]
        if t.size > 1 and np.any(np.diff(t) < 0):
            row = int(np.nonzero(np.diff(t) < 0)[0][0]) + 1
            raise BadTestrunFile(f"{name}: time goes backwards at data row {row + 1}")
    else:
        interval = params.get("Interval", params.get("Sample time", "1"))
        try:
            step = _number(interval.split()[0]) if interval.split() else 1.0
        except ValueError:
            raise BadTestrunFile(f"{name}: Interval '{interval}' is not a number of ms") from None
        t, columns = np.arange(len(rows), dtype=float) * step, header
    scope = Scope("testsetp")
    for j, column in enumerate(columns):
        curve = Curve(column, Source(method="file", signal=column, controller=None,
                                     info={"testrun": Path(name).name, **params}), first_of_set=j == 0)
        curve.buffer.set_capacity(max(t.size, 1))
        curve.buffer.extend(t, data[:, j])
        scope.add_curve(curve)
    return scope


def _is_number(text: str) -> bool:
    try:
        _number(text)
        return True
    except ValueError:
        return False


def read_testrun(path: Path | str) -> Scope:
    path = Path(path)
    data = read_bytes(path, MAX_BYTES, "Testrun file")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("latin-1")  # old Windows files
    return parse_testrun(text, str(path))
