"""Curve edits of the CAM editor, Qt-free: every function takes a Curve and returns a new, validated Curve or
raises CurveError with a message for the user (the editor shows it and keeps the old curve).

Sources: DG L3642-3682 (mouse editing), L3960-4070 (Fix points and Start Stop tables), L3731-3793 (master
length, interpolation grid); ide-spec 4.25-4.48.
"""

from __future__ import annotations

import dataclasses
import math

from motiontool.camcurve.model import MAX_USER_PAIRS, Curve, CurveError, FixPoint, StartStopPair, segment_kinds
from motiontool.camcurve.motionlaws import LAWS
from motiontool.camcurve.spline import profile

#: Fix point type names of the popup menu [DG L3676]; then the VDI 2143 motion laws (decision C10).
TYPE_NAMES = {"C": "Curve", "T": "Tangent", "CZ": "Trapezoid", "C3": "3'rd order",
              **{code: law.name for code, law in LAWS.items()}}


def replace(curve: Curve, **changes) -> Curve:
    """A copy with ``changes`` (validated by Curve itself)."""
    return dataclasses.replace(curve, **changes)


def grid_snap(curve: Curve, master: float) -> float:
    """Nearest interpolation grid position, as an int when the grid is integral (the array stores longs)."""
    value = round(master / curve.interval_size) * curve.interval_size
    return int(round(value)) if abs(value - round(value)) < 1e-9 else value


def _whole(value: float) -> float:
    return int(round(value)) if abs(value - round(value)) < 1e-9 else value


def typed(operation):
    """``operation`` on values the user typed (Fix Points cell, the Add dialogs): a fix point or start/stop point
    the edit leaves off whole numbers is refused naming it, because the controller array stores longs and Save
    would refuse it later (decision C20; a drag rounds, C17). Values that were already there are not judged."""
    def run(curve: Curve, *args, **kwargs) -> Curve:
        new = operation(curve, *args, **kwargs)
        old = set(curve.fix_points)
        for i, p in enumerate(new.fix_points):
            if p not in old:
                _refuse_fraction("fix_points", f"point {i + 1}", (("master", p.master), ("slave", p.slave)), i)
        old_pairs = set(curve.start_stop_pairs)
        for k, pair in enumerate(new.start_stop_pairs):
            if pair not in old_pairs:
                _refuse_fraction("start_stop_pairs", f"pair {k}", (("start", pair.start), ("stop", pair.stop)))
        return new
    return run


def _refuse_fraction(field: str, where: str, values, point: int | None = None) -> None:
    for what, value in values:
        if value != math.floor(value):
            raise CurveError(field, f"{where}: {what} {value} is not a whole number (the controller stores the "
                                    f"curve as longs): type {math.floor(value)} or {math.ceil(value)}", point)


def _blockers(curve: Curve) -> list[tuple[float, str]]:
    """Positions the last fix point must not precede [DG L3745-3752] (besides the previous fix point)."""
    found = []
    for k, pair in enumerate(curve.start_stop_pairs):
        for value, label in ((pair.start, "Start"), (pair.stop, "Stop")):
            found.append((value, f"start/stop pair {k} {label} at {value:g}"))
    for name, label in (("correction_start", "Correction Start"), ("correction_end", "Correction End"),
                        ("master_marker_pos", "Master Marker Pos.")):
        found.append((getattr(curve, name), f"{label} {getattr(curve, name):g}"))
    return found


def check_last_point(curve: Curve, master: float) -> None:
    """Raise CurveError naming the blocking item when the last fix point may not move to ``master``."""
    pts = curve.fix_points
    if len(pts) > 1 and master <= pts[-2].master:
        raise CurveError("master_length", f"the last fix point cannot move to {master:g}: fix point {len(pts) - 1} "
                                          f"at {pts[-2].master:g} is in the way", len(pts) - 1)
    for value, label in _blockers(curve):
        if master < value:
            raise CurveError("master_length", f"the master length cannot become {master:g}: {label} is in the "
                                              "way; move that first", len(pts) - 1)


