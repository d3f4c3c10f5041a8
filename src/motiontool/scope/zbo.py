"""Oscilloscope files (.zbo, docs/formats/zbo.md): versioned JSON with the configuration and, unless saved
"without data", each curve's samples as base64 of zlib-compressed little-endian float64 (ide-spec 7.7,
DG 5349-5355). The reader never evaluates anything; every problem names the file and the JSON path.
"""

from __future__ import annotations

import base64
import binascii
import json
import zlib
from dataclasses import asdict, fields
from pathlib import Path
from typing import NoReturn

import numpy as np

from motiontool.fileio import MiB, atomic_write_text, read_text
from motiontool.scope import select
from motiontool.scope.buffer import RingBuffer
from motiontool.scope.curves import (
    FORMATS,
    INTERPOLATIONS,
    METHODS,
    VARIANTS,
    AxisSettings,
    Curve,
    Group,
    Scaling,
    Scope,
    Settings,
    Source,
)

MAGIC = "motiontool oscilloscope"
VERSION = 2                 # the newest version read and written; 2 added source.select (docs/formats/zbo.md)
SELECT_VERSION = 2          # a file is written as version 1 unless a curve has a byte/word/bit selection
ENCODING = "f8le-zlib-base64"
MAX_SAMPLES = 10_000_000    # per curve, checked before allocating: a ring buffer takes 32 bytes a sample
MAX_FILE_SAMPLES = 20_000_000  # all curves of a file together (640 MB of buffers; decisions R16)
MAX_BYTES = 1024 * MiB      # ten million samples per curve are some 200 MiB (decisions R4)


OPTIONAL = {"controller": int, "share": str, "bit_mask": int, "select": str}   # fields that may be null


class ZboError(ValueError):
    pass


def encode_array(a: np.ndarray) -> str:
    return base64.b64encode(zlib.compress(np.asarray(a, dtype="<f8").tobytes(), 6)).decode("ascii")


def decode_array(text: object, count: int, where: str) -> np.ndarray:
    if not isinstance(text, str):
        raise ZboError(f"{where}: expected base64 text")
    inflate = zlib.decompressobj()
    try:
        # never more than the declared count is inflated: a 1.3 MB bomb of 1 GiB stops at count * 8 bytes
        raw = inflate.decompress(base64.b64decode(text.encode("ascii"), validate=True), count * 8)
        if not inflate.eof and inflate.decompress(inflate.unconsumed_tail, 1):
            raise ZboError(f"{where}: inflates to more than the {count} values 'count' says")
    except (binascii.Error, zlib.error, UnicodeEncodeError, ValueError) as exc:
        if isinstance(exc, ZboError):
            raise
        raise ZboError(f"{where}: not {ENCODING} data ({exc})") from None
    if len(raw) != count * 8:
        raise ZboError(f"{where}: {len(raw) // 8} values, 'count' says {count}")
    return np.frombuffer(raw, dtype="<f8").astype(float)


def _source_dict(source: Source) -> dict:
    d = asdict(source)
    if d["select"] is None:     # absent in version 1: a file without selections stays readable by 1-readers
        del d["select"]
    return d


def scope_to_dict(scope: Scope, with_data: bool = True) -> dict:
    curves = []
    version = SELECT_VERSION if any(c.source.select for c in scope.curves) else 1
    for c in scope.curves:
        entry = {
            "name": c.name, "colour": c.colour, "unit": c.unit, "visible": c.visible, "active": c.active,
            "format": c.fmt, "interpolation": c.interpolation,
            "scaling": asdict(c.scaling) if c.scaling is not None else None,
            "range": [c.range_low, c.range_high], "smoothing": c.smoothing, "axis": asdict(c.axis),
            "first_of_set": c.first_of_set, "source": _source_dict(c.source), "capacity": c.buffer.capacity,
            "data": None,
        }
        if with_data:
            t, y = c.raw()
            entry["data"] = {"encoding": ENCODING, "count": int(t.size), "time_ms": encode_array(t),
                             "values": encode_array(y)}
        curves.append(entry)
    return {"format": MAGIC, "version": version, "variant": scope.variant, "settings": asdict(scope.settings),
            "cursors": list(scope.cursors), "pauses": list(scope.pauses),
            "groups": [asdict(g) for g in scope.groups], "curves": curves}


def dumps(scope: Scope, with_data: bool = True) -> str:
    return json.dumps(scope_to_dict(scope, with_data), indent=1, ensure_ascii=False, allow_nan=True) + "\n"


