"""Configuration files (.zbc, and the older .cnf extension): parameters, arrays and CAM curve definitions.

Our own versioned, line-based text format (ide-spec 4.2, 7.4; described in docs/formats/zbc.md).  Qt-free.
The output is deterministic (parameters sorted by number, arrays in DIM order, fixed key order and number
formatting), so ``config_text(read_config(config_text(c))) == config_text(c)``.  The reader never evaluates
anything; every problem raises ConfigError naming the 1-based line and the reason.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from motiontool.camcurve.layout import CurveArrayError, decode, encode
from motiontool.camcurve.model import (
    FIX_POINT_TYPES,
    LAW_TYPES,
    MAX_ARRAY_ELEMENTS,
    MAX_INTERVALS,
    Curve,
    CurveError,
    CurveType,
    FixPoint,
    StartStopPair,
)
from motiontool.fileio import MiB, atomic_write_text, read_bytes
from motiontool.formats import zbc_drive
from motiontool.paramdb import Parameter, ParameterError, database

FORMAT_VERSION = 3  # 2: motion laws (LAW_TYPES), 3: the [fc300] section; each written only by files that use it
LAW_FORMAT = 2
MAGIC = "# motiontool configuration file, format "
EXTENSIONS = (".zbc", ".cnf")
VALUES_PER_LINE = 16
MAX_BYTES = 64 * MiB  # a full array memory (1 000 000 values) is some 12 MiB of text (decisions R4)
INT32_MIN, INT32_MAX = -(2 ** 31), 2 ** 31 - 1
PARAMETER_SECTIONS = ("global", "axis", "user")

#: Keys of a [curve NAME] section in the order they are written (point/pair lines follow).
CURVE_KEYS = ("master_length", "intervals", "interpolation", "curve_type", "slave_stop_position",
              "correction_start", "correction_end", "max_correction", "cycles_per_min", "master_marker_pos",
              "slave_marker_pos", "start_gradient", "end_gradient")
_NUMBER_KEYS = CURVE_KEYS[4:]
# ASCII digits only: Python's \d and int() also take other scripts' digits ("٥٠" would load as 50).
_INT_RE = re.compile(r"[-+]?[0-9]+")
_FLOAT_RE = re.compile(r"[-+]?([0-9]+\.[0-9]*|\.[0-9]+|[0-9]+)([eE][-+]?[0-9]+)?")
_PARAM_KEY_RE = re.compile(r"([0-9][0-9]-[0-9][0-9])(?:[ \t]+([A-Za-z][A-Za-z0-9_]*))?")


class ConfigError(ValueError):
    """A configuration file that cannot be read (or a configuration that cannot be written).

    ``line`` is the 1-based line concerned (0 when no line applies), ``message`` the reason.
    """

    def __init__(self, message: str, line: int = 0, source: str | None = None) -> None:
        where = f"{source}:" if source else ""
        where += f"{line}: " if line else (" " if source else "")
        super().__init__(f"{where}{message}".strip())
        self.message = message
        self.line = line
        self.source = source


def parameter_section(param: Parameter) -> str:
    """The section a parameter is saved in: 19-xx user (application), 33-8x/33-9x global, other 32/33 axis."""
    if param.number.startswith("19-"):
        return "user"
    if param.number.startswith(("33-8", "33-9")):
        return "global"
    return "axis"


def _savable(param: Parameter) -> bool:
    return not param.read_only


@dataclass
class ArrayEntry:
    """One controller array: name, values (longs) and, for a curve array, the name of its curve."""

    name: str
    values: list[int]
    curve: str | None = None


@dataclass
class ConfigFile:
    """Contents of a .zbc/.cnf file.  ``parameters`` by number ("32-60"); ``arrays`` in DIM order."""

    parameters: dict[str, int | float] = field(default_factory=dict)
    arrays: list[ArrayEntry] = field(default_factory=list)
    curves: list[Curve] = field(default_factory=list)
    drive: dict[str, int] = field(default_factory=dict)  # FC 300 settings by LCP number ("4-13"), zbc_drive

    def array(self, name: str) -> ArrayEntry | None:
        return next((a for a in self.arrays if a.name == name), None)

    def curve(self, name: str) -> Curve | None:
        return next((c for c in self.curves if c.name == name), None)

    def add_curve(self, curve: Curve) -> ArrayEntry:
        """Add or replace ``curve`` and its encoded array (same name; a replaced array keeps its DIM position).

        Raises CurveError when the controller array cannot hold the curve (layout.encode).
        """
        values = encode(curve)
        entry = ArrayEntry(curve.name, values, curve.name)
        for i, existing in enumerate(self.curves):
            if existing.name == curve.name:
                self.curves[i] = curve
                break
        else:
            self.curves.append(curve)
        for i, array in enumerate(self.arrays):
            if array.name == curve.name:
                self.arrays[i] = entry
                break
        else:
            self.arrays.append(entry)
        return entry

    def remove_curve(self, name: str) -> None:
        """Remove a curve and its array."""
        self.curves = [c for c in self.curves if c.name != name]
        self.arrays = [a for a in self.arrays if not (a.name == name or a.curve == name)]


# -- writing -------------------------------------------------------------------------------------------------------
def _num(value: float) -> str:
    """ints as ints, floats with repr (round-trips exactly, keeps the type)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ConfigError(f"{value!r} is not a number")
    if isinstance(value, int):
        return str(value)
    if not math.isfinite(value):
        raise ConfigError(f"{value!r} is not a finite number")
    return repr(float(value))


