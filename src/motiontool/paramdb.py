"""MCO 305 parameter database (groups 19-xx, 32-xx, 33-xx, 34-xx), Qt-free and stdlib only.

Data: ``resources/parameters/mco305.csv``; columns, usage and corrections: ``docs/parameters.md``.
``database().get("kprop").format_line()`` -> ``'32-60 KPROP 30 [0..100000] Proportional Factor'``.
"""

from __future__ import annotations

import csv
import functools
import math
import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from motiontool.resources import resources_path

COLUMNS = ("number", "name", "description", "group", "default", "min", "max", "unit", "options",
           "conversion_index", "data_type", "changes_during_operation", "seed_lines")
DATA_TYPES = ("Int8", "Int16", "Int32", "Uint8", "Uint16", "Uint32")
_NUMBER_RE = re.compile(r"[0-9][0-9]-[0-9][0-9]")
_NAME_RE = re.compile(r"[A-Z][A-Z0-9_]*")
_OPTION_RE = re.compile(r"(-?[0-9]+)=([^|=]+)")


class ParameterError(ValueError):
    """A bad parameter value, an unknown parameter or a malformed database file."""


def _number(text: str) -> int | float:
    """Parse a plain number ("30", "-1", "1.000"); raise ValueError for anything else."""
    text = text.strip()
    if re.fullmatch(r"[-+]?[0-9]{1,30}", text):  # ASCII digits only: \d and int() take every script's digits
        return int(text)
    if re.fullmatch(r"[-+]?([0-9]+\.[0-9]*|\.[0-9]+)", text):
        return float(text)
    raise ValueError(f"{text!r} is not a number")


@dataclass(frozen=True)
class Parameter:
    """One MCO 305 parameter; ``index`` is the number without dash as ``GET 3260`` / ``ON PARAM`` use it."""

    number: str
    index: int
    name: str | None
    description: str
    group: str
    default: int | float
    minimum: int | float
    maximum: int | float
    unit: str
    options: dict[int, str] = field(hash=False)
    conversion_index: int | None
    data_type: str
    changes_during_operation: bool
    seed_lines: str

    @property
    def label(self) -> str:
        return f"{self.number} {self.name}" if self.name else self.number

    @property
    def integral(self) -> bool:
        """True when values are whole numbers (no decimal places in default and range)."""
        return all(isinstance(v, int) for v in (self.default, self.minimum, self.maximum))

    @property
    def read_only(self) -> bool:
        """34-xx readouts and the LCP read-out parameters 19-90..19-99 cannot be written by SET."""
        return self.number.startswith("34-") or 1990 <= self.index <= 1999

    @property
    def _decimals(self) -> int | None:
        """Decimal places of a scaled parameter (conversion index -3 -> 3), None when integral."""
        ci = self.conversion_index
        return -ci if ci is not None and ci < 0 and not self.integral else None

    def _fmt(self, value: int | float) -> str:
        places = self._decimals
        if isinstance(value, int) or places is None or value != round(value, places):
            return repr(value)
        return f"{value:.{places}f}"

    def validate(self, value: object) -> int | float:
        """Return ``value`` as a number (int for integral parameters) or raise ParameterError.

        Accepts int, float and numeric strings; checks the range and, for enumerations, that the
        value is one of the option numbers. Scaled values are rounded to their resolution.
        """
        if isinstance(value, str):
            try:
                value = _number(value)
            except ValueError:
                raise ParameterError(f"{self.label}: {value!r} is not a number") from None
        if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
            raise ParameterError(f"{self.label}: {value!r} is not a number")
        if self.integral:
            if value != int(value):
                raise ParameterError(f"{self.label}: {value!r} is not an integer")
            value = int(value)
        else:
            value = float(value)
        if self.options and value not in self.options:
            choices = ", ".join(str(k) for k in self.options)
            raise ParameterError(f"{self.label}: {self._fmt(value)} is not one of the options {choices}")
        if not self.minimum <= value <= self.maximum:
            raise ParameterError(f"{self.label}: {self._fmt(value)} is outside "
                                 f"{self._fmt(self.minimum)}..{self._fmt(self.maximum)}")
        return value if self._decimals is None else round(value, self._decimals)

    def to_raw(self, value: int | float) -> int:
        """Display value → the raw integer GET/SET and the links use (RAMPMIN 1.000 s → 1000, index -3)."""
        if self.conversion_index:
            return round(value * 10 ** (-self.conversion_index))
        return int(round(value))

    def from_raw(self, raw: int) -> int | float:
        """Raw integer → display value (1000 → 1.0 for conversion index -3); integral parameters stay int."""
        if self.conversion_index:
            value = raw * 10 ** self.conversion_index
            return round(value, self._decimals) if self._decimals is not None else value
        return int(raw)

    def format_line(self) -> str:
        """One-line summary: ``"32-60 KPROP 30 [0..100000] Proportional Factor"``."""
        return (f"{self.number} {self.name or '-'} {self._fmt(self.default)} "
                f"[{self._fmt(self.minimum)}..{self._fmt(self.maximum)}] {self.description}")


