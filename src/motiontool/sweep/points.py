"""The points of a sweep: a grid of `--vary KEY=LO:HI:STEP` ranges, the rows of a `--points` CSV file, or
`--random N` points drawn with a seed. A point is a tuple of whole numbers, one per varied parameter, because
every parameter the controllers hold is a whole number (cliargs.PARAMETER_VALUE)."""

from __future__ import annotations

import csv
import io
import itertools
import random
import re
from dataclasses import dataclass
from pathlib import Path

from motiontool.cliargs import PARAMETER_VALUE, BadNumber, shown, whole
from motiontool.fileio import read_text, reason

MAX_POINTS = 1_000_000          # a sweep beyond this is a typing slip (20:80:0.5 → 20:80000000:5)
MAX_POINTS_FILE = 64 << 20      # bytes of a --points file (fileio's size limit, decisions R4)
_KEY = re.compile(r"[A-Za-z0-9_#.\-]{1,40}")  # 32-60, KPROP, 18.11, #18.11; nothing a CSV header must quote


class SweepError(ValueError):
    """A refused option or file of a sweep: ``str()`` names the option and the position, one line."""


@dataclass(frozen=True)
class Vary:
    """One `--vary KEY=LO:HI[:STEP]`: the whole numbers LO, LO+STEP, … up to HI (STEP None: any in LO..HI)."""
    key: str
    lo: int
    hi: int
    step: int | None

    def values(self) -> range:
        return range(self.lo, self.hi + 1, self.step or 1)


def _number(text: str, where: str, lo: int = PARAMETER_VALUE[0], hi: int = PARAMETER_VALUE[1]) -> int:
    """The whole number `text` (cliargs.whole: ASCII digits, bounded), else SweepError naming `where`."""
    try:
        return whole(text, "", lo, hi)
    except BadNumber:
        raise SweepError(f"{where}: '{shown(text)}' is not a whole number from {lo} to {hi}") from None


def parse_vary(text: str, nth: int = 1) -> Vary:
    """`KEY=LO:HI:STEP` (a grid) or `KEY=LO:HI` (--random only); SweepError naming --vary, which one and where."""
    what = f"--vary '{shown(text)}' (number {nth})"
    key, eq, rng = text.partition("=")
    if not eq:
        raise SweepError(f"{what}, position 1: give KEY=LO:HI:STEP, e.g. 32-60=20:80:5")
    if not _KEY.fullmatch(key.strip()):
        raise SweepError(f"{what}, position 1: '{shown(key)}' is no parameter: give its number (32-60, 18.11) or "
                         "name (KPROP)")
    parts = rng.split(":")
    if len(parts) not in (2, 3):
        raise SweepError(f"{what}, position {len(key) + 2}: give LO:HI:STEP after '=', got '{shown(rng)}'")
    starts = list(itertools.accumulate([len(key) + 2] + [len(p) + 1 for p in parts[:-1]]))
    lo = _number(parts[0], f"{what}, position {starts[0]}")
    hi = _number(parts[1], f"{what}, position {starts[1]}")
    if hi < lo:
        raise SweepError(f"{what}, position {starts[1]}: HI {hi} is below LO {lo}")
    step = _number(parts[2], f"{what}, position {starts[2]}", 1, PARAMETER_VALUE[1]) if len(parts) == 3 else None
    return Vary(key.strip(), lo, hi, step)


def check_keys(keys: list[str], what: str) -> None:
    seen = set()
    for key in keys:
        if key.upper() in seen:
            raise SweepError(f"{what}: parameter {key} is given twice")
        seen.add(key.upper())


def grid(varies: list[Vary]) -> list[tuple[int, ...]]:
    """Every combination, the first --vary outermost (the rows of the CSV in the order the options were given)."""
    for n, v in enumerate(varies, start=1):
        if v.step is None:
            raise SweepError(f"--vary '{v.key}={v.lo}:{v.hi}' (number {n}): a grid needs a STEP "
                             f"({v.key}={v.lo}:{v.hi}:STEP), or draw points with --random N")
    _limit([len(v.values()) for v in varies], "--vary")
    return list(itertools.product(*(v.values() for v in varies)))


def random_points(varies: list[Vary], count: int, seed: int) -> list[tuple[int, ...]]:
    """`count` points, each value drawn uniformly from its range (on the STEP grid when STEP is given) with
    Python's Mersenne Twister seeded by `seed`: the same seed gives the same points on every machine."""
    _limit([count], "--random")
    rng = random.Random(seed)
    return [tuple(v.lo + rng.randrange(len(v.values())) * (v.step or 1) for v in varies) for _ in range(count)]


def _limit(sizes: list[int], option: str) -> None:
    total = 1
    for size in sizes:
        total *= size
        if total > MAX_POINTS:
            raise SweepError(f"{option}: more than {MAX_POINTS} points; sweep a coarser grid or several parts")


def read_points(path: Path) -> tuple[list[str], list[tuple[int, ...]]]:
    """(parameter keys, points) of a `--points` CSV file: a header of parameter keys, then one point per line."""
    what = f"--points {path}"
    try:
        text = read_text(path, MAX_POINTS_FILE, "points file")
    except OSError as exc:
        raise SweepError(f"{what}: {reason(exc)}") from None
    except UnicodeDecodeError:
        raise SweepError(f"{what}: not a UTF-8 text file") from None
    rows = [r for r in csv.reader(io.StringIO(text.lstrip("\ufeff"))) if any(c.strip() for c in r)]
    if not rows:
        raise SweepError(f"{what}: empty; give a header of parameters (32-60,32-61) and one point per line")
    keys = [k.strip() for k in rows[0]]
    for col, key in enumerate(keys, start=1):
        if not _KEY.fullmatch(key):
            raise SweepError(f"{what}, line 1, column {col}: '{shown(key)}' is no parameter")
    check_keys(keys, what)
    _limit([len(rows) - 1], what)
    points = []
    for line, row in enumerate(rows[1:], start=2):
        if len(row) != len(keys):
            raise SweepError(f"{what}, line {line}: {len(row)} values for {len(keys)} parameters")
        points.append(tuple(_number(v, f"{what}, line {line}, column {col}") for col, v in enumerate(row, start=1)))
    if not points:
        raise SweepError(f"{what}: no points after the header")
    return keys, points