def last_point_minimum(curve: Curve) -> float:
    """Smallest master position the last point may take (on the grid when interpolation is on)."""
    pts = curve.fix_points
    step = curve.interval_size if curve.interpolation else 1
    low = math.floor(pts[-2].master / step + 1e-9) * step + step if len(pts) > 1 else step
    for value, _ in _blockers(curve):
        low = max(low, math.ceil(value / step - 1e-9) * step)
    return _whole(low)


def with_master_length(curve: Curve, points: tuple[FixPoint, ...], check: bool = True) -> Curve:
    """``points`` as the curve's fix points; a moved last point changes the master length and, with the interval
    size kept, the number of intervals [DG L3978, L3988].  The last point is always snapped to the grid."""
    size = curve.interval_size
    last = points[-1]
    master = grid_snap(curve, last.master) if curve.interpolation else _whole(last.master)
    if master <= 0:
        master = size
    points = points[:-1] + (FixPoint(master, last.slave, last.type),)
    if check and master < curve.master_length:
        check_last_point(replace_points_unchecked(curve, points), master)
    intervals = max(1, int(round(master / size)))
    return replace(curve, fix_points=points, master_length=master, intervals=intervals)


def replace_points_unchecked(curve: Curve, points: tuple[FixPoint, ...]) -> Curve:
    """``curve`` with other points, not validated: for the blocker check, and for move_point's drag fast path
    where the caller guarantees Curve.validate would pass (tests/cameditor/test_drag_fast_paths.py)."""
    clone = object.__new__(Curve)
    for f in dataclasses.fields(Curve):
        object.__setattr__(clone, f.name, getattr(curve, f.name))
    object.__setattr__(clone, "fix_points", points)
    return clone


def move_point(curve: Curve, index: int, master: float, slave: float, snap_on_grid: bool = False,
               clamp: bool = False) -> Curve:
    """Move fix point ``index``.  The first point stays at master 0; a point never passes its neighbours (clamp
    keeps it just inside, for mouse drags; otherwise a CurveError names the neighbour) [DG L3988]."""
    pts = list(curve.fix_points)
    if not 0 <= index < len(pts):
        raise CurveError("fix_points", f"there is no fix point {index + 1}")
    if snap_on_grid or (index == len(pts) - 1 and curve.interpolation):
        master = grid_snap(curve, master)
    master, slave = _whole(master), _whole(slave)
    if index == 0:
        master = 0
    else:
        low = pts[index - 1].master
        high = pts[index + 1].master if index + 1 < len(pts) else math.inf
        if clamp:
            step = curve.interval_size if snap_on_grid or index == len(pts) - 1 else 1
            if master <= low:
                master = _whole(low + step)
            if master >= high:
                master = _whole(high - step)
            if not low < master < high:
                master = pts[index].master
        if master <= low:
            raise CurveError("fix_points", f"point {index + 1} cannot move to {master:g}: it would pass point "
                                           f"{index} at {low:g}", index)
        if master >= high:
            raise CurveError("fix_points", f"point {index + 1} cannot move to {master:g}: it would pass point "
                                           f"{index + 2} at {high:g}", index)
    pts[index] = FixPoint(master, slave, pts[index].type)
    if index == len(pts) - 1:
        if clamp:
            pts[index] = FixPoint(max(master, last_point_minimum(curve)), slave, pts[index].type)
        return with_master_length(curve, tuple(pts))
    if _plain(master) and _plain(slave):
        # the curve was valid and one inner point moved between its neighbours (ensured above), keeping its type:
        # every rule of Curve.validate still holds, so skip re-checking all points (a drag of a 10 000-point curve)
        return replace_points_unchecked(curve, tuple(pts))
    return replace(curve, fix_points=tuple(pts))


def _plain(value) -> bool:
    """A finite int or float, as Curve.validate requires of positions."""
    return type(value) in (int, float) and math.isfinite(value)


