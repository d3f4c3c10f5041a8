"""Measured traces for the CAM editor's overlay (issue 6 item 5, decision C14), Qt-free.

Two CSV layouts are read:

* ``motiontool run --trace OUT.csv --signals ...`` (motiontool.headless): a header ``time_ms,SIG1,SIG2,...`` and
  one row of numbers per sample, every column on the same time base;
* the oscilloscope's CSV export (motiontool.scope.export, DG 5891-5905): row 1 the group and curve names, each
  followed by an empty cell; row 2 ``X,Y`` for every column pair; then rows where each curve has its own time (X)
  and value (Y), group columns and finished curves left empty.

The user picks the master and the slave column by name (``guess_columns`` proposes MAPOS / CMASTERCPOS and
APOS); ``wrap`` turns them into slave position over master position modulo the master cycle, the slave taken
back by one slave cycle length per master cycle, with NaN gaps where the master wraps (drawn as separate
strokes).  Every problem raises TraceError naming ``file:line``.
"""

from __future__ import annotations

import csv
import io
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from motiontool.fileio import MiB, read_bytes

#: Column names proposed for the master and the slave position, best first (a column matches when the name
#: appears in it as a word, so the scope's "Axis: CMASTERCPOS [4230]" matches too).
MASTER_NAMES = ("CMASTERCPOS", "MAPOS", "4230", "MASTER_POS", "4105", "MCPOS")
SLAVE_NAMES = ("APOS", "CPOS", "REG_ACTPOS", "4097")
MAX_BYTES = 512 * MiB  # decisions R4


class TraceError(ValueError):
    """A trace file that cannot be used; str() is ``source:line: message``."""

    def __init__(self, message: str, line: int = 0, source: str | None = None) -> None:
        where = f"{source or '<trace>'}:{line}: " if line else f"{source or '<trace>'}: "
        super().__init__(where + message)
        self.message = message
        self.line = line
        self.source = source


