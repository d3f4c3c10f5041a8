"""The controller's curve array: encode a Curve into the long values of its DIM array, and decode/validate one.

Layout: /work/shared/spec/cam-array-layout.md (MCO 305 DG appendix "Array Structure of CAM Profiles"), with our
choices for the parts that are not public; everything is described element by element in
docs/formats/cam-array.md.  Offsets are 0-based indices into the value list (APOSS element a[k] is value k-1).

Element count = 15 + 14 + 2n + 3F + I + 2n + 2n + 2M with n start/stop pairs (pair 0 included), F fix points,
I = N+1 interpolation points (0 without interpolation) and M = MaxStartStopLen
= max(2, max over pairs of span/interval + 1).  Stamping 92, marker 112, slavesync 108 [DG L1476, L1552, L1729].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from motiontool.camcurve.model import (
    FIX_POINT_TYPE_CODES,
    FIX_POINT_TYPES,
    MAX_ARRAY_ELEMENTS,
    MAX_USER_PAIRS,
    MIN_FIX_POINTS_ARRAY,
    Curve,
    CurveError,
    CurveType,
    FixPoint,
    StartStopPair,
    segment_kinds,
)
from motiontool.camcurve.spline import blend, interpolation_points, path_point_count, profile, round_half_up

#: Identification of a curve array (header element 0): ASCII "CAME" as a big-endian long (our choice).
CURVE_ARRAY_ID = 0x43414D45
#: Structure version (header element 1) written and accepted by this module.
STRUCTURE_VERSION = 1
HEADER_LEN = 15
CURVE_INFO_LEN = 14
NAME_WORDS = 4
VELOCITY_SCALE = 100_000  # start/stop velocities in UU/MU × 100000 (layout)
PATH_SCALE = 100_000  # start/stop path values: weight of the profile × 100000 (our choice)
NO_INDEX = -1  # start/stop index without an interpolation section
INT32_MIN, INT32_MAX = -(2 ** 31), 2 ** 31 - 1

# header element offsets
H_ID, H_VERSION, H_TYPE, H_NAME = 0, 1, 2, 3
H_CI, H_STP, H_FIP, H_INP, H_STPIND, H_STPVEL, H_STIP, H_STPIP = range(7, 15)
# curve info offsets (relative to IndexCI)
(CI_MASTER_LEN, CI_SLAVE_LEN, CI_FIX_NO, CI_INTERPOL_NO, CI_INTERPOL_TYPE, CI_SLAVE_STOP, CI_CORR_START,
 CI_CORR_STOP, CI_MAX_CORR, CI_MAX_STST_LEN, CI_STST_NO, CI_MAX_CYCLES, CI_M_MARKER, CI_S_MARKER) = range(14)


class CurveArrayError(ValueError):
    """An array that is not a valid curve (the kernel reports controller error 191 "Illegal cam array").

    ``index`` is the 0-based element concerned (len(values) - 1 when the array ends too early).
    """

    def __init__(self, message: str, index: int) -> None:
        super().__init__(f"element {index}: {message}")
        self.message = message
        self.index = index


# -- helpers --------------------------------------------------------------------------------------------------
def encode_name(name: str) -> list[int]:
    """16 ASCII characters, NUL padded, 4 per long, first character in the most significant byte."""
    raw = name.encode("ascii").ljust(4 * NAME_WORDS, b"\0")
    return [int.from_bytes(raw[i:i + 4], "big", signed=True) for i in range(0, 4 * NAME_WORDS, 4)]


def max_start_stop_len(curve: Curve) -> int:
    """MaxStartStopLen M = max(2, max over all pairs of span/interval + 1) (span wraps when Start > Stop)."""
    return max([2] + [path_point_count(curve, curve.pair_span(k)) for k in range(len(curve.start_stop_pairs))])


def start_path_values(count: int) -> list[int]:
    """Start (engage) path: profile weight w(u) × 100000 at ``count`` equidistant u in 0..1 (w = quintic blend)."""
    return round_half_up([float(blend(j / (count - 1))) * PATH_SCALE for j in range(count)])


def stop_path_values(count: int) -> list[int]:
    """Stop (disengage) path: profile weight 1 − w(u), i.e. 100000 − start path."""
    return [PATH_SCALE - v for v in start_path_values(count)]


def element_count(curve: Curve) -> int:
    """The DIM size the program needs (the editor's "Length" field)."""
    n, f = len(curve.start_stop_pairs), len(curve.fix_points)
    return HEADER_LEN + CURVE_INFO_LEN + 6 * n + 3 * f + curve.interpolation_point_count + 2 * max_start_stop_len(curve)


def _integral(field: str, value: float) -> int:
    if value != math.floor(value):
        raise CurveError(field, f"{value!r} is not a whole number (the controller stores longs)")
    if not INT32_MIN <= value <= INT32_MAX:
        raise CurveError(field, f"{value!r} does not fit a 32-bit long")
    return int(value)


# -- encode -----------------------------------------------------------------------------------------------------
def encode(curve: Curve) -> list[int]:
    """The controller array of a curve; raises CurveError for curves the array cannot hold."""
    if len(curve.fix_points) < MIN_FIX_POINTS_ARRAY:
        raise CurveError("fix_points", f"the controller needs at least {MIN_FIX_POINTS_ARRAY} fix points "
                                       f"(FixPointNo), the curve has {len(curve.fix_points)}")
    n, f = len(curve.start_stop_pairs), len(curve.fix_points)
    fixed = HEADER_LEN + CURVE_INFO_LEN + 6 * n + 3 * f + curve.interpolation_point_count
    if fixed > MAX_ARRAY_ELEMENTS:  # refused before the interpolation points are computed (decisions R15)
        raise CurveError("intervals", f"the array would have at least {fixed} elements, more than the controller's "
                                      f"array memory of {MAX_ARRAY_ELEMENTS}")
    inp = interpolation_points(curve) if curve.interpolation else []
    m = max_start_stop_len(curve)
    i_ci = HEADER_LEN
    i_stp = i_ci + CURVE_INFO_LEN
    i_fip = i_stp + 2 * n
    i_inp = i_fip + 3 * f
    i_stpind = i_inp + len(inp)
    i_stpvel = i_stpind + 2 * n
    i_stip = i_stpvel + 2 * n
    i_stpip = i_stip + m
    header = [CURVE_ARRAY_ID, STRUCTURE_VERSION, int(curve.curve_type), *encode_name(curve.name),
              i_ci, i_stp, i_fip, i_inp, i_stpind, i_stpvel, i_stip, i_stpip]
    info = [_integral("master_length", curve.master_length), _integral("fix_points", curve.slave_length), f, len(inp),
            0, _integral("slave_stop_position", curve.slave_stop_position),
            _integral("correction_start", curve.correction_start), _integral("correction_end", curve.correction_end),
            _integral("max_correction", curve.max_correction), m, n, max(1, round(curve.cycles_per_min)),
            _integral("master_marker_pos", curve.master_marker_pos),
            _integral("slave_marker_pos", curve.slave_marker_pos)]
    stp: list[int] = []
    for pair in curve.start_stop_pairs:
        stp += [_integral("start_stop_pairs", pair.start), _integral("start_stop_pairs", pair.stop)]
    fip: list[int] = []
    for p in curve.fix_points:
        fip += [_integral("fix_points", p.master), _integral("fix_points", p.slave), FIX_POINT_TYPE_CODES[p.type]]
    if curve.interpolation:
        stpind = [round(v / curve.interval_size) for v in stp]
    else:
        stpind = [NO_INDEX] * (2 * n)
    vel = profile(curve).velocity([float(v) for v in stp]) if stp else []
    stpvel = round_half_up([v * VELOCITY_SCALE for v in vel])
    for v in inp + stpvel:
        if not INT32_MIN <= v <= INT32_MAX:
            raise CurveError("fix_points", f"curve value {v} does not fit a 32-bit long")
    values = header + info + stp + fip + inp + stpind + stpvel + start_path_values(m) + stop_path_values(m)
    assert len(values) == element_count(curve) == i_stpip + m
    return values


# -- decode -----------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class DecodedCurve:
    """The validated contents of a curve array (raw controller values)."""

    curve_type: CurveType
    name_words: tuple[int, ...]
    name: str
    master_length: int
    slave_length: int
    interpol_type: int
    slave_stop_position: int
    correction_start: int
    correction_end: int
    max_correction: int
    max_start_stop_len: int
    cycles_per_min: int
    master_marker_pos: int
    slave_marker_pos: int
    start_stop_pairs: tuple[StartStopPair, ...]
    fix_points: tuple[FixPoint, ...]
    interpolation_points: tuple[int, ...]
    start_stop_indices: tuple[int, ...]
    start_stop_velocities: tuple[int, ...]  # UU/MU × 100000, two per pair (at Start, at Stop)
    start_path: tuple[int, ...]
    stop_path: tuple[int, ...]

    @property
    def interpolation(self) -> bool:
        return bool(self.interpolation_points)

    @property
    def intervals(self) -> int | None:
        return len(self.interpolation_points) - 1 if self.interpolation_points else None

    def values(self) -> list[int]:
        """Serialise again (decode(v).values() == v for every accepted v)."""
        n, f, i, m = (len(self.start_stop_pairs), len(self.fix_points), len(self.interpolation_points),
                      self.max_start_stop_len)
        i_stp = HEADER_LEN + CURVE_INFO_LEN
        i_fip = i_stp + 2 * n
        i_inp = i_fip + 3 * f
        i_stpind = i_inp + i
        i_stpvel = i_stpind + 2 * n
        i_stip = i_stpvel + 2 * n
        header = [CURVE_ARRAY_ID, STRUCTURE_VERSION, int(self.curve_type), *self.name_words, HEADER_LEN, i_stp,
                  i_fip, i_inp, i_stpind, i_stpvel, i_stip, i_stip + m]
        info = [self.master_length, self.slave_length, f, i, self.interpol_type, self.slave_stop_position,
                self.correction_start, self.correction_end, self.max_correction, m, n, self.cycles_per_min,
                self.master_marker_pos, self.slave_marker_pos]
        stp = [v for p in self.start_stop_pairs for v in (int(p.start), int(p.stop))]
        fip = [v for p in self.fix_points for v in (int(p.master), int(p.slave), FIX_POINT_TYPE_CODES[p.type])]
        return (header + info + stp + fip + list(self.interpolation_points) + list(self.start_stop_indices)
                + list(self.start_stop_velocities) + list(self.start_path) + list(self.stop_path))

    def to_curve(self, intervals: int | None = None, start_gradient: float = 0.0, end_gradient: float = 0.0) -> Curve:
        """The editable curve.  Not stored in the array: the gradients of the SPECIFIED_* types and, for arrays
        without interpolation, the editor's nominal interval count (default 1)."""
        return Curve(self.name, self.master_length, self.fix_points, interpolation=self.interpolation,
                     intervals=self.intervals or intervals or 1, curve_type=self.curve_type,
                     start_stop_pairs=self.start_stop_pairs, slave_stop_position=self.slave_stop_position,
                     correction_start=self.correction_start, correction_end=self.correction_end,
                     max_correction=self.max_correction, cycles_per_min=self.cycles_per_min,
                     master_marker_pos=self.master_marker_pos, slave_marker_pos=self.slave_marker_pos,
                     start_gradient=start_gradient, end_gradient=end_gradient)


def decode(values: list[int]) -> DecodedCurve:
    """Validate and decode a curve array; raises CurveArrayError(message, index) naming the element."""
    values = list(values)
    size = len(values)

    def need(count: int, what: str) -> None:
        if size < count:
            raise CurveArrayError(f"array ends after {size} elements, {what} needs {count}", max(size - 1, 0))

    for i, v in enumerate(values):
        if not isinstance(v, int) or isinstance(v, bool):
            raise CurveArrayError(f"not an integer: {v!r}", i)
        if not INT32_MIN <= v <= INT32_MAX:
            raise CurveArrayError(f"{v} does not fit a 32-bit long", i)
    need(HEADER_LEN, "the header")
    if values[H_ID] != CURVE_ARRAY_ID:
        raise CurveArrayError(f"not a curve array (identification {values[H_ID]}, expected {CURVE_ARRAY_ID})", H_ID)
    if values[H_VERSION] != STRUCTURE_VERSION:
        raise CurveArrayError(f"structure version {values[H_VERSION]} is not supported (expected "
                              f"{STRUCTURE_VERSION})", H_VERSION)
    if values[H_TYPE] not in set(CurveType):
        raise CurveArrayError(f"unknown curve type {values[H_TYPE]}", H_TYPE)
    name = _decode_name(values)
    if values[H_CI] != HEADER_LEN:
        raise CurveArrayError(f"IndexCI is {values[H_CI]}, the curve info follows the header at {HEADER_LEN}", H_CI)
    ci = HEADER_LEN
    need(ci + CURVE_INFO_LEN, "the curve info")
    info = values[ci:ci + CURVE_INFO_LEN]
    length, f, i_no, m, n = (info[CI_MASTER_LEN], info[CI_FIX_NO], info[CI_INTERPOL_NO], info[CI_MAX_STST_LEN],
                             info[CI_STST_NO])
    if length <= 0:
        raise CurveArrayError(f"master cycle length {length} must be > 0", ci + CI_MASTER_LEN)
    if f < MIN_FIX_POINTS_ARRAY:
        raise CurveArrayError(f"FixPointNo {f} < {MIN_FIX_POINTS_ARRAY}", ci + CI_FIX_NO)
    if i_no == 1 or i_no < 0:
        raise CurveArrayError(f"InterpolPointNo {i_no} (0 or at least 2)", ci + CI_INTERPOL_NO)
    if info[CI_INTERPOL_TYPE] not in (0, 1):
        raise CurveArrayError(f"InterpolType {info[CI_INTERPOL_TYPE]} (0 or 1)", ci + CI_INTERPOL_TYPE)
    if m < 2:
        raise CurveArrayError(f"MaxStartStopLen {m} < 2", ci + CI_MAX_STST_LEN)
    if not 0 <= n <= MAX_USER_PAIRS + 1:
        raise CurveArrayError(f"StartStopNo {n} outside 0..{MAX_USER_PAIRS + 1}", ci + CI_STST_NO)
    if info[CI_MAX_CYCLES] <= 0:
        raise CurveArrayError(f"cycles/min {info[CI_MAX_CYCLES]} must be > 0", ci + CI_MAX_CYCLES)
    if info[CI_MAX_CORR] < 0:
        raise CurveArrayError(f"maximum correction {info[CI_MAX_CORR]} < 0", ci + CI_MAX_CORR)
    for off in (CI_CORR_START, CI_CORR_STOP, CI_M_MARKER):
        if not 0 <= info[off] <= length:
            raise CurveArrayError(f"{info[off]} lies outside the master cycle 0..{length}", ci + off)
    # section indices and total size
    expected = {}
    expected[H_STP] = ci + CURVE_INFO_LEN
    expected[H_FIP] = expected[H_STP] + 2 * n
    expected[H_INP] = expected[H_FIP] + 3 * f
    expected[H_STPIND] = expected[H_INP] + i_no
    expected[H_STPVEL] = expected[H_STPIND] + 2 * n
    expected[H_STIP] = expected[H_STPVEL] + 2 * n
    expected[H_STPIP] = expected[H_STIP] + m
    for slot, index in expected.items():
        if values[slot] != index:
            raise CurveArrayError(f"section index {values[slot]} inconsistent with the curve info (expected "
                                  f"{index})", slot)
    end = expected[H_STPIP] + m
    if size != end:
        raise CurveArrayError(f"the sections add up to {end} elements, the array has {size}", min(end, size - 1))
    # start/stop points
    stp = values[expected[H_STP]:expected[H_FIP]]
    for k, v in enumerate(stp):
        if not 0 <= v <= length:
            raise CurveArrayError(f"start/stop point {v} outside the master cycle 0..{length}", expected[H_STP] + k)
    pairs = tuple(StartStopPair(stp[2 * k], stp[2 * k + 1]) for k in range(n))
    fix_points = _decode_fix_points(values, expected[H_FIP], f, length, info[CI_SLAVE_LEN], ci)
    inp = values[expected[H_INP]:expected[H_STPIND]]
    if i_no:
        intervals = i_no - 1
        if inp[0] != fix_points[0].slave:
            raise CurveArrayError("first interpolation point differs from the first fix point", expected[H_INP])
        if inp[-1] != fix_points[-1].slave:
            raise CurveArrayError("last interpolation point differs from the last fix point", expected[H_STPIND] - 1)
    # start/stop indices
    ind = values[expected[H_STPIND]:expected[H_STPVEL]]
    for k, (point, index) in enumerate(zip(stp, ind, strict=True)):
        at = expected[H_STPIND] + k
        if not i_no:
            if index != NO_INDEX:
                raise CurveArrayError(f"start/stop index {index} without interpolation section (expected "
                                      f"{NO_INDEX})", at)
        elif point * intervals % length:
            raise CurveArrayError(f"start/stop point {point} is not on an interpolation point", expected[H_STP] + k)
        elif index != point * intervals // length:
            raise CurveArrayError(f"start/stop index {index} does not match point {point}", at)
    if i_no:
        spans = [b - a if b >= a else b - a + length for a, b in zip(stp[0::2], stp[1::2], strict=True)]
        need_m = max([2] + [max(2, s * intervals // length + 1) for s in spans])
        if m < need_m:
            raise CurveArrayError(f"MaxStartStopLen {m} is too short for the longest start/stop path ({need_m})",
                                  ci + CI_MAX_STST_LEN)
    vel = values[expected[H_STPVEL]:expected[H_STIP]]
    start_path = values[expected[H_STIP]:expected[H_STPIP]]
    stop_path = values[expected[H_STPIP]:end]
    _check_path(start_path, expected[H_STIP], 0, PATH_SCALE, "start")
    _check_path(stop_path, expected[H_STPIP], PATH_SCALE, 0, "stop")
    return DecodedCurve(CurveType(values[H_TYPE]), tuple(values[H_NAME:H_NAME + NAME_WORDS]), name, length,
                        info[CI_SLAVE_LEN], info[CI_INTERPOL_TYPE], info[CI_SLAVE_STOP], info[CI_CORR_START],
                        info[CI_CORR_STOP], info[CI_MAX_CORR], m, info[CI_MAX_CYCLES], info[CI_M_MARKER],
                        info[CI_S_MARKER], pairs, fix_points, tuple(inp), tuple(ind), tuple(vel), tuple(start_path),
                        tuple(stop_path))


def _decode_name(values: list[int]) -> str:
    raw = b"".join(values[H_NAME + w].to_bytes(4, "big", signed=True) for w in range(NAME_WORDS))
    text, _, padding = raw.partition(b"\0")
    for pos, byte in enumerate(raw):
        bad_char = byte != 0 and not 32 <= byte < 127
        bad_pad = pos >= len(text) and byte != 0
        if bad_char or bad_pad:
            raise CurveArrayError("curve name is not NUL-padded printable ASCII", H_NAME + pos // 4)
    del padding
    return text.decode("ascii")


def _decode_fix_points(values: list[int], start: int, count: int, length: int, slave_len: int,
                       ci: int) -> tuple[FixPoint, ...]:
    points: list[FixPoint] = []
    codes = {code: t for t, code in FIX_POINT_TYPE_CODES.items()}
    for k in range(count):
        at = start + 3 * k
        master, slave_pos, code = values[at:at + 3]
        if code not in codes:
            raise CurveArrayError(f"fix point {k + 1}: unknown type code {code}", at + 2)
        if k == 0 and master != 0:
            raise CurveArrayError(f"first fix point at master {master}, must be 0", at)
        if k and master <= points[-1].master:
            raise CurveArrayError(f"fix point {k + 1}: master {master} not after {points[-1].master} "
                                  "(fix points must increase)", at)
        points.append(FixPoint(master, slave_pos, codes[code]))
    if points[-1].master != length:
        raise CurveArrayError(f"last fix point at master {points[-1].master}, the cycle length is {length}",
                              start + 3 * (count - 1))
    if slave_len != points[-1].slave - points[0].slave:
        raise CurveArrayError(f"slave cycle length {slave_len} differs from the fix points "
                              f"({points[-1].slave - points[0].slave})", ci + CI_SLAVE_LEN)
    try:
        segment_kinds([p.type for p in points])
    except CurveError as exc:
        raise CurveArrayError(exc.message, start + 3 * (exc.point or 0) + 2) from None
    assert all(p.type in FIX_POINT_TYPES for p in points)
    return tuple(points)


def _check_path(path: list[int], start: int, first: int, last: int, what: str) -> None:
    if path[0] != first:
        raise CurveArrayError(f"{what} path must begin at {first}", start)
    if path[-1] != last:
        raise CurveArrayError(f"{what} path must end at {last}", start + len(path) - 1)
    rising = last > first
    for k in range(1, len(path)):
        if not 0 <= path[k] <= PATH_SCALE:
            raise CurveArrayError(f"{what} path value {path[k]} outside 0..{PATH_SCALE}", start + k)
        if (path[k] < path[k - 1]) if rising else (path[k] > path[k - 1]):
            raise CurveArrayError(f"{what} path is not monotonic", start + k)