def _param_value(param: Parameter, value: int | float) -> str:
    if isinstance(value, int) and not isinstance(value, bool):
        return str(value)
    ci = param.conversion_index
    if ci is not None and ci < 0 and not param.integral:
        return f"{value:.{-ci}f}"
    return repr(float(value))


def config_text(config: ConfigFile) -> str:
    """The file text of ``config``; raises ConfigError for a configuration that cannot be saved."""
    db = database()
    sections: dict[str, list[str]] = {s: [] for s in PARAMETER_SECTIONS}
    params: list[tuple[Parameter, int | float]] = []
    for key, value in config.parameters.items():
        try:
            param = db.get(key)
            value = param.validate(value)
        except ParameterError as exc:
            raise ConfigError(str(exc)) from None
        if not _savable(param):
            raise ConfigError(f"{param.label}: read-only parameter, not saved in a configuration file")
        params.append((param, value))
    for param, value in sorted(params, key=lambda pv: pv[0].index):
        sections[parameter_section(param)].append(f"{param.label} = {_param_value(param, value)}")
    uses_laws = any(p.type in LAW_TYPES for c in config.curves for p in c.fix_points)
    version = zbc_drive.DRIVE_FORMAT if config.drive else LAW_FORMAT if uses_laws else 1
    out = [f"{MAGIC}{version}", "# see docs/formats/zbc.md", ""]
    for name in PARAMETER_SECTIONS:
        out.append(f"[{name}]")
        out.extend(sections[name])
        out.append("")
    if config.drive:
        try:
            out.extend(zbc_drive.section_lines(config.drive))
        except ValueError as exc:
            raise ConfigError(str(exc)) from None
    for entry in config.arrays:
        out.append(f"[array {entry.name}]")
        out.append(f"size = {len(entry.values)}")
        if entry.curve is not None:
            out.append(f"curve = {entry.curve}")
        for k in range(0, len(entry.values), VALUES_PER_LINE):
            chunk = entry.values[k:k + VALUES_PER_LINE]
            for v in chunk:
                if isinstance(v, bool) or not isinstance(v, int) or not INT32_MIN <= v <= INT32_MAX:
                    raise ConfigError(f"array {entry.name}: {v!r} is not a 32-bit integer")
            out.append("values = " + " ".join(str(v) for v in chunk))
        out.append("")
    for curve in config.curves:
        out.append(f"[curve {curve.name}]")
        for key in CURVE_KEYS:
            value = getattr(curve, key)
            if key == "interpolation":
                text = "yes" if value else "no"
            elif key == "curve_type":
                text = CurveType(value).name
            else:
                text = _num(value)
            out.append(f"{key} = {text}")
        for p in curve.fix_points:
            out.append(f"point = {_num(p.master)}, {_num(p.slave)}, {p.type}")
        for pair in curve.start_stop_pairs:
            out.append(f"pair = {_num(pair.start)}, {_num(pair.stop)}")
        out.append("")
    out.append("[end]")
    return "\n".join(out) + "\n"


