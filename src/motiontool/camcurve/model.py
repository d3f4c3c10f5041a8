"""CAM curve model: fix points, start/stop pairs and the curve data of the CAM editor's Curve Data card.

Qt-free: imported by the controller kernel and by the CAM editor alike (docs/architecture.md rule 2).

Sources: Design Guide (seed 000) "CAM Control" L1342-1750 and the CAM-Editor chapter L3467-4074;
docs/formats/cam-array.md for the controller array these values are stored in.

Units: master positions in MU, slave positions in UU.  Velocities are UU/MU, accelerations UU/MU².
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import IntEnum

import numpy as np

#: Fix point types [DG L3998-4022]: Curve, Tangent, Trapezoid, 3'rd order; then, beyond the manual, the
#: VDI 2143 motion laws of camcurve.motionlaws (the segment ending at such a point follows the law, decision C10).
LAW_TYPES = ("P345", "MSIN", "CYCL", "MTRAP", "HARM")
FIX_POINT_TYPES = ("C", "T", "CZ", "C3", *LAW_TYPES)
#: Fix point type code stored in the controller array (our choice, docs/formats/cam-array.md); laws 4..8.
FIX_POINT_TYPE_CODES = {"C": 0, "T": 1, "CZ": 2, "C3": 3, "P345": 4, "MSIN": 5, "CYCL": 6, "MTRAP": 7, "HARM": 8}

MAX_NAME_LENGTH = 16  # "Names may be up to 16 characters long" [DG L3696]
MAX_USER_PAIRS = 25  # "A maximum of 25 Start Stop point pairs can be defined" [DG L4048]
MIN_FIX_POINTS_ARRAY = 4  # curve info FixPointNo "min 4" (cam-array-layout.md)
#: The controller's array memory in elements (kernel/arrays.py MAX_ARRAY_ELEMENTS, error 175): one curve array
#: holds its interpolation points, so no curve has more intervals (decisions R15).
MAX_ARRAY_ELEMENTS = 1_000_000
MAX_INTERVALS = MAX_ARRAY_ELEMENTS - 1
#: The curve array holds whole cycles per minute (at least 1): a tiny value only made infinite interval times.
CYCLES_PER_MIN = (1, 2 ** 31 - 1)

# segment kinds produced by segment_kinds()
LINE, SPLINE, TRAPEZOID, CUBIC, LAW = "line", "spline", "trapezoid", "cubic", "law"


class CurveError(ValueError):
    """An invalid curve definition; ``field`` names the offending Curve field."""

    def __init__(self, field: str, message: str, point: int | None = None) -> None:
        super().__init__(f"{field}: {message}")
        self.field = field
        self.message = message
        self.point = point  # 0-based fix point concerned, when there is one


class CurveType(IntEnum):
    """The five "Type of Curve" choices of the Curve Data card, in the manual's order [DG L3708-3729].

    Numbered from 0: the Command Reference calls the specified-gradient curve "CU_GRAD curves (type 3)"
    [seed 001 L950], which fits a 0-based numbering of the manual's list.
    """

    AVERAGE_GRADIENTS = 0  # "Average start and end gradients"
    END_EQUALS_START = 1  # "Set end gradient to start gradient"
    ZERO_GRADIENTS = 2  # "Set both start and end gradient to 0"
    SPECIFIED_GRADIENTS = 3  # "Specify start and end gradients" (CU_GRAD)
    SPECIFIED_IMMEDIATE = 4  # "Specify gradients (immediate)"


@dataclass(frozen=True)
class FixPoint:
    master: float
    slave: float
    type: str = "C"


@dataclass(frozen=True)
class StartStopPair:
    """Engage/disengage window: forward, engaging runs Start (a) → Stop (b) [DG L4040-4046]."""

    start: float
    stop: float


def segment_kinds(types: list[str] | tuple[str, ...]) -> list[str]:
    """Shape of every segment (fix point i → i+1) from the fix point types; raises CurveError("fix_points").

    The model of ide-spec 4.36: a T point opens a straight segment that the next point (T, CZ or C3) closes;
    the segment leaving a closing point is curved and its shape comes from the closing point's type
    (T → spline/quintic, CZ → trapezoid, C3 → cubic); C points start spline segments.  CZ and C3 segments must
    run between two straight sections ("can only be used between adjacent tangent segments" [DG L4014-4020]),
    so at least one curved segment always separates two straight sections [DG L3992].

    Motion-law points (LAW_TYPES, decision C10): the segment *ending* at a law point follows the law (LAW);
    it must be a curved segment that a C point, a law point or a closing T point opened (not a straight or a
    CZ/C3 segment, and not the first point, which ends no segment).  The segment leaving a law point is shaped
    as if the point were a C point.  A law starts and ends at rest: its neighbours see a zero gradient there.
    """
    n = len(types)
    if set(types) == {"C"}:  # the common all-curve case, fast for long curves
        return [SPLINE] * (n - 1)
    kinds: list[str] = []
    open_line = False
    for i, t in enumerate(types):
        last = i == n - 1
        if t not in FIX_POINT_TYPES:
            raise CurveError("fix_points", f"point {i + 1}: unknown type {t!r} (one of {', '.join(FIX_POINT_TYPES)})",
                             i)
        if t in LAW_TYPES:
            _law_segment(kinds, types, i, open_line)
            if not last:
                kinds.append(SPLINE)
            continue
        if open_line:
            if t == "C":
                raise CurveError("fix_points", f"point {i}: a tangent (T) point needs a second T point to form a "
                                               f"straight line, point {i + 1} is C", i)
            open_line = False
            if not last:
                kinds.append({"T": SPLINE, "CZ": TRAPEZOID, "C3": CUBIC}[t])
        elif t == "T":
            if last:
                raise CurveError("fix_points", f"point {i + 1}: tangent points come in pairs, the last point has "
                                               "no partner", i)
            kinds.append(LINE)
            open_line = True
        elif t == "C":
            if not last:
                kinds.append(SPLINE)
        else:
            raise CurveError("fix_points", f"point {i + 1}: type {t} is allowed only between two straight "
                                           "sections (it must close a tangent pair)", i)
    for k, kind in enumerate(kinds):
        if kind in (TRAPEZOID, CUBIC) and (k + 1 >= len(kinds) or kinds[k + 1] != LINE):
            label = "CZ" if kind == TRAPEZOID else "C3"
            raise CurveError("fix_points", f"point {k + 1}: a {label} segment must be followed by a straight "
                                           "section (tangent pair)", k)
    return kinds


def _law_segment(kinds: list[str], types, i: int, open_line: bool) -> None:
    """Turn the segment ending at law point i into a LAW segment, or raise CurveError."""
    if i == 0:
        raise CurveError("fix_points", f"point 1: a motion law ({types[0]}) shapes the segment ending at its point; "
                                       "the first point ends no segment", 0)
    if open_line:
        raise CurveError("fix_points", f"point {i}: a tangent (T) point needs a second T point to form a straight "
                                       f"line, point {i + 1} is the motion law {types[i]}", i)
    if kinds[-1] != SPLINE:
        raise CurveError("fix_points", f"point {i + 1}: the motion law {types[i]} cannot replace the "
                                       f"{kinds[-1]} segment that point {i} ({types[i - 1]}) starts", i)
    kinds[-1] = LAW


def _finite(name: str, value: float) -> None:
    if not isinstance(value, int | float) or isinstance(value, bool) or not math.isfinite(value):
        raise CurveError(name, f"must be a finite number, got {value!r}")


def default_pairs() -> tuple[StartStopPair, ...]:
    """Pair 0, the hidden Start = Stop pair every new curve carries (see docs/formats/cam-array.md)."""
    return (StartStopPair(0, 0),)


@dataclass(frozen=True)
class Curve:
    """One CAM profile (one controller array).

    ``start_stop_pairs[k]`` is pair number ``k`` of SYNCCSTART/SYNCCSTOP.  Pair 0 is the editor's hidden
    Start = Stop pair ("SYNCCSTART 0 // Engage roller immediately with the set maximum velocity" [DG L1485]);
    the editor's table shows pairs 1.. ("Point 1: 1000 1500, Point 2: 2500 3000" [DG L1508-1511]).
    The master length must equal the last fix point's master position [DG L3731-3743]; the slave length is
    derived: last slave − first slave [DG L3735].
    """

    name: str
    master_length: float
    fix_points: tuple[FixPoint, ...]
    interpolation: bool = True
    intervals: int = 40
    curve_type: CurveType = CurveType.AVERAGE_GRADIENTS
    start_stop_pairs: tuple[StartStopPair, ...] = field(default_factory=default_pairs)
    slave_stop_position: float = 0
    correction_start: float = 0
    correction_end: float = 0
    max_correction: float = 0
    cycles_per_min: float = 60
    master_marker_pos: float = 0
    slave_marker_pos: float = 0
    start_gradient: float = 0.0  # UU/MU, used by the SPECIFIED_* curve types ("Set" button)
    end_gradient: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "fix_points", tuple(self.fix_points))
        object.__setattr__(self, "start_stop_pairs", tuple(self.start_stop_pairs))
        try:
            object.__setattr__(self, "curve_type", CurveType(self.curve_type))
        except ValueError:
            raise CurveError("curve_type", f"unknown curve type {self.curve_type!r} (0..4)") from None
        self.validate()

    # -- derived values -------------------------------------------------------------------------------------
    @property
    def slave_length(self) -> float:
        """Slave position at the end minus at the start (0 for a closed cam) [DG L3735]."""
        return self.fix_points[-1].slave - self.fix_points[0].slave

    @property
    def interval_size(self) -> float:
        """Interval size [MU] = master length / number of intervals [DG L3835-3839]."""
        return self.master_length / self.intervals

    @property
    def interval_time_ms(self) -> float:
        """Interval time [ms] = 60000 / (cycles/min × intervals); S1: 60/min, 40 intervals → 25 ms [DG L1438]."""
        return 60000.0 / self.cycles_per_min / self.intervals

    @property
    def interpolation_point_count(self) -> int:
        """InterpolPointNo: N + 1 with interpolation (first and last included), 0 without."""
        return self.intervals + 1 if self.interpolation else 0

    @property
    def segment_kinds(self) -> list[str]:
        return segment_kinds([p.type for p in self.fix_points])

    def on_grid(self, master: float) -> bool:
        q = master / self.interval_size
        return abs(q - round(q)) <= 1e-9 * max(1.0, abs(q))

    # -- validation -------------------------------------------------------------------------------------------
    def validate(self) -> None:
        if not isinstance(self.name, str) or len(self.name) > MAX_NAME_LENGTH:
            raise CurveError("name", f"at most {MAX_NAME_LENGTH} characters")
        if not all(32 <= ord(ch) < 127 for ch in self.name):
            raise CurveError("name", "printable ASCII characters only (stored 4 per array element)")
        _finite("master_length", self.master_length)
        if self.master_length <= 0:
            raise CurveError("master_length", "must be > 0")
        if not isinstance(self.intervals, int) or isinstance(self.intervals, bool) or self.intervals < 1:
            raise CurveError("intervals", f"must be an integer >= 1, got {self.intervals!r}")
        if self.intervals > MAX_INTERVALS:  # before any interpolation point is computed
            raise CurveError("intervals", f"{self.intervals} is more than the controller's array memory holds "
                                          f"({MAX_ARRAY_ELEMENTS} elements): at most {MAX_INTERVALS}")
        self._validate_fix_points()
        for name in ("slave_stop_position", "correction_start", "correction_end", "max_correction",
                     "cycles_per_min", "master_marker_pos", "slave_marker_pos", "start_gradient", "end_gradient"):
            _finite(name, getattr(self, name))
        for name in ("correction_start", "correction_end", "master_marker_pos"):
            if not 0 <= getattr(self, name) <= self.master_length:
                raise CurveError(name, f"must lie inside the master cycle 0..{self.master_length:g}")
        if self.max_correction < 0:
            raise CurveError("max_correction", "must be >= 0")
        if not CYCLES_PER_MIN[0] <= self.cycles_per_min <= CYCLES_PER_MIN[1]:
            raise CurveError("cycles_per_min", f"must be from {CYCLES_PER_MIN[0]} to {CYCLES_PER_MIN[1]} (the curve "
                                               "array holds whole cycles per minute)")
        self._validate_pairs()

    def _validate_fix_points(self) -> None:
        pts = self.fix_points
        if len(pts) < 2:
            raise CurveError("fix_points", "at least 2 fix points are needed")
        if self._points_plainly_valid():
            segment_kinds([p.type for p in pts])
            return
        for i, p in enumerate(pts):
            if not isinstance(p, FixPoint):
                raise CurveError("fix_points", f"point {i + 1} is not a FixPoint")
            _finite("fix_points", p.master)
            _finite("fix_points", p.slave)
        if pts[0].master != 0:
            raise CurveError("fix_points", f"the first fix point must be at master 0, not {pts[0].master:g}")
        for i in range(1, len(pts)):
            if not pts[i].master > pts[i - 1].master:
                raise CurveError("fix_points", f"point {i + 1} (master {pts[i].master:g}) must lie after point {i} "
                                               f"(master {pts[i - 1].master:g}); fix points are sorted by master")
        if pts[-1].master != self.master_length:
            raise CurveError("master_length", f"{self.master_length:g} differs from the last fix point's master "
                                              f"position {pts[-1].master:g}")
        if self.interpolation and not self.on_grid(pts[-1].master):
            raise CurveError("fix_points", "the last fix point must lie on the interpolation grid")
        segment_kinds([p.type for p in pts])

    def _points_plainly_valid(self) -> bool:
        """Fast check of the common case (every rule below holds), vectorised for long curves; when it fails the
        point-by-point checks find the first offending point for the message."""
        pts = self.fix_points
        if not all(type(p) is FixPoint for p in pts):
            return False
        values = [v for p in pts for v in (p.master, p.slave)]
        if not {type(v) for v in values} <= {int, float}:
            return False
        arr = np.array(values, dtype=float)
        if not np.isfinite(arr).all():
            return False
        masters = arr[0::2]
        return bool(masters[0] == 0 and (np.diff(masters) > 0).all() and pts[-1].master == self.master_length
                    and (not self.interpolation or self.on_grid(pts[-1].master)))

    def _validate_pairs(self) -> None:
        if len(self.start_stop_pairs) > MAX_USER_PAIRS + 1:
            raise CurveError("start_stop_pairs", f"at most {MAX_USER_PAIRS} pairs (plus pair 0)")
        for k, pair in enumerate(self.start_stop_pairs):
            if not isinstance(pair, StartStopPair):
                raise CurveError("start_stop_pairs", f"pair {k} is not a StartStopPair")
            for value in (pair.start, pair.stop):
                _finite("start_stop_pairs", value)
                if not 0 <= value <= self.master_length:
                    raise CurveError("start_stop_pairs", f"pair {k}: {value:g} lies outside the master cycle "
                                                         f"0..{self.master_length:g}")
                if self.interpolation and not self.on_grid(value):
                    raise CurveError("start_stop_pairs", f"pair {k}: {value:g} is not on the interpolation grid "
                                                         f"(interval {self.interval_size:g})")

    # -- helpers ----------------------------------------------------------------------------------------------
    def pair_span(self, k: int) -> float:
        """Master distance from Start to Stop of pair k, wrapping around the cycle when Start > Stop [DG L4052]."""
        pair = self.start_stop_pairs[k]
        span = pair.stop - pair.start
        return span + self.master_length if span < 0 else span


def snap(value: float, grid: float) -> float:
    """Nearest grid position (Snap on Grid)."""
    return round(value / grid) * grid