@dataclass
class TraceTable:
    """The columns of one trace file: name → (times [ms], values)."""

    source: str
    layout: str  # "trace" (motiontool run --trace) or "scope" (oscilloscope export)
    columns: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)

    @property
    def names(self) -> list[str]:
        return list(self.columns)

    def master_slave(self, master: str, slave: str, cycle: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Master and slave values at the slave's sample times (a scope master on another time base is
        interpolated linearly onto them). ``cycle``: the master's cycle length in the column's own units; a master
        that wraps at it is unwrapped first, so no value is interpolated across a wrap."""
        for name in (master, slave):
            if name not in self.columns:
                raise TraceError(f"no column {name!r} (columns: {', '.join(self.names)})", 0, self.source)
        (tm, m), (ts, s) = self.columns[master], self.columns[slave]
        if len(tm) == len(ts) and np.array_equal(tm, ts):
            return m, s
        inside = (ts >= tm[0]) & (ts <= tm[-1])
        if not inside.any():
            raise TraceError(f"the columns {master!r} and {slave!r} do not overlap in time", 0, self.source)
        if cycle:
            m = unwrap(m, cycle)
        return np.interp(ts[inside], tm, m), s[inside]


# ASCII digits only (float() would take every script's digits); inf/nan pass to be refused as not finite
_DECIMAL = re.compile(r"[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?|[-+]?(inf|infinity|nan)", re.IGNORECASE)


def _number(text: str, source: str, line: int, column: str) -> float:
    try:
        if not _DECIMAL.fullmatch(text.strip()):
            raise ValueError(text)
        value = float(text)
    except ValueError:
        raise TraceError(f"column {column!r}: {text.strip()!r} is not a number", line, source) from None
    if not math.isfinite(value):
        raise TraceError(f"column {column!r}: {text.strip()!r} is not a finite number", line, source)
    return value


def parse_trace(text: str, source: str = "<trace>") -> TraceTable:
    """Parse the text of a --trace CSV or a scope CSV export."""
    reader = csv.reader(io.StringIO(text.lstrip("\ufeff")))
    rows = []
    try:
        for row in reader:
            rows.append(row)
    except csv.Error as exc:  # e.g. a lone carriage return inside a field
        raise TraceError(f"not a CSV file: {exc}", reader.line_num, source) from None
    numbered = [(k, row) for k, row in enumerate(rows, 1) if any(cell.strip() for cell in row)]
    if not numbered:
        raise TraceError("the file is empty", 1, source)
    if len(numbered) > 1 and _is_xy_row(numbered[1][1]):
        return _parse_scope(numbered, source)
    line, header = numbered[0]
    names = [cell.strip() for cell in header]
    if not names or names[0].lower() != "time_ms":
        raise TraceError("not a trace: the first row must start with time_ms (motiontool run --trace) or the "
                         "second row be X,Y,... (oscilloscope CSV export)", line, source)
    if len(names) < 3:
        raise TraceError("a trace needs at least two signal columns besides time_ms (master and slave)", line,
                         source)
    _unique(names[1:], line, source)
    values: list[list[float]] = []
    for line, row in numbered[1:]:
        if len(row) != len(names):
            raise TraceError(f"{len(row)} values, the header has {len(names)} columns", line, source)
        values.append([_number(cell, source, line, name) for cell, name in zip(row, names, strict=True)])
    if not values:
        raise TraceError("the trace has a header but no samples", numbered[0][0], source)
    data = np.array(values)
    table = TraceTable(source, "trace")
    for j, name in enumerate(names[1:], 1):
        table.columns[name] = (data[:, 0], data[:, j])
    return table


def _is_xy_row(row: list[str]) -> bool:
    cells = [c.strip().upper() for c in row]
    return len(cells) >= 2 and len(cells) % 2 == 0 and cells == ["X", "Y"] * (len(cells) // 2)


def _unique(names: list[str], line: int, source: str) -> None:
    seen: set[str] = set()
    for name in names:
        if not name:
            raise TraceError("a column has no name", line, source)
        if name in seen:
            raise TraceError(f"column {name!r} appears twice", line, source)
        seen.add(name)


def _parse_scope(numbered: list[tuple[int, list[str]]], source: str) -> TraceTable:
    (name_line, names_row), (xy_line, xy_row) = numbered[0], numbered[1]
    width = len(xy_row)
    names_row = names_row + [""] * (width - len(names_row))
    if len(names_row) != width:
        raise TraceError(f"{len(names_row)} cells, row 2 has {width}", name_line, source)
    pairs = [(names_row[2 * k].strip(), 2 * k) for k in range(width // 2)]
    points: dict[str, tuple[list[float], list[float]]] = {}
    finished: set[str] = set()
    for line, row in numbered[2:]:
        if len(row) > width:
            raise TraceError(f"{len(row)} cells, row 2 has {width}", line, source)
        row = row + [""] * (width - len(row))
        for name, col in pairs:
            x, y = row[col].strip(), row[col + 1].strip()
            if not x and not y:
                if name in points:
                    finished.add(name)
                continue
            if not x or not y:
                raise TraceError(f"curve {name!r}: X and Y must both be given", line, source)
            if name in finished:
                raise TraceError(f"curve {name!r}: a value after the curve had ended", line, source)
            xs, ys = points.setdefault(name, ([], []))
            xs.append(_number(x, source, line, name))
            ys.append(_number(y, source, line, name))
    table = TraceTable(source, "scope")
    for name, _ in pairs:
        if name in points:  # groups (name, no values) are headings only
            if name in table.columns:
                raise TraceError(f"curve {name!r} appears twice", name_line, source)
            table.columns[name] = (np.array(points[name][0]), np.array(points[name][1]))
    if len(table.columns) < 2:
        raise TraceError("the scope export holds fewer than two curves with values (master and slave needed)",
                         xy_line, source)
    return table


def read_trace(path: str | Path) -> TraceTable:
    path = Path(path)
    try:
        data = read_bytes(path, MAX_BYTES, "trace")
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise TraceError("not UTF-8 text", line, str(path)) from None
    except OSError as exc:
        raise TraceError(exc.strerror or str(exc), 0, str(path)) from None
    return parse_trace(text, str(path))


def _matches(candidate: str, name: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(candidate)}(?![A-Za-z0-9_])", name, re.IGNORECASE) is not None


def guess_columns(names: list[str]) -> tuple[str | None, str | None]:
    """The proposed (master, slave) columns: the first of MASTER_NAMES / SLAVE_NAMES that a column contains."""
    def pick(candidates: tuple[str, ...], taken: str | None) -> str | None:
        for candidate in candidates:
            for name in names:
                if name != taken and _matches(candidate, name):
                    return name
        return None

    master = pick(MASTER_NAMES, None)
    return master, pick(SLAVE_NAMES, master)


def unwrap(master, length: float) -> np.ndarray:
    """A master that wraps at its cycle (CMASTERCPOS) as a continuous position: a step of more than half a
    cycle between two samples that both lie inside 0..length is taken as a wrap."""
    m = np.asarray(master, dtype=float)
    if len(m) < 2:
        return m
    step = np.diff(m)
    in_cycle = (m >= 0) & (m <= length)
    wrapped = (np.abs(step) > length / 2) & in_cycle[:-1] & in_cycle[1:]
    wraps = np.where(wrapped, np.sign(step), 0.0)
    return m - length * np.concatenate([[0.0], np.cumsum(wraps)])


def wrap(master, slave, master_length: float, slave_length: float = 0.0, master_scale: float = 1.0,
         slave_scale: float = 1.0, slave_offset: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Slave over master modulo the master cycle: x = M mod L, y = S − ⌊M/L⌋·slave_length − offset, with
    M = master·master_scale, S = slave·slave_scale; a NaN pair separates the strokes where the cycle changes.

    A master that already wraps at the cycle (CMASTERCPOS, the curve master position) is unwrapped first: a step
    of more than half a cycle between two samples that both lie inside 0..L is taken as a wrap."""
    if not master_length > 0:
        raise ValueError("the master cycle length must be > 0")
    m = unwrap(np.asarray(master, dtype=float) * master_scale, master_length)
    s = np.asarray(slave, dtype=float) * slave_scale
    cycle = np.floor(m / master_length)
    x = np.clip(m - cycle * master_length, 0.0, master_length)  # (rounding at the cycle's ends)
    y = s - cycle * slave_length - slave_offset
    breaks = np.nonzero(np.diff(cycle) != 0)[0] + 1
    return np.insert(x, breaks, np.nan), np.insert(y, breaks, np.nan)