def save(scope: Scope, path: Path | str, with_data: bool = True) -> None:
    """File → Save / Save without Data. The text is read back before the atomic write."""
    text = dumps(scope, with_data)
    loads(text, str(path))
    atomic_write_text(path, text)


def load(path: Path | str) -> Scope:
    path = Path(path)
    try:
        text = read_text(path, MAX_BYTES, "oscilloscope file")
    except UnicodeDecodeError as exc:
        raise ZboError(f"{path}: not UTF-8 text (byte {exc.start})") from None
    return loads(text, str(path))


# --- reading -----------------------------------------------------------------------------------------------
def loads(text: str, name: str = "<zbo>") -> Scope:
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ZboError(f"{name}:{exc.lineno}:{exc.colno}: not JSON: {exc.msg}") from None
    except ValueError as exc:  # an integer of thousands of digits
        raise ZboError(f"{name}: not a valid oscilloscope file: {exc}") from None
    except RecursionError:
        raise ZboError(f"{name}: nested too deeply") from None
    r = _Reader(name)
    obj = r.dict(doc, "")
    if obj.get("format") != MAGIC:
        raise ZboError(f"{name}: not an oscilloscope file (no \"format\": \"{MAGIC}\")")
    version = obj.get("version")
    if not isinstance(version, int) or isinstance(version, bool) or version < 1:
        raise ZboError(f"{name}: version: expected a positive integer")
    if version > VERSION:
        raise ZboError(f"{name}: format version {version} is newer than this motiontool reads ({VERSION})")
    r.version = version
    variant = r.choice(obj, "variant", VARIANTS, "")
    scope = Scope(variant)
    scope.settings = r.dataclass(Settings, obj.get("settings", {}), "settings")
    cursors = r.list(obj.get("cursors", [None, None]), "cursors")
    if len(cursors) != 2:
        raise ZboError(f"{name}: cursors: expected [A, B]")
    scope.cursors = [r.number_or_none(v, f"cursors[{i}]") for i, v in enumerate(cursors)]
    scope.pauses = [r.number(v, f"pauses[{i}]") for i, v in enumerate(r.list(obj.get("pauses", []), "pauses"))]
    for i, g in enumerate(r.list(obj.get("groups", []), "groups")):
        group = r.dataclass(Group, g, f"groups[{i}]")
        if not group.name.strip():
            raise ZboError(f"{name}: groups[{i}].name: expected a non-empty name")
        try:
            scope.add_group(group)
        except ValueError as exc:
            raise ZboError(f"{name}: groups[{i}]: {exc}") from None
    names = set()
    for i, c in enumerate(r.list(obj.get("curves", []), "curves")):
        curve = r.curve(c, f"curves[{i}]")
        if curve.name in names:
            raise ZboError(f"{name}: curves[{i}].name: '{curve.name}' appears twice")
        names.add(curve.name)
        scope.curves.append(curve)
    return scope


