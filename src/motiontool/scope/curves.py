"""The oscilloscope's document: curves, groups and settings (ide-spec 6d, 6e, 6g). No Qt.

A curve is named "Axis: Name [Index]" (DG 5343-5345) when it comes from a SYSVAR index, e.g.
"1: REG_ACTPOS [4097]"; a curve that records one byte, word or bit of the value adds the APOSS suffix,
"1: REG_STAT [4104].b2" (scope/select.py). Its samples live in a RingBuffer (the FIFO "max number of
samples", DG 5995-6001); display properties (scaling, range validation, smoothing) change what is shown, never
the stored data (DG 5125-5161). A selection is part of the source: it decides what is stored.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from motiontool.scope.buffer import DEFAULT_CAPACITY, RingBuffer
from motiontool.scope.numbers import value_text

PALETTE = ["#e6194b", "#3cb44b", "#4363d8", "#f58231", "#911eb4", "#42d4f4", "#f032e6", "#9a6324",
           "#808000", "#000075", "#a9a9a9", "#bfef45"]
VARIANTS = ("free_run", "polling", "single_shot", "testsetp", "tune")
METHODS = ("free_run", "single_shot", "polled", "variable", "testsetp", "derived", "file")
FORMATS = ("decimal", "hexadecimal", "character")
INTERPOLATIONS = ("lines", "values", "spline")
AXIS_BASE = 0x1000


def signal_label(signal: str, axis: int = 1) -> str:
    """The manual's curve name for a signal: "Axis: Name [Index]" for SYSVAR indices, "Axis: Name" else.
    Names for indices come from the controller's upload (`names`), here only the common ones are known."""
    text = str(signal).strip()
    try:
        index = int(text, 0)
    except ValueError:
        return f"{axis}: {text.upper()}"
    return f"{axis}: {KNOWN_INDICES.get(index, 'SYSVAR')} [{text}]"


KNOWN_INDICES = {0x1001: "REG_ACTPOS", 0x1002: "REG_COMPOS", 0x1003: "REG_ACTVEL", 0x1004: "REG_COMVEL",
                 0x1005: "REG_SPEEDREF", 0x1006: "REG_TRACKERR", 0x1007: "REG_AXEND", 0x1008: "REG_STAT",
                 0x1017: "sys_clock", 0x01250001: "REG_ACTPOS", 0x01250002: "REG_COMPOS",
                 0x01250006: "REG_TRACKERR"}


@dataclass
class Scaling:
    """Display → Enable scaling (DG 5125-5129): "(y-offset)*scale" or "(y*scale)-offset"."""
    offset: float = 0.0
    scale: float = 1.0
    offset_first: bool = True

    def __post_init__(self):
        self.offset, self.scale = float(self.offset), float(self.scale)

    def apply(self, y):
        return (y - self.offset) * self.scale if self.offset_first else y * self.scale - self.offset


@dataclass
class AxisSettings:
    """Axis tab (DG 5180-5225): min height, automatic or user range, zero options, shared axis."""
    min_height: float = 1.0
    automatic: bool = True
    low: float = 0.0
    high: float = 1.0
    center_zero: bool = False
    zero_mark: bool = False
    share: str | None = None    # name of the curve whose Y axis this one uses

    def __post_init__(self):
        self.min_height, self.low, self.high = float(self.min_height), float(self.low), float(self.high)


@dataclass
class Source:
    """Where a curve's data comes from (Source tab, DG 5227-5236)."""
    method: str = "free_run"    # one of METHODS
    signal: str = ""            # link signal: "APOS", "4097", "KPROP", "0x01250001", a variable "a[3]"
    group: str = ""
    controller: int | None = 1
    interface: str = ""
    bit_mask: int | None = None
    select: str | None = None   # byte/word/bit of the 32-bit value: "b2", "sw1", "3" … (scope/select.py)
    derived: dict | None = None  # derived.DerivedSpec as a dict
    info: dict = field(default_factory=dict)  # e.g. the recording, test parameters of an old testrun