def write_config(path: str | Path, config: ConfigFile) -> None:
    """Save atomically.  The text is read back first, so a file is never written that cannot be opened."""
    text = config_text(config)
    read_config(text)
    atomic_write_text(path, text)


# -- reading -------------------------------------------------------------------------------------------------------
def _parse_number(text: str, line: int, what: str) -> int | float:
    text = text.strip()
    if _INT_RE.fullmatch(text) and len(text) <= 30:  # longer: float() says inf (int() would refuse > 4300 digits)
        return int(text)
    if _FLOAT_RE.fullmatch(text):
        value = float(text)
        if math.isfinite(value):
            return value
    raise ConfigError(f"{what}: {text!r} is not a number", line)


@dataclass
class _CurveSection:
    name: str
    line: int
    keys: dict[str, tuple[str, int]] = field(default_factory=dict)
    points: list[tuple[str, int]] = field(default_factory=list)
    pairs: list[tuple[str, int]] = field(default_factory=list)


@dataclass
class _ArraySection:
    name: str
    line: int
    size: int | None = None
    size_line: int = 0
    curve: str | None = None
    curve_line: int = 0
    values: list[int] = field(default_factory=list)
    value_lines: list[tuple[int, int]] = field(default_factory=list)  # (first element index, line)

    def line_of(self, index: int) -> int:
        found = self.line
        for first, line in self.value_lines:
            if first <= index:
                found = line
        return found