def add_points(curve: Curve, points: list[tuple[float, float]], snap_on_grid: bool = False) -> Curve:
    """Add several fix points in any order (one undo step) [DG L3974-3978].  A point at the master position of
    an existing point replaces that point's slave value; a point beyond the last one extends the master length."""
    if not points:
        return curve
    by_master = {p.master: p for p in curve.fix_points}
    for master, slave in points:
        if not (math.isfinite(master) and math.isfinite(slave)):
            raise CurveError("fix_points", f"({master}, {slave}) is not a pair of finite numbers")
        if master < 0:
            raise CurveError("fix_points", f"master {master:g} lies before the curve start 0")
        if snap_on_grid:
            master = grid_snap(curve, master)
        master, slave = _whole(master), _whole(slave)
        old = by_master.get(master)
        by_master[master] = FixPoint(master, slave, old.type if old else "C")
    pts = tuple(by_master[m] for m in sorted(by_master))
    if pts[-1].master != curve.master_length:
        return with_master_length(curve, pts)
    return replace(curve, fix_points=pts)


def insert_on_curve(curve: Curve, master: float, snap_on_grid: bool = False) -> Curve:
    """Popup "Insert on Curve": a new point at ``master`` with the slave value of the current profile [DG L3662]."""
    if snap_on_grid:
        master = grid_snap(curve, master)
    if not 0 < master < curve.master_length:
        raise CurveError("fix_points", f"master {master:g} lies outside the curve 0..{curve.master_length:g}")
    slave = float(profile(curve).slave(master, periodic=False))
    return add_points(curve, [(master, round(slave))])


def delete_point(curve: Curve, index: int) -> Curve:
    """Delete fix point ``index`` (Del in the table, popup Delete).  The first point cannot go; deleting the last
    makes the previous point last (and shortens the master length)."""
    pts = list(curve.fix_points)
    if len(pts) <= 2:
        raise CurveError("fix_points", "a curve needs at least 2 fix points")
    if index == 0:
        raise CurveError("fix_points", "the first fix point (master 0) cannot be deleted", 0)
    del pts[index]
    if index == len(pts):
        return with_master_length(curve, tuple(pts))
    return replace(curve, fix_points=tuple(pts))


def tangent_partner(types: list[str], index: int) -> int | None:
    """The other point of the straight section that T point ``index`` opens or closes, if any."""
    open_at = None
    for i, t in enumerate(types):
        if open_at is not None:
            if i == index:
                return open_at
            if open_at == index:
                return i
            open_at = None
        elif t == "T":
            open_at = i
    return None


def change_type(curve: Curve, index: int, new_type: str) -> Curve:
    """Change the type of fix point ``index`` (Type cell, popup Change type).

    Tangent pairing [DG L1441-1445, ide-spec 4.33]: making a point T also makes the preceding point T (the
    first point pairs with the following one), in one step.  Making a T point something else also releases its
    partner back to C when the partner would otherwise be left without one.  Anything else the type rules
    refuse raises the rules' CurveError (e.g. CZ with no straight section after it) [DG L4014-4020].
    """
    types = [p.type for p in curve.fix_points]
    if not 0 <= index < len(types):
        raise CurveError("fix_points", f"there is no fix point {index + 1}")
    if types[index] == new_type:
        return curve
    candidates: list[list[str]] = []
    if new_type == "T":
        neighbour = index - 1 if index > 0 else index + 1
        first = list(types)
        first[index] = "T"
        if 0 <= neighbour < len(types):
            first[neighbour] = "T"
        candidates.append(first)
        alone = list(types)
        alone[index] = "T"
        candidates.append(alone)
        if index + 1 < len(types):
            after = list(alone)
            after[index + 1] = "T"
            candidates.append(after)
    else:
        alone = list(types)
        alone[index] = new_type
        candidates.append(alone)
        partner = tangent_partner(types, index) if types[index] == "T" else None
        if partner is not None and types[partner] == "T":
            released = list(alone)
            released[partner] = "C"
            candidates.append(released)
    first_error: CurveError | None = None
    for candidate in candidates:
        try:
            segment_kinds(candidate)
        except CurveError as exc:
            first_error = first_error or exc
            continue
        pts = tuple(FixPoint(p.master, p.slave, t) for p, t in zip(curve.fix_points, candidate, strict=True))
        return replace(curve, fix_points=pts)
    assert first_error is not None
    raise CurveError("fix_points", f"point {index + 1} cannot become {TYPE_NAMES.get(new_type, new_type)}: "
                                   f"{first_error.message}", index)


