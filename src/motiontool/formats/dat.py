"""CAM Export/Import: one curve as a ``.dat`` text file holding its controller array (docs/formats/dat.md).

The manual exports "the curve data … to an ASCII text file" in "the exact format of the array" [DG L3581] and
imports only what "exactly match[es] an export file" [DG L3580] (ide-spec 7.5).  Layout (format 1)::

    # motiontool cam export, format 1
    name = stamping
    intervals = 40
    start_gradient = 0
    end_gradient = 0
    elements = 92
    1128353093
    1
    ...

Then exactly ``elements`` lines of one signed 32-bit integer each: the curve array in controller order
(docs/formats/cam-array.md).  The three header values the array does not carry (the editor's interval count of
a curve without interpolation points, and the gradients of the SPECIFIED curve types) let Import rebuild the
exported curve exactly.  Import decodes the array with the same layout module the kernel uses and raises
DatError naming the 1-based line.  Qt-free.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

from motiontool.camcurve.layout import CurveArrayError, decode, encode
from motiontool.camcurve.model import MAX_ARRAY_ELEMENTS, MAX_INTERVALS, Curve, CurveError
from motiontool.fileio import MiB, atomic_write_text, read_text

DAT_VERSION = 1
DAT_MAGIC = "# motiontool cam export, format "
HEADER_KEYS = ("name", "intervals", "start_gradient", "end_gradient", "elements")
FIRST_VALUE_LINE = len(HEADER_KEYS) + 2  # magic line + header lines, 1-based
MAX_BYTES = 16 * MiB  # one curve array (decisions R4)
INT32_MIN, INT32_MAX = -(2 ** 31), 2 ** 31 - 1
# ASCII digits only: Python's \d, isdigit() and int() also take other scripts' digits.
_INT_RE = re.compile(r"[-+]?[0-9]+")
_FLOAT_RE = re.compile(r"[-+]?([0-9]+\.[0-9]*|\.[0-9]+|[0-9]+)([eE][-+]?[0-9]+)?")


class DatError(ValueError):
    """A .dat file that does not match the export layout; ``line`` is 1-based, ``source`` the file when known."""

    def __init__(self, message: str, line: int = 0, source: str | None = None) -> None:
        if source:
            where = f"{source}:{line}: " if line else f"{source}: "
        else:
            where = f"line {line}: " if line else ""
        super().__init__(where + message)
        self.message = message
        self.line = line
        self.source = source


@dataclass(frozen=True)
class DatCurve:
    """The contents of a .dat file: the curve array and the editor values the array does not hold."""

    name: str
    values: tuple[int, ...]
    intervals: int = 1
    start_gradient: float = 0.0
    end_gradient: float = 0.0

    def to_curve(self) -> Curve:
        """The exported curve, rebuilt from its array (raises DatError for an array that does not decode)."""
        try:
            decoded = decode(list(self.values))
            return decoded.to_curve(self.intervals, self.start_gradient, self.end_gradient)
        except CurveArrayError as exc:
            raise DatError(str(exc), FIRST_VALUE_LINE + exc.index) from None
        except CurveError as exc:
            raise DatError(str(exc), FIRST_VALUE_LINE) from None


def _num(value: float) -> str:
    value = float(value)
    return str(int(value)) if value.is_integer() and abs(value) < 2 ** 53 else repr(value)


def export_curve(curve: Curve) -> DatCurve:
    return DatCurve(curve.name, tuple(encode(curve)), curve.intervals, curve.start_gradient, curve.end_gradient)


def dat_text(data: Curve | DatCurve) -> str:
    if isinstance(data, Curve):
        data = export_curve(data)
    lines = [f"{DAT_MAGIC}{DAT_VERSION}", f"name = {data.name}", f"intervals = {data.intervals}",
             f"start_gradient = {_num(data.start_gradient)}", f"end_gradient = {_num(data.end_gradient)}",
             f"elements = {len(data.values)}"]
    lines += [str(v) for v in data.values]
    return "\n".join(lines) + "\n"


def write_dat(path: str | Path, curve: Curve | DatCurve) -> None:
    atomic_write_text(path, dat_text(curve))


def _float(text: str, line: int, key: str) -> float:
    if _FLOAT_RE.fullmatch(text) and math.isfinite(float(text)):
        return float(text)
    raise DatError(f"{key} {text!r} is not a number", line)


def _count(text: str, line: int, key: str, minimum: int, maximum: int) -> int:
    if not re.fullmatch(r"[0-9]{1,9}", text) or int(text) < minimum:
        raise DatError(f"{key} {text!r} is not an integer >= {minimum}", line)
    if int(text) > maximum:  # the controller's array memory; checked before anything is built (decisions R15)
        raise DatError(f"{key} = {text} is more than the controller's array memory allows ({maximum})", line)
    return int(text)


def parse_dat(text: str) -> DatCurve:
    lines = text.split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    lines = [line.rstrip("\r") for line in lines]
    if not lines or not lines[0].lstrip("\ufeff").startswith(DAT_MAGIC):
        raise DatError(f"not a motiontool cam export: the first line must be '{DAT_MAGIC}N'", 1)
    version = lines[0].lstrip("\ufeff")[len(DAT_MAGIC):].strip()
    if not re.fullmatch(r"[0-9]{1,9}", version) or not 1 <= int(version) <= DAT_VERSION:
        raise DatError(f"unsupported export format {version!r} (this motiontool reads 1..{DAT_VERSION})", 1)
    header: dict[str, str] = {}
    for k, key in enumerate(HEADER_KEYS, start=1):
        if k >= len(lines):
            raise DatError(f"missing '{key} = ...' line (truncated?)", k + 1)
        prefix = f"{key} = "
        if not lines[k].startswith(prefix):
            raise DatError(f"expected '{key} = ...', got {lines[k]!r}", k + 1)
        header[key] = lines[k][len(prefix):].strip()
    intervals = _count(header["intervals"], 3, "intervals", 1, MAX_INTERVALS)
    start_gradient = _float(header["start_gradient"], 4, "start_gradient")
    end_gradient = _float(header["end_gradient"], 5, "end_gradient")
    count = _count(header["elements"], 6, "elements", 1, MAX_ARRAY_ELEMENTS)
    body = lines[FIRST_VALUE_LINE - 1:]
    if len(body) < count:
        raise DatError(f"elements = {count} but only {len(body)} value lines follow (truncated?)", len(lines))
    if len(body) > count:
        raise DatError(f"more than elements = {count} value lines", FIRST_VALUE_LINE + count)
    values = []
    for k, line in enumerate(body):
        number = FIRST_VALUE_LINE + k
        item = line.strip()
        if not _INT_RE.fullmatch(item):
            raise DatError(f"expected one integer, got {line!r}", number)
        value = int(item) if len(item) <= 12 else INT32_MAX + 1
        if not INT32_MIN <= value <= INT32_MAX:
            raise DatError(f"{item} does not fit a 32-bit array element", number)
        values.append(value)
    data = DatCurve(header["name"], tuple(values), intervals, start_gradient, end_gradient)
    curve = data.to_curve()  # refuse an array the controller would refuse (SETCURVE error 191)
    if curve.name != data.name:
        raise DatError(f"name = {data.name} but the array is named {curve.name!r}", 2)
    return data


def read_dat(path: str | Path) -> DatCurve:
    """Read a .dat file; every DatError names the file (and the line)."""
    try:
        text = read_text(path, MAX_BYTES, "curve export")
    except UnicodeDecodeError:
        raise DatError("not a text file (invalid UTF-8)", 0, str(path)) from None
    try:
        return parse_dat(text)
    except DatError as exc:
        raise DatError(exc.message, exc.line, str(path)) from None
    except (CurveError, CurveArrayError) as exc:
        raise DatError(str(exc), 0, str(path)) from None