class _Reader:
    def __init__(self, text: str, source: str | None) -> None:
        self.text = text
        self.source = source
        self.db = database()
        self.config = ConfigFile()
        self.param_lines: dict[str, int] = {}
        self.drive_lines: dict[str, int] = {}
        self.arrays: list[_ArraySection] = []
        self.curves: list[_CurveSection] = []
        self.seen_sections: set[str] = set()
        self.array_names: set[str] = set()  # a set: a list scan per section made 40 000 arrays take 100 s
        self.curve_names: set[str] = set()
        self.elements = 0  # declared sizes so far, refused beyond the controller's array memory
        self.version = 1

    def error(self, message: str, line: int) -> ConfigError:
        return ConfigError(message, line, self.source)

    def run(self) -> ConfigFile:
        lines = self.text.split("\n")
        if lines and lines[-1] == "":
            lines.pop()
        if not lines:
            raise self.error("empty file, not a motiontool configuration file", 1)
        self._check_format(lines[0])
        section: str | None = None
        current: _ArraySection | _CurveSection | None = None
        ended = False
        for number, raw in enumerate(lines[1:], start=2):
            line = raw.rstrip("\r")
            stripped = line.strip()
            if not stripped or stripped.startswith("#"):
                continue
            if ended:
                raise self.error("text after the [end] line", number)
            if stripped.startswith("["):
                if not line.endswith("]") or line.startswith(" "):
                    raise self.error(f"malformed section header {stripped!r}", number)
                if current is not None:
                    self._close(current)
                section, current = self._open_section(line[1:-1], number)
                if section == "end":
                    ended = True
                continue
            if section is None:
                raise self.error("line outside a section", number)
            if " = " not in line and not line.rstrip().endswith(" ="):
                raise self.error(f"expected 'key = value', got {stripped!r}", number)
            key, _, value = line.partition(" =")
            key = key.strip()
            value = value[1:] if value.startswith(" ") else value
            if section in PARAMETER_SECTIONS:
                self._parameter(section, key, value, number)
            elif section == zbc_drive.SECTION:
                zbc_drive.read_line(self.config.drive, key, value, number, self.drive_lines, self.error)
            elif isinstance(current, _ArraySection):
                self._array_line(current, key, value, number)
            elif isinstance(current, _CurveSection):
                self._curve_line(current, key, value, number)
        if not ended:
            raise self.error("the file ends without the [end] line (truncated?)", len(lines))
        self._link()
        return self.config

    def _check_format(self, first: str) -> None:
        first = first.rstrip("\r").lstrip("\ufeff")
        if not first.startswith(MAGIC):
            raise self.error(f"not a motiontool configuration file: the first line must be '{MAGIC}N'", 1)
        version = first[len(MAGIC):].strip()
        if not re.fullmatch(r"[0-9]{1,9}", version):
            raise self.error(f"format version {version!r} is not a number", 1)
        if int(version) > FORMAT_VERSION:
            raise self.error(f"format {int(version)} is newer than this motiontool reads (up to {FORMAT_VERSION}); "
                             "update motiontool", 1)
        if int(version) < 1:
            raise self.error(f"unknown format version {version}", 1)
        self.version = int(version)

    def _open_section(self, inner: str, number: int) -> tuple[str, _ArraySection | _CurveSection | None]:
        if inner in (*PARAMETER_SECTIONS, zbc_drive.SECTION, "end"):
            if inner in self.seen_sections:
                raise self.error(f"section [{inner}] appears twice", number)
            if inner == zbc_drive.SECTION and self.version < zbc_drive.DRIVE_FORMAT:
                raise self.error(f"section [{inner}] needs format {zbc_drive.DRIVE_FORMAT}, the file says format "
                                 f"{self.version}", number)
            self.seen_sections.add(inner)
            return inner, None
        kind, sep, name = inner.partition(" ")
        if kind == "array" and sep:
            if name in self.array_names:
                raise self.error(f"array {name!r} appears twice", number)
            self.array_names.add(name)
            entry = _ArraySection(name, number)
            self.arrays.append(entry)
            return "array", entry
        if kind == "curve" and sep:
            if name in self.curve_names:
                raise self.error(f"curve {name!r} appears twice", number)
            self.curve_names.add(name)
            entry2 = _CurveSection(name, number)
            self.curves.append(entry2)
            return "curve", entry2
        raise self.error(f"unknown section [{inner}] (global, axis, user, fc300, array NAME, curve NAME, "
                         "end)", number)

    def _parameter(self, section: str, key: str, value: str, number: int) -> None:
        m = _PARAM_KEY_RE.fullmatch(key)
        if not m:
            raise self.error(f"expected a parameter number like '32-60 KPROP', got {key!r}", number)
        try:
            param = self.db.get(m.group(1))
        except ParameterError:
            raise self.error(f"unknown parameter {m.group(1)}", number) from None
        if m.group(2) and (param.name or "").upper() != m.group(2).upper():
            raise self.error(f"parameter {param.number} is {param.name or 'unnamed'}, not {m.group(2)}", number)
        if not _savable(param):
            raise self.error(f"{param.label}: read-only parameter, cannot be restored from a file", number)
        home = parameter_section(param)
        if home != section:
            raise self.error(f"{param.label} belongs in [{home}], not [{section}]", number)
        if param.number in self.config.parameters:
            raise self.error(f"{param.label} given twice (first on line {self.param_lines[param.number]})", number)
        try:
            self.config.parameters[param.number] = param.validate(value.strip())
        except ParameterError as exc:
            raise self.error(str(exc), number) from None
        self.param_lines[param.number] = number

    def _array_line(self, entry: _ArraySection, key: str, value: str, number: int) -> None:
        if key == "size":
            if entry.size is not None:
                raise self.error(f"array {entry.name}: size given twice", number)
            if entry.values:
                raise self.error(f"array {entry.name}: size must come before the values", number)
            text = value.strip()
            if not re.fullmatch(r"[0-9]{1,9}", text) or int(text) < 1:
                raise self.error(f"array {entry.name}: size {text!r} is not a positive integer", number)
            self.elements += int(text)
            if self.elements > MAX_ARRAY_ELEMENTS:  # before the values are read (decisions R15)
                raise self.error(f"array {entry.name}: size = {text} takes the arrays to {self.elements} elements, "
                                 f"more than the controller's array memory of {MAX_ARRAY_ELEMENTS}", number)
            entry.size, entry.size_line = int(text), number
        elif key == "curve":
            if entry.curve is not None:
                raise self.error(f"array {entry.name}: curve given twice", number)
            entry.curve, entry.curve_line = value, number
        elif key == "values":
            if entry.size is None:
                raise self.error(f"array {entry.name}: values before the size line", number)
            entry.value_lines.append((len(entry.values), number))
            for word in value.split():
                if not _INT_RE.fullmatch(word):
                    raise self.error(f"array {entry.name}: {word!r} is not an integer", number)
                v = int(word) if len(word) <= 12 else INT32_MAX + 1
                if not INT32_MIN <= v <= INT32_MAX:
                    raise self.error(f"array {entry.name}: {word} does not fit a 32-bit long", number)
                entry.values.append(v)
            if len(entry.values) > entry.size:
                raise self.error(f"array {entry.name}: more than size = {entry.size} values", number)
        else:
            raise self.error(f"array {entry.name}: unknown key {key!r} (size, curve, values)", number)

    def _curve_line(self, entry: _CurveSection, key: str, value: str, number: int) -> None:
        if key == "point":
            entry.points.append((value, number))
        elif key == "pair":
            entry.pairs.append((value, number))
        elif key in CURVE_KEYS:
            if key in entry.keys:
                raise self.error(f"curve {entry.name}: {key} given twice", number)
            entry.keys[key] = (value.strip(), number)
        else:
            raise self.error(f"curve {entry.name}: unknown key {key!r}", number)

    def _close(self, entry: _ArraySection | _CurveSection) -> None:
        if isinstance(entry, _ArraySection):
            if entry.size is None:
                raise self.error(f"array {entry.name}: no size line", entry.line)
            if len(entry.values) != entry.size:
                raise self.error(f"array {entry.name}: size = {entry.size} but {len(entry.values)} values follow "
                                 "(truncated?)", entry.size_line)
            self.config.arrays.append(ArrayEntry(entry.name, entry.values, entry.curve))
        else:
            self.config.curves.append(self._build_curve(entry))

    def _build_curve(self, entry: _CurveSection) -> Curve:
        name = entry.name
        for key in CURVE_KEYS:
            if key not in entry.keys:
                raise self.error(f"curve {name}: missing key {key}", entry.line)
        kw: dict[str, object] = {}
        for key in _NUMBER_KEYS + ("master_length",):
            text, line = entry.keys[key]
            kw[key] = _parse_number(text, line, f"curve {name}: {key}")
        text, line = entry.keys["intervals"]
        if not _INT_RE.fullmatch(text) or len(text) > 12:
            raise self.error(f"curve {name}: intervals {text!r} is not an integer", line)
        if int(text) > MAX_INTERVALS:  # never computes 10^8 interpolation points (decisions R15)
            raise self.error(f"curve {name}: intervals = {int(text)} is more than the controller's array memory "
                             f"allows ({MAX_INTERVALS})", line)
        kw["intervals"] = int(text)
        text, line = entry.keys["interpolation"]
        if text not in ("yes", "no"):
            raise self.error(f"curve {name}: interpolation must be yes or no, not {text!r}", line)
        kw["interpolation"] = text == "yes"
        text, line = entry.keys["curve_type"]
        if text not in CurveType.__members__:
            raise self.error(f"curve {name}: curve_type {text!r} is not one of {', '.join(CurveType.__members__)}",
                             line)
        kw["curve_type"] = CurveType[text]
        points = []
        for text, line in entry.points:
            parts = [p.strip() for p in text.split(",")]
            if len(parts) != 3:
                raise self.error(f"curve {name}: point must be 'master, slave, TYPE', got {text.strip()!r}", line)
            if parts[2] not in FIX_POINT_TYPES:
                raise self.error(f"curve {name}: fix point type {parts[2]!r} is not one of "
                                 f"{', '.join(FIX_POINT_TYPES)}", line)
            if parts[2] in LAW_TYPES and self.version < LAW_FORMAT:
                raise self.error(f"curve {name}: fix point type {parts[2]} (a motion law) needs format "
                                 f"{LAW_FORMAT}, the file says format {self.version}", line)
            points.append(FixPoint(_parse_number(parts[0], line, f"curve {name}: point master"),
                                   _parse_number(parts[1], line, f"curve {name}: point slave"), parts[2]))
        pairs = []
        for text, line in entry.pairs:
            parts = [p.strip() for p in text.split(",")]
            if len(parts) != 2:
                raise self.error(f"curve {name}: pair must be 'start, stop', got {text.strip()!r}", line)
            pairs.append(StartStopPair(_parse_number(parts[0], line, f"curve {name}: pair start"),
                                       _parse_number(parts[1], line, f"curve {name}: pair stop")))
        try:
            return Curve(name, fix_points=tuple(points), start_stop_pairs=tuple(pairs), **kw)  # type: ignore[arg-type]
        except CurveError as exc:
            raise self.error(f"curve {name}: {exc}", self._curve_error_line(entry, exc)) from None

    @staticmethod
    def _curve_error_line(entry: _CurveSection, exc: CurveError) -> int:
        if exc.field == "fix_points":
            index = exc.point
            if index is None:
                m = re.match(r"point (\d+)", exc.message)
                index = int(m.group(1)) - 1 if m else None
            if index is not None and 0 <= index < len(entry.points):
                return entry.points[index][1]
            return entry.points[0][1] if entry.points else entry.line
        if exc.field == "start_stop_pairs":
            m = re.match(r"pair (\d+)", exc.message)
            k = int(m.group(1)) if m else 0
            return entry.pairs[k][1] if k < len(entry.pairs) else entry.line
        if exc.field in entry.keys:
            return entry.keys[exc.field][1]
        return entry.line

    def _link(self) -> None:
        """Every curve has exactly one curve array, and that array holds that curve."""
        sections = {c.name: c for c in self.curves}
        curves = {c.name: c for c in self.config.curves}
        linked: dict[str, _ArraySection] = {}
        for entry in self.arrays:
            if entry.curve is None:
                continue
            if entry.curve not in curves:
                raise self.error(f"array {entry.name}: no [curve {entry.curve}] section", entry.curve_line)
            if entry.curve in linked:
                raise self.error(f"curve {entry.curve} already has array {linked[entry.curve].name}",
                                 entry.curve_line)
            linked[entry.curve] = entry
            try:
                decoded = decode(entry.values)
            except CurveArrayError as exc:
                raise self.error(f"array {entry.name}: not a valid curve array: {exc}",
                                 entry.line_of(exc.index)) from None
            differs = _difference(curves[entry.curve], decoded)
            if differs:
                raise self.error(f"curve {entry.curve} and its array {entry.name} differ: {differs}",
                                 sections[entry.curve].line)
        for name, section in sections.items():
            if name not in linked:
                raise self.error(f"curve {name}: no array marked 'curve = {name}'", section.line)