@dataclass
class Curve:
    name: str
    source: Source = field(default_factory=Source)
    colour: str = PALETTE[0]
    unit: str = ""
    visible: bool = True
    active: bool = True
    fmt: str = "decimal"
    interpolation: str = "lines"
    scaling: Scaling | None = None
    range_low: float | None = None
    range_high: float | None = None
    smoothing: int = 0          # w: centred moving average over 2w+1 points (DG 5143-5161)
    axis: AxisSettings = field(default_factory=AxisSettings)
    first_of_set: bool = False  # first curve of a TESTSETP set: grey background (DG 5343)
    buffer: RingBuffer = field(default_factory=RingBuffer)

    # --- data as shown ------------------------------------------------------------------------------------
    def raw(self) -> tuple[np.ndarray, np.ndarray]:
        return self.buffer.arrays()

    def scaled(self, y):
        y = np.asarray(y, dtype=float)
        return self.scaling.apply(y) if self.scaling is not None else y

    def display(self) -> tuple[np.ndarray, np.ndarray]:
        """Chart data: scaled, then smoothed (display only)."""
        t, y = self.raw()
        y = self.scaled(y)
        if self.smoothing > 0:
            y = smooth(y, self.smoothing)
        return t, y

    def stats(self) -> tuple[float, float, float] | None:
        """Last, minimum, maximum of the scaled values (the list's columns, DG 5007-5028); None when empty."""
        t, y = self.raw()
        if y.size == 0:
            return None
        y = self.scaled(y)
        return float(y[-1]), float(y.min()), float(y.max())

    def out_of_range(self, value: float) -> bool:
        """Range validation (DG 5131-5141): outside the low/high bound (either may be blank)."""
        return (self.range_low is not None and value < self.range_low) or (
            self.range_high is not None and value > self.range_high)

    def format_value(self, value: float) -> str:
        if self.fmt == "hexadecimal" and self.interpolation == "values":
            return f"0x{int(value) & 0xFFFFFFFF:X}"
        if self.fmt == "character" and self.interpolation == "values":
            return "".join(chr(b) if 32 <= b < 127 else "." for b in int(value).to_bytes(4, "big", signed=True))
        return value_text(value)

    def y_range(self) -> tuple[float, float]:
        """Axis → Scaling (DG 5191-5203): data min/max padded ~10 %, at least Min Height; centre zero."""
        a = self.axis
        if not a.automatic:
            lo, hi = a.low, a.high
        else:
            st = self.stats()
            lo, hi = (st[1], st[2]) if st else (0.0, 0.0)
            pad = (hi - lo) * 0.1
            lo, hi = lo - pad, hi + pad
        if a.center_zero:
            m = max(abs(lo), abs(hi))
            lo, hi = -m, m
        if hi - lo < a.min_height:
            mid = (hi + lo) / 2
            lo, hi = mid - a.min_height / 2, mid + a.min_height / 2
        return lo, hi


def smooth(y: np.ndarray, w: int) -> np.ndarray:
    """Centred moving average over 2w+1 points; near the ends the window shrinks to the points there."""
    n = y.size
    if w <= 0 or n == 0:
        return y
    c = np.concatenate([[0.0], np.cumsum(y)])
    i = np.arange(n)
    lo = np.maximum(i - w, 0)
    hi = np.minimum(i + w + 1, n)
    return (c[hi] - c[lo]) / (hi - lo)


@dataclass
class Group:
    """A Free Run group is one PDO mapping, a Single Shot group one TESTSETP recording (DG 5386-5397)."""
    name: str
    method: str = "free_run"          # free_run | single_shot | polled | testsetp
    controller: int | None = 1
    interval_ms: int = 1              # PDO event time or sample interval
    destination: str = "DYNMEM"       # Single Shot storage: dynamic memory or a user array
    cyclic: bool = False
    count: int = 1000                 # Single Shot sets; 0 = fill available space
    active: bool = True


OTHER_CURVES = "Other Curves"   # the fixed group for polled, derived and file curves (DG 4821-4848)


@dataclass
class Settings:
    """Settings → Oscilloscope (DG 5963-6001)."""
    poll_ms: int = 100
    default_samples: int = DEFAULT_CAPACITY
    relative_origin: bool = False     # Shift to 0 initial state (a new window turns it on, decision S32)
    min_length_ms: float = 1000.0
    bus_bitrate: int = 125_000        # for the polling load estimate (decisions in scope/acquisition.py)