def snap_all(curve: Curve) -> Curve:
    """Toolbar "Snap on Grid": every fix point and start/stop point onto the grid, as one step [DG L3578].
    Points that would collide keep the first; the last point keeps the master length."""
    pts: dict[float, FixPoint] = {}
    for p in curve.fix_points:
        m = grid_snap(curve, p.master)
        if m not in pts and (m < curve.master_length or p is curve.fix_points[-1]):
            pts[m] = FixPoint(m, p.slave, p.type)
    pairs = tuple(StartStopPair(grid_snap(curve, p.start) % curve.master_length if p.start != curve.master_length
                                else p.start, grid_snap(curve, p.stop)) for p in curve.start_stop_pairs)
    return replace(curve, fix_points=tuple(pts[m] for m in sorted(pts)), start_stop_pairs=pairs)


def snap_point(curve: Curve, index: int) -> Curve:
    """Fix point popup "Snap on Grid": this point only."""
    p = curve.fix_points[index]
    return move_point(curve, index, p.master, p.slave, snap_on_grid=True)


def add_pairs(curve: Curve, pairs: list[tuple[float, float]]) -> Curve:
    """Add start/stop pairs in any order [DG L4060]; at most 25 (plus the hidden pair 0) [DG L4048]."""
    new = curve.start_stop_pairs + tuple(StartStopPair(_whole(a), _whole(b)) for a, b in pairs)
    if len(new) > MAX_USER_PAIRS + 1:
        raise CurveError("start_stop_pairs", f"at most {MAX_USER_PAIRS} start/stop pairs can be defined")
    return replace(curve, start_stop_pairs=new)


def set_pair(curve: Curve, k: int, start: float, stop: float) -> Curve:
    pairs = list(curve.start_stop_pairs)
    pairs[k] = StartStopPair(_whole(start), _whole(stop))
    return replace(curve, start_stop_pairs=tuple(pairs))


def delete_pair(curve: Curve, k: int) -> Curve:
    if k == 0:
        raise CurveError("start_stop_pairs", "pair 0 (SYNCCSTART 0: engage at maximum velocity) cannot be deleted")
    pairs = list(curve.start_stop_pairs)
    del pairs[k]
    return replace(curve, start_stop_pairs=tuple(pairs))


def set_length(curve: Curve, master_length: float, intervals: int, interpolation: bool) -> Curve:
    """Curve Data "Set": master length and intervals together, slave length unchanged [DG L3737-3743].
    The master length is made a multiple of the new interval size; the last point moves with it."""
    if not isinstance(intervals, int) or intervals < 1:
        raise CurveError("intervals", f"must be an integer >= 1, got {intervals!r}")
    if not math.isfinite(master_length) or master_length <= 0:
        raise CurveError("master_length", "must be > 0")
    master_length = _whole(master_length)
    check_last_point(curve, master_length)
    last = curve.fix_points[-1]
    pts = curve.fix_points[:-1] + (FixPoint(master_length, last.slave, last.type),)
    return replace(curve, fix_points=pts, master_length=master_length, intervals=intervals,
                   interpolation=interpolation)


def new_curve(name: str, master_length: float, intervals: int, interpolation: bool) -> Curve:
    """Add CAM array: two fix points forming a straight line [DG L3582] (slave rises by the master length)."""
    length = _whole(master_length)
    return Curve(name, length, (FixPoint(0, 0), FixPoint(length, length)), interpolation=interpolation,
                 intervals=intervals)