class _Reader:
    def __init__(self, name: str):
        self.name = name
        self.version = VERSION
        self.samples = 0  # capacities of the curves read so far

    def fail(self, where: str, message: str) -> NoReturn:
        raise ZboError(f"{self.name}: {where}: {message}" if where else f"{self.name}: {message}")

    def dict(self, v, where) -> dict:
        if not isinstance(v, dict):
            self.fail(where, "expected an object")
        return v

    def list(self, v, where) -> list:
        if not isinstance(v, list):
            self.fail(where, "expected a list")
        return v

    def number(self, v, where) -> float:
        if isinstance(v, bool) or not isinstance(v, int | float):
            self.fail(where, "expected a number")
        return float(v)

    def number_or_none(self, v, where) -> float | None:
        return None if v is None else self.number(v, where)

    def choice(self, obj, key, options, where):
        v = obj.get(key)
        if v not in options:
            self.fail(f"{where}.{key}".lstrip("."), f"'{v}' is not one of {', '.join(options)}")
        return v

    def dataclass(self, cls, v, where):
        """Fill a dataclass from an object: known keys only, each of the default's type."""
        obj = self.dict(v, where)
        default = cls(**{f.name: "" for f in fields(cls) if f.name == "name"})
        values = {}
        for key, value in obj.items():
            if key not in {f.name for f in fields(cls)}:
                self.fail(f"{where}.{key}", "unknown key")
            current = getattr(default, key)
            if key in OPTIONAL:
                ok = value is None or (isinstance(value, OPTIONAL[key]) and not isinstance(value, bool))
            elif isinstance(current, bool):
                ok = isinstance(value, bool)
            elif isinstance(current, int | float):
                ok = isinstance(value, int | float) and not isinstance(value, bool) and (
                    isinstance(current, float) or isinstance(value, int))
            else:
                ok = isinstance(value, str)
            if not ok:
                self.fail(f"{where}.{key}", f"expected {OPTIONAL.get(key, type(current)).__name__}")
            values[key] = float(value) if isinstance(current, float) else value
        return cls(**{**{f.name: getattr(default, f.name) for f in fields(cls)}, **values})

    def curve(self, v, where) -> Curve:
        obj = self.dict(v, where)
        known = {"name", "colour", "unit", "visible", "active", "format", "interpolation", "scaling", "range",
                 "smoothing", "axis", "first_of_set", "source", "capacity", "data"}
        for key in obj:
            if key not in known:
                self.fail(f"{where}.{key}", "unknown key")
        name = obj.get("name")
        if not isinstance(name, str) or not name.strip():
            self.fail(f"{where}.name", "expected a non-empty name")
        c = Curve(name)
        for key in ("colour", "unit"):
            if not isinstance(obj.get(key, ""), str):
                self.fail(f"{where}.{key}", "expected text")
        c.colour, c.unit = obj.get("colour", c.colour), obj.get("unit", "")
        for key in ("visible", "active", "first_of_set"):
            if not isinstance(obj.get(key, True), bool):
                self.fail(f"{where}.{key}", "expected true or false")
            setattr(c, key, obj.get(key, getattr(c, key)))
        c.fmt = self.choice(obj, "format", FORMATS, where) if "format" in obj else c.fmt
        c.interpolation = self.choice(obj, "interpolation", INTERPOLATIONS, where) if "interpolation" in obj \
            else c.interpolation
        if obj.get("scaling") is not None:
            c.scaling = self.dataclass(Scaling, obj["scaling"], f"{where}.scaling")
        rng = self.list(obj.get("range", [None, None]), f"{where}.range")
        if len(rng) != 2:
            self.fail(f"{where}.range", "expected [low, high]")
        c.range_low, c.range_high = (self.number_or_none(x, f"{where}.range") for x in rng)
        smoothing = obj.get("smoothing", 0)
        if not isinstance(smoothing, int) or isinstance(smoothing, bool) or not 0 <= smoothing <= 10_000:
            self.fail(f"{where}.smoothing", "expected an integer 0..10000")
        c.smoothing = smoothing
        c.axis = self.dataclass(AxisSettings, obj.get("axis", {}), f"{where}.axis")
        source = self.dict(obj.get("source", {}), f"{where}.source")
        info = source.get("info", {})
        derived = source.get("derived")
        c.source = self.dataclass(Source, {k: v for k, v in source.items() if k not in ("info", "derived")},
                                  f"{where}.source")
        if c.source.method not in METHODS:
            self.fail(f"{where}.source.method", f"'{c.source.method}' is not one of {', '.join(METHODS)}")
        if "select" in source:
            if self.version < SELECT_VERSION:
                self.fail(f"{where}.source.select", f"needs format version {SELECT_VERSION} (file says {self.version})")
            try:
                c.source.select = select.canonical(c.source.select)
            except ValueError as exc:
                self.fail(f"{where}.source.select", str(exc))
        c.source.info = self.dict(info, f"{where}.source.info")
        c.source.derived = None if derived is None else self.dict(derived, f"{where}.source.derived")
        capacity = obj.get("capacity", 10_000)
        if not isinstance(capacity, int) or isinstance(capacity, bool) or not 1 <= capacity <= MAX_SAMPLES:
            self.fail(f"{where}.capacity", f"expected an integer 1..{MAX_SAMPLES}")
        self.samples += capacity
        if self.samples > MAX_FILE_SAMPLES:
            self.fail(f"{where}.capacity", f"the curves' capacities add up to {self.samples}, more than the "
                                           f"{MAX_FILE_SAMPLES} samples a file may hold")
        data = obj.get("data")
        if data is not None:
            data = self.dict(data, f"{where}.data")
            if data.get("encoding") != ENCODING:
                self.fail(f"{where}.data.encoding", f"expected '{ENCODING}'")
            count = data.get("count")
            if not isinstance(count, int) or isinstance(count, bool) or not 0 <= count <= capacity:
                self.fail(f"{where}.data.count", f"expected an integer 0..capacity ({capacity})")
            t = decode_array(data.get("time_ms"), count, f"{self.name}: {where}.data.time_ms")
            y = decode_array(data.get("values"), count, f"{self.name}: {where}.data.values")
            c.buffer = RingBuffer(capacity)
            c.buffer.extend(t, y)
        else:
            c.buffer = RingBuffer(capacity)
        return c