def _difference(curve: Curve, decoded) -> str | None:
    """The first stored field in which the curve definition and its decoded array disagree, else None."""
    checks = [("name", curve.name, decoded.name), ("master_length", curve.master_length, decoded.master_length),
              ("curve_type", curve.curve_type, decoded.curve_type),
              ("interpolation", curve.interpolation, decoded.interpolation),
              ("slave_stop_position", curve.slave_stop_position, decoded.slave_stop_position),
              ("correction_start", curve.correction_start, decoded.correction_start),
              ("correction_end", curve.correction_end, decoded.correction_end),
              ("max_correction", curve.max_correction, decoded.max_correction),
              ("cycles_per_min", max(1, round(curve.cycles_per_min)), decoded.cycles_per_min),
              ("master_marker_pos", curve.master_marker_pos, decoded.master_marker_pos),
              ("slave_marker_pos", curve.slave_marker_pos, decoded.slave_marker_pos),
              ("fix_points", curve.fix_points, decoded.fix_points),
              ("start_stop_pairs", curve.start_stop_pairs, decoded.start_stop_pairs)]
    if curve.interpolation:
        checks.append(("intervals", curve.intervals, decoded.intervals))
    for name, ours, theirs in checks:
        if ours != theirs:
            return f"{name} {ours!r} in the curve, {theirs!r} in the array"
    return None


def read_config(source: str | Path) -> ConfigFile:
    """Read a .zbc/.cnf file.  ``source`` is a Path, a path string, or the file text (a str with a newline)."""
    if isinstance(source, str) and "\n" in source:
        return _Reader(source, None).run()
    path = Path(source)
    try:
        data = read_bytes(path, MAX_BYTES, "configuration file")
    except OSError as exc:
        raise ConfigError(f"cannot read: {exc.strerror or exc}", 0, str(path)) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ConfigError("not a text file (invalid UTF-8)", data[:exc.start].count(b"\n") + 1, str(path)) from None
    return _Reader(text, str(path)).run()
