"""Array definition files (.zba): the Array Editor's template of names, limits, defaults and descriptions
(ide-spec 5.31-5.38, DG L4515-4590; docs/formats/zba.md).

One definition per line; fields separated by `,` or `;` (either, per line), spaces around fields trimmed.
Field 1 is the record type; a line with another first field is a comment and is not kept.  Data and Group
records carry, after the type: Array, Index, Name, Value, Default, Minimum, Maximum, Description, RW.

The reader is lenient where the manual's own example is irregular (a User line without its empty Array field,
Group lines with fewer trailing fields) and reports every other problem as ZbaError with the 1-based line.
The writer is strict: the type plus all nine fields, names and descriptions quoted when they need it.  Qt-free.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from motiontool.fileio import MiB, atomic_write_text, read_bytes

DATA_TYPES = ("User", "Global", "System", "Axis", "Temp", "Proc", "Array")
RECORD_TYPES = ("Date", "Widths", *DATA_TYPES, "Group")
FIELDS = ("array", "index", "name", "value", "default", "minimum", "maximum", "description", "rw")
# ASCII digits only: Python's \d and int() also take other scripts' digits.
_INT = re.compile(r"[-+]?[0-9]+")
_NUMBER = re.compile(r"[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?")
_DATE = re.compile(r"[0-9]{4}:[0-9]{2}:[0-9]{2} [0-9]{2}:[0-9]{2}")
MAX_BYTES = 16 * MiB  # decisions R4


class ZbaError(ValueError):
    def __init__(self, message: str, line: int = 0) -> None:
        super().__init__(f"line {line}: {message}" if line else message)
        self.message = message
        self.line = line


@dataclass(frozen=True)
class Record:
    """One list row: a data item (kind in DATA_TYPES) or a group heading (kind "Group")."""

    kind: str
    array: int | None
    index: int
    name: str = ""
    value: int | float | None = None
    default: int | float | None = None
    minimum: int | float | None = None
    maximum: int | float | None = None
    description: str = ""
    rw: bool = True

    @property
    def key(self) -> tuple[str, int | None, int]:
        return (self.kind, self.array, self.index)

    def check(self, value: int | float) -> str | None:
        """Why `value` is not allowed for this item, or None (the red cell's tooltip, ide-spec 5.8)."""
        if self.minimum is not None and value < self.minimum:
            return f"{_fmt(value)} is below the minimum {_fmt(self.minimum)}"
        if self.maximum is not None and value > self.maximum:
            return f"{_fmt(value)} is above the maximum {_fmt(self.maximum)}"
        return None


@dataclass
class ZbaFile:
    date: str = ""
    widths: list[int] = field(default_factory=list)
    records: list[Record] = field(default_factory=list)


def _fmt(value: int | float | None) -> str:
    if value is None:
        return ""
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return str(value)


def _split(line: str) -> list[str]:
    """Fields separated by `,` or `;`; double quotes protect separators inside Name/Description."""
    fields, current, quoted = [], [], False
    for ch in line:
        if ch == '"':
            quoted = not quoted
            current.append(ch)
        elif ch in ",;" and not quoted:
            fields.append("".join(current).strip())
            current = []
        else:
            current.append(ch)
    fields.append("".join(current).strip())
    return fields


def _text(value: str, line: int, what: str) -> str:
    if value.startswith('"'):
        if len(value) < 2 or not value.endswith('"') or '"' in value[1:-1]:
            raise ZbaError(f"{what} {value!r}: unbalanced double quotes", line)
        return value[1:-1]
    if '"' in value:
        raise ZbaError(f"{what} {value!r} must not contain a double quote", line)
    return value


def _number(value: str, line: int, what: str) -> int | float | None:
    if value == "":
        return None
    if _INT.fullmatch(value) and len(value) <= 30:  # longer: float() says inf (int() refuses > 4300 digits)
        return int(value)
    if _NUMBER.fullmatch(value) and math.isfinite(float(value)):
        return float(value)
    raise ZbaError(f"{what} {value!r} is not a number", line)


def _int(value: str, line: int, what: str) -> int:
    if not _INT.fullmatch(value) or len(value) > 30:
        raise ZbaError(f"{what} {value!r} is not an integer", line)
    return int(value)


def _optional_int(value: str, line: int, what: str, required: bool) -> int | None:
    if value == "" and not required:
        return None
    return _int(value, line, what)


def _record(kind: str, fields: list[str], n: int) -> Record:
    if kind == "Group":  # Array (visibility code), Index, Name ... and the last field is RW
        if len(fields) < 3:
            raise ZbaError("a Group line needs Array, Index and Name", n)
        rw = _int(fields[-1], n, "RW") if len(fields) > 3 else 0
        return Record("Group", _int(fields[0], n, "Array"), _int(fields[1], n, "Index"),
                      _text(fields[2], n, "Name"), rw=bool(rw))
    if len(fields) == len(FIELDS) - 1 and kind in ("User", "Global") and not _INT.fullmatch(fields[1]):
        fields = ["", *fields]  # the manual's example leaves the empty Array field out (ide-spec 5.36)
    if len(fields) != len(FIELDS):
        raise ZbaError(f"a line of type {kind} needs {len(FIELDS)} fields after the type "
                       f"({', '.join(FIELDS)}), it has {len(fields)}", n)
    array = _optional_int(fields[0], n, "Array", required=kind in ("Axis", "Temp", "Proc", "Array"))
    if kind in ("User", "Global", "System") and array is not None:
        raise ZbaError(f"the Array field of a {kind} line must be empty", n)
    rw = _int(fields[8], n, "RW")
    if rw not in (0, 1):
        raise ZbaError(f"RW must be 0 or 1, not {rw}", n)
    return Record(kind, array, _int(fields[1], n, "Index"), _text(fields[2], n, "Name"),
                  _number(fields[3], n, "Value"), _number(fields[4], n, "Default"),
                  _number(fields[5], n, "Minimum"), _number(fields[6], n, "Maximum"),
                  _text(fields[7], n, "Description"), bool(rw))


def parse_zba(text: str) -> ZbaFile:
    result = ZbaFile()
    seen: dict[tuple, int] = {}
    for n, raw in enumerate(text.splitlines(), start=1):
        fields = _split(raw.lstrip("\ufeff"))
        kind = fields[0]
        if kind not in RECORD_TYPES:
            continue  # a comment line (DG L4540)
        rest = fields[1:]
        if raw.count('"') % 2:
            raise ZbaError("unbalanced double quotes", n)
        if kind == "Date":
            if not rest or not _DATE.fullmatch(rest[0]):
                raise ZbaError("Date needs YYYY:MM:DD HH:MM", n)
            result.date = rest[0]
        elif kind == "Widths":
            result.widths = [_int(w, n, "width") for w in rest if w != ""]
        else:
            record = _record(kind, rest, n)
            if kind != "Group":
                if record.key in seen:
                    raise ZbaError(f"{kind} {record.array if record.array is not None else ''} "
                                   f"{record.index} is already defined on line {seen[record.key]}", n)
                seen[record.key] = n
            result.records.append(record)
    return result


def read_zba(path: str | Path) -> ZbaFile:
    data = read_bytes(path, MAX_BYTES, "array definition file")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("latin-1")  # spreadsheets often save CSV as ANSI
    return parse_zba(text)


def _quote(text: str) -> str:
    if '"' in text:
        raise ZbaError(f"{text!r}: names and descriptions must not contain a double quote")
    return f'"{text}"' if re.search(r"[,; ]", text) else text


def zba_text(zba: ZbaFile) -> str:
    lines = []
    if zba.date:
        lines.append(f"Date,{zba.date}")
    if zba.widths:
        lines.append("Widths," + ",".join(str(w) for w in zba.widths))
    for r in zba.records:
        array = "" if r.array is None else str(r.array)
        lines.append(",".join([r.kind, array, str(r.index), _quote(r.name), _fmt(r.value), _fmt(r.default),
                               _fmt(r.minimum), _fmt(r.maximum), _quote(r.description), "1" if r.rw else "0"]))
    return "\n".join(lines) + "\n"


def write_zba(path: str | Path, zba: ZbaFile) -> None:
    text = zba_text(zba)
    parse_zba(text)  # never write what we cannot read back
    atomic_write_text(path, text)