class Scope:
    """All curves and groups of one oscilloscope window, in list order."""

    def __init__(self, variant: str = "free_run"):
        if variant not in VARIANTS:
            raise ValueError(f"unknown oscilloscope variant '{variant}' ({', '.join(VARIANTS)})")
        self.variant = variant
        self.groups: list[Group] = []
        self.curves: list[Curve] = []
        self.settings = Settings()
        self.cursors: list[float | None] = [None, None]     # A, B times (ms)
        self.pauses: list[float] = []                        # red bars where a paused run resumed (DG 5943)

    def curve(self, name: str) -> Curve:
        for c in self.curves:
            if c.name == name:
                return c
        raise KeyError(f"no curve '{name}'")

    def group(self, name: str) -> Group:
        for g in self.groups:
            if g.name == name:
                return g
        raise KeyError(f"no group '{name}'")

    def add_group(self, group: Group) -> Group:
        if any(g.name == group.name for g in self.groups) or group.name == OTHER_CURVES:
            raise ValueError(f"a group '{group.name}' exists already")
        self.groups.append(group)
        return group

    def unique_name(self, name: str) -> str:
        names = {c.name for c in self.curves}
        if name not in names:
            return name
        n = 2
        while f"{name} ({n})" in names:
            n += 1
        return f"{name} ({n})"

    def add_curve(self, curve: Curve, after: str | None = None) -> Curve:
        curve.name = self.unique_name(curve.name)
        if curve.buffer.capacity != self.settings.default_samples and len(curve.buffer) == 0:
            curve.buffer = RingBuffer(self.settings.default_samples)
        if curve.colour == PALETTE[0]:
            curve.colour = self._free_colour()
        if after is not None:
            i = [c.name for c in self.curves].index(after)
            self.curves.insert(i + 1, curve)
        else:
            self.curves.append(curve)
        return curve

    def _free_colour(self) -> str:
        """The first palette colour no curve has (counting curves repeated colours after a removal), else the
        next in turn."""
        used = {c.colour for c in self.curves}
        return next((c for c in PALETTE if c not in used), PALETTE[len(self.curves) % len(PALETTE)])

    def rename_curve(self, old: str, new: str) -> str:
        """Rename a curve (made unique) and every reference to it: shared axes and derived curves' inputs."""
        curve = self.curve(old)
        if new == old:
            return old
        curve.name = ""
        new = self.unique_name(new)
        curve.name = new
        for c in self.curves:
            if c.axis.share == old:
                c.axis.share = new
            spec = c.source.derived
            if spec:
                for key in ("base", "second"):
                    if spec.get(key) == old:
                        spec[key] = new
                if isinstance(spec.get("variables"), dict):
                    spec["variables"] = {k: new if v == old else v for k, v in spec["variables"].items()}
        return new

    def remove_curve(self, name: str) -> None:
        self.curves.remove(self.curve(name))
        for c in self.curves:
            if c.axis.share == name:
                c.axis.share = None

    def members(self, group: str) -> list[Curve]:
        return [c for c in self.curves if c.source.group == group]

    def set_group_active(self, name: str, active: bool) -> None:
        """Single Shot: only one group per controller can record; enabling one disables the other
        (DG 5865: "If a second group is selected for the same controller, then the first group will be
        automatically deselected")."""
        target = self.group(name)
        target.active = active
        if active and target.method == "single_shot":
            for g in self.groups:
                if g is not target and g.method == "single_shot" and g.controller == target.controller:
                    g.active = False

    def shared_root(self, name: str) -> str:
        """The curve whose axis `name` finally uses: shares chain, C→B→A means C uses A (DG 5207-5225)."""
        seen = [name]
        current = self.curve(name)
        while current.axis.share is not None and current.axis.share not in seen:
            seen.append(current.axis.share)
            try:
                current = self.curve(current.axis.share)
            except KeyError:
                break
        return current.name

    def clear_data(self) -> None:
        """Delete data: every curve's samples, hidden ones too (DG 4628)."""
        for c in self.curves:
            c.buffer.clear()
        self.pauses.clear()

    def time_span(self) -> tuple[float, float] | None:
        spans = [(c.raw()[0][0], c.raw()[0][-1]) for c in self.curves if len(c.buffer)]
        if not spans:
            return None
        return min(s[0] for s in spans), max(s[1] for s in spans)
