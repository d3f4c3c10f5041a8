"""A finished sweep, read back from its CSV (docs/sweep.md "The CSV") for the IDE's sweep view: the points, their
measures as numbers, the failed points, and the shapes a plot wants (a line over one parameter, a grid over two).

The reader is bounded and says where a file is wrong (`sweep.csv, line 4, column 3: …`); it takes any file the
sweep writes, with gaps where a Ctrl+C left points undone."""

from __future__ import annotations

import csv
import io
import math
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from motiontool.fileio import read_text

MAX_RESULTS_FILE = 64 << 20   # a million points of a few measures: the sweep refuses more points (R19)


class ResultsError(ValueError):
    """A file that is not a sweep's CSV; the message names the file and the place."""


@dataclass(frozen=True)
class SweepResults:
    keys: list[str]                     # the varied parameters, as the sweep was given them
    measures: list[str]                 # the measure expressions (the CSV's headers)
    numbers: list[int]                  # each row's point number (1-based; gaps after a Ctrl+C)
    points: np.ndarray                  # rows × keys, the parameter values (int64)
    values: np.ndarray                  # rows × measures, float; NaN where a measure has no value
    errors: list[str]                   # each row's error, "" when it ran

    @property
    def failed(self) -> int:
        return sum(1 for e in self.errors if e)

    def line(self, measure: int, key: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(parameter values, measure) over parameter `key`, sorted by the parameter: for one varied parameter."""
        order = np.argsort(self.points[:, key], kind="stable")
        return self.points[order, key].astype(float), self.values[order, measure]

    def grid(self, measure: int, x: int = 0, y: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(x values, y values, measure[x, y]) for a heat map over two parameters; NaN where no point ran (or
        where a measure had no value). With more parameters, the last point at each (x, y) is shown."""
        xs, ys = np.unique(self.points[:, x]), np.unique(self.points[:, y])
        table = np.full((xs.size, ys.size), np.nan)
        table[np.searchsorted(xs, self.points[:, x]), np.searchsorted(ys, self.points[:, y])] = \
            self.values[:, measure]
        return xs.astype(float), ys.astype(float), table

    def row_of(self, number: int) -> int:
        return self.numbers.index(number)


def read_results(path: Path | str) -> SweepResults:
    path = Path(path)
    try:
        text = read_text(path, MAX_RESULTS_FILE, "sweep file")
    except UnicodeDecodeError as exc:
        raise ResultsError(f"{path}: not UTF-8 text (byte {exc.start})") from None
    return parse_results(text, str(path))


def parse_results(text: str, name: str = "sweep.csv") -> SweepResults:
    try:
        rows = list(csv.reader(io.StringIO(text.lstrip("\ufeff"))))
    except csv.Error as exc:
        raise ResultsError(f"{name}: not a CSV file ({exc})") from None
    header = [h.strip() for h in rows[0]] if rows else []
    if len(header) < 3 or header[0] != "point" or header[-1] != "error":
        raise ResultsError(f"{name}, line 1: not a sweep's CSV (its header is point, the parameters, the measures, "
                           "error)")
    middle = header[1:-1]
    # a measure is one number from signals: always a function call; a parameter key never has parentheses
    keys = [h for h in middle if "(" not in h]
    measures = middle[len(keys):]
    if not keys or not measures or any("(" not in m for m in measures):
        raise ResultsError(f"{name}, line 1: expected the parameters, then the measures (e.g. 32-60,max(APOS))")
    numbers, points, values, errors = [], [], [], []
    for line, row in enumerate(rows[1:], start=2):
        if not any(cell.strip() for cell in row):
            continue
        if len(row) != len(header):
            raise ResultsError(f"{name}, line {line}: {len(row)} columns, the header has {len(header)}")
        numbers.append(_whole(row[0], name, line, 0))
        points.append([_whole(row[c], name, line, c) for c in range(1, 1 + len(keys))])
        values.append([_measure(row[c], name, line, c) for c in range(1 + len(keys), len(header) - 1)])
        errors.append(row[-1].strip())
    repeated = [n for n, count in Counter(numbers).items() if count > 1]
    if repeated:
        raise ResultsError(f"{name}: point {repeated[0]} appears twice")
    return SweepResults(keys, measures, numbers, np.array(points, dtype=np.int64).reshape(len(numbers), len(keys)),
                        np.array(values, dtype=float).reshape(len(numbers), len(measures)), errors)


def _whole(cell: str, name: str, line: int, column: int) -> int:
    try:
        return int(cell.strip())
    except ValueError:
        raise ResultsError(f"{name}, line {line}, column {column + 1}: '{cell[:40]}' is not a whole number") \
            from None


def _measure(cell: str, name: str, line: int, column: int) -> float:
    text = cell.strip()
    if not text:
        return math.nan          # a failed point's measures are empty
    try:
        return float(text)       # also "nan": a settle time that never came
    except ValueError:
        raise ResultsError(f"{name}, line {line}, column {column + 1}: '{cell[:40]}' is not a number") from None