def _parse_row(row: dict[str, str]) -> Parameter:
    """Build a Parameter from one CSV row; raise ValueError naming the parameter and the bad column."""
    row = {k: v.strip() for k, v in row.items()}
    number, name = row["number"], row["name"] or None
    conv, flag = row["conversion_index"], row["changes_during_operation"]
    label = f"{number} {name}" if name else number
    if not _NUMBER_RE.fullmatch(number):
        raise ValueError(f"number {number!r} is not like '32-60'")
    if name is not None and not _NAME_RE.fullmatch(name):
        raise ValueError(f"{label}: name is not an APOSS code name")
    values = {}
    for col in ("default", "min", "max"):
        try:
            values[col] = _number(row[col])
        except ValueError as exc:
            raise ValueError(f"{label}: {col} {exc}") from None
    parts = row["options"].split("|") if row["options"] else []
    for part in parts:
        if not _OPTION_RE.fullmatch(part.strip()):
            raise ValueError(f"{label}: option {part!r} is not like '0=Off'")
    if conv and not re.fullmatch(r"-?\d+", conv):
        raise ValueError(f"{label}: conversion_index {conv!r} is not an integer")
    if row["data_type"] not in DATA_TYPES:
        raise ValueError(f"{label}: data_type {row['data_type']!r} is not one of {', '.join(DATA_TYPES)}")
    if flag not in ("TRUE", "FALSE"):
        raise ValueError(f"{label}: changes_during_operation {flag!r} is not TRUE or FALSE")
    if values["min"] > values["max"]:
        raise ValueError(f"{label}: min {row['min']} is above max {row['max']}")
    param = Parameter(
        number=number, index=int(number.replace("-", "")), name=name, description=row["description"],
        group=row["group"], default=values["default"], minimum=values["min"], maximum=values["max"],
        unit=row["unit"], options={int(k): v.strip() for k, v in (p.split("=") for p in parts)},
        conversion_index=int(conv) if conv else None, data_type=row["data_type"],
        changes_during_operation=flag == "TRUE", seed_lines=row["seed_lines"])
    try:
        param.validate(param.default)
    except ParameterError as exc:
        raise ValueError(f"default {exc}") from None
    return param


def _default_path() -> Path:
    try:
        path = resources_path("parameters", "mco305.csv")
        if path.is_file():
            return path
    except (ImportError, TypeError):  # motiontool._resources missing: fall back to the source checkout
        pass
    return Path(__file__).resolve().parents[2] / "resources" / "parameters" / "mco305.csv"


class ParameterDatabase:
    """All parameters of one CSV file, looked up by number ("32-60"), index (3260) or code name."""

    def __init__(self, parameters: list[Parameter], source: str = "<memory>") -> None:
        self.source = source
        self._params = sorted(parameters, key=lambda p: p.index)
        self._by_index = {p.index: p for p in self._params}
        self._by_name = {p.name.upper(): p for p in self._params if p.name}
        if len(self._by_index) != len(self._params):
            raise ParameterError(f"{source}: duplicate parameter numbers")

    @classmethod
    def load(cls, path: str | Path | None = None) -> ParameterDatabase:
        """Read the CSV (default: the packaged ``parameters/mco305.csv``); errors name file:line."""
        path = Path(path) if path is not None else _default_path()
        try:
            with path.open(encoding="utf-8", newline="") as fh:
                reader = csv.DictReader(fh)
                if tuple(reader.fieldnames or ()) != COLUMNS:
                    raise ParameterError(f"{path}:1: header must be {','.join(COLUMNS)}, "
                                         f"got {','.join(reader.fieldnames or ())}")
                params: list[Parameter] = []
                seen: set[str] = set()
                for row in reader:
                    where = f"{path}:{reader.line_num}"
                    if None in row or None in row.values():
                        raise ParameterError(f"{where}: expected {len(COLUMNS)} fields")
                    try:
                        param = _parse_row(row)
                    except ValueError as exc:
                        raise ParameterError(f"{where}: {exc}") from None
                    keys = {param.number, (param.name or param.number).upper()}
                    if seen & keys:
                        raise ParameterError(f"{where}: duplicate parameter {', '.join(sorted(seen & keys))}")
                    seen |= keys
                    params.append(param)
        except (OSError, UnicodeDecodeError, csv.Error) as exc:
            raise ParameterError(f"{path}: cannot read parameter file: {exc}") from None
        return cls(params, str(path))

    def __iter__(self) -> Iterator[Parameter]:
        return iter(self._params)

    def __len__(self) -> int:
        return len(self._params)

    def __contains__(self, key: object) -> bool:
        if isinstance(key, Parameter):
            return self._by_index.get(key.index) == key
        try:
            self.get(key)  # type: ignore[arg-type]
        except ParameterError:
            return False
        return True

    def get(self, key: str | int) -> Parameter:
        """Look up by "32-60", "3260", 3260 or code name (case-insensitive)."""
        param = None
        if isinstance(key, int) and not isinstance(key, bool):
            param = self._by_index.get(key)
        elif isinstance(key, str):
            text = key.strip()
            if _NUMBER_RE.fullmatch(text):
                param = self._by_index.get(int(text.replace("-", "")))
            elif re.fullmatch(r"[0-9]{1,9}", text):
                param = self._by_index.get(int(text))
            else:
                param = self._by_name.get(text.upper())
        if param is None:
            raise ParameterError(f"unknown parameter {key!r}")
        return param

    def find(self, text: str) -> list[Parameter]:
        """Parameters whose number, index, name or description contains ``text`` (case-insensitive)."""
        needle = text.strip().lower()
        return [p for p in self._params
                if needle in f"{p.number}\n{p.index}\n{p.name or ''}\n{p.description}".lower()]

    def group(self, prefix: str) -> list[Parameter]:
        """Parameters whose number starts with ``prefix`` ("32", "32-6", "32-6*", "32-60")."""
        prefix = prefix.strip().rstrip("*")
        return [p for p in self._params if p.number.startswith(prefix)]

    def validate(self, key: str | int, value: object) -> int | float:
        return self.get(key).validate(value)


@functools.cache
def database() -> ParameterDatabase:
    """The default database (``resources/parameters/mco305.csv``), loaded once."""
    return ParameterDatabase.load()
