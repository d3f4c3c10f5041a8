"""Converting between MCO fix-point curves and APC CAM tables (spec §7.2) — Qt-free.

The two models differ: the MCO curve is a spline through absolute fix points (master in MU, slave in UU); an
APC table is a chain of relative segments in counts, each with one of six closed-form laws. Neither converts
exactly into the other, so both directions report the largest position error they introduce.

* APC → MCO: every segment is sampled into fix points (its ends and `points_per_segment` - 1 points inside); the
  editor's spline through them follows the laws closely, and the error is measured densely.
* MCO → APC with continuous speed (`curve_to_smooth_table`, the editor's "From MCO curve"): the six laws alone
  change speed only from or to rest, so a chain of them steps its speed at every join (81 Linear segments for a
  plain curve, issue 23). A Square1 segment with a linear second slave travel (OutArray2%) ramps the speed
  linearly from Y2/X to (2·Y1 + Y2)/X (L1440; OutArray2 L1337, L3446): pairs of such segments, the first starting at the
  speed the last one ended with, reach the curve's position and speed at the end of each pair. Equal segment
  lengths make every join exact in whole counts (decision C21).
* MCO → APC (`curve_to_table`): from each fix point the longest run of fix-point segments that one law follows
  within the tolerance becomes one APC segment (the law that fits best; same ends, so the positions are exact
  at those fix points); where not even a single fix-point segment fits, it is split in half, down to
  `min_master` counts (spec §7.2: "several short linear segments, error bounded").
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from motiontool.apc.camlaws import LAW_NAMES, law_value
from motiontool.camcurve import spline
from motiontool.camcurve.model import Curve, FixPoint
from motiontool.cameditor.apctable import ApcCamTable, ApcSegment

_PROBES = 24   # points at which a candidate law is compared with the curve inside one segment


@dataclass(frozen=True)
class Conversion:
    table: ApcCamTable | None
    curve: Curve | None
    max_error: float            # largest position difference, slave counts (MCO → APC) or UU (APC → MCO)


def table_to_curve(table: ApcCamTable, *, name: str | None = None, points_per_segment: int = 8,
                   mu_per_count: float = 1.0, uu_per_count: float = 1.0) -> Conversion:
    """The fix-point curve through `table`'s window (one cycle, before the output ratio)."""
    masters: list[int] = [0]
    position = 0
    for s in table.window:
        masters += [position + round(s.master * k / points_per_segment) for k in range(1, points_per_segment + 1)]
        position += s.master
    masters = sorted(set(masters))
    points = tuple(FixPoint(m * mu_per_count, table.slave_at(m) * uu_per_count) for m in masters)
    curve = Curve(name or table.name[:16], points[-1].master, points, interpolation=False)
    probe = np.linspace(0, table.master_length, max(2000, 40 * len(table.window)))
    exact = np.array([table.slave_at(int(round(m))) for m in probe]) * uu_per_count
    drawn = spline.slave(curve, np.round(probe) * mu_per_count)
    return Conversion(None, curve, float(np.max(np.abs(drawn - exact))))


def curve_to_table(curve: Curve, *, name: str | None = None, counts_per_mu: float = 1.0,
                   counts_per_uu: float = 1.0, tolerance: float = 1.0, min_master: int = 16) -> Conversion:
    """The APC table that follows `curve` within `tolerance` slave counts where it can (see the module doc)."""
    masters = [round(p.master * counts_per_mu) for p in curve.fix_points]
    if any(b <= a for a, b in zip(masters, masters[1:], strict=False)):
        raise ValueError("two fix points fall on the same master count: use more counts per MU")

    def slave_counts(master_counts):
        return np.asarray(spline.slave(curve, np.asarray(master_counts, dtype=float) / counts_per_mu)) \
            * counts_per_uu

    segments: list[ApcSegment] = []
    worst = 0.0
    i, last = 0, len(masters) - 1
    while i < last:
        j = _longest_run(masters, i, slave_counts, tolerance)
        pieces, error = _fit(masters[i], masters[j], slave_counts, tolerance, min_master, masters[i:j + 1])
        segments += pieces
        worst = max(worst, error)
        i = j
    start = round(float(slave_counts([masters[0]])[0]))
    table = ApcCamTable(name or _identifier(curve.name), tuple(segments))
    # the table's positions are relative to its first point: measure against the curve shifted likewise
    probe = np.linspace(masters[0], masters[-1], max(2000, 8 * len(segments)))
    drawn = np.array([table.slave_at(int(m) - masters[0]) for m in np.round(probe)]) + start
    worst = max(worst, float(np.max(np.abs(drawn - slave_counts(np.round(probe))))))
    return Conversion(table, None, worst)


SQUARE1 = 2          # the law whose speed ramps linearly from the start speed (0 plus the OutArray2 part)
_SMOOTH_PROBES = 8   # points per segment at which the smooth table is compared with the curve


def curve_to_smooth_table(curve: Curve, *, name: str | None = None, counts_per_mu: float = 1.0,
                          counts_per_uu: float = 1.0, tolerance: float = 2.0,
                          max_segments: int = 8192) -> Conversion:
    """The APC table of Square1 segments with a linear OutArray2 part whose slave speed is continuous at every
    join (also from the last segment to the first when the curve ends at its start speed and travel parity
    allows, see `_smooth_segments`), with the fewest pairs of equal segments that follow `curve` within
    `tolerance` slave counts (or `max_segments`, then the error says how close it came)."""
    start_master = round(curve.fix_points[0].master * counts_per_mu)
    total = round(curve.fix_points[-1].master * counts_per_mu) - start_master
    if total < 2:
        raise ValueError("the curve is shorter than two master counts: use more counts per MU")

    def slave_counts(master_counts):
        return np.asarray(spline.slave(curve, (np.asarray(master_counts, dtype=float) + start_master)
                                       / counts_per_mu)) * counts_per_uu

    def speed(master_counts):
        return np.asarray(spline.velocity(curve, (np.asarray(master_counts, dtype=float) + start_master)
                                          / counts_per_mu)) * counts_per_uu / counts_per_mu

    origin = float(slave_counts([0])[0])

    def build(pairs: int) -> tuple[list[ApcSegment], float]:
        bounds = [round(k * total / (2 * pairs)) for k in range(2 * pairs + 1)]
        at_pairs = bounds[::2]
        positions = np.round(slave_counts(at_pairs) - origin).astype(int)
        speeds = speed(at_pairs)
        speeds[-1] = speeds[0] if abs(speeds[-1] - speeds[0]) < 1e-9 * max(1.0, abs(speeds[0])) else speeds[-1]
        segments = _smooth_segments(bounds, [int(p) for p in positions], [float(v) for v in speeds])
        return segments, _smooth_error(segments, bounds, slave_counts, origin)

    tolerance_before_rounding = max(tolerance - 0.5, tolerance / 2)  # the kernel rounds each value to a count
    pairs = max(1, len(curve.fix_points) - 1)
    best = build(pairs)
    while best[1] > tolerance_before_rounding and 4 * pairs <= min(max_segments, total):
        finer = build(2 * pairs)
        if finer[1] > 0.75 * best[1]:  # whole counts, not the segment length, limit the error now
            break
        pairs, best = 2 * pairs, finer
    enough = max(tolerance_before_rounding, best[1])
    low, high = pairs // 2, pairs  # the fewest pairs that follow the curve as closely
    while high - low > 1:
        middle = (low + high) // 2
        candidate = build(middle)
        if candidate[1] <= enough:
            high, best = middle, candidate
        else:
            low = middle
    for more in range(high, min(2 * high, total // 2) + 1):  # equal lengths: every join exact in whole counts
        if total % (2 * more) == 0:
            candidate = build(more)
            if candidate[1] <= enough:
                best = candidate
                break
    table = ApcCamTable(name or _identifier(curve.name), tuple(best[0]))
    probe = np.unique(np.linspace(0, total, max(2000, 8 * len(best[0]))).round().astype(int))
    drawn = np.array([table.slave_at(int(m)) for m in probe]) + round(origin)
    return Conversion(table, None, float(np.max(np.abs(drawn - slave_counts(probe)))))


def _smooth_segments(bounds: list[int], positions: list[int], speeds: list[float]) -> list[ApcSegment]:
    """Pairs of Square1 + OutArray2 segments over `bounds` (2 per pair): each pair starts at the speed the one
    before ended with (OutArray2 = that speed × X, rounded), ends exactly on `positions`, and chooses how its
    travel splits between its halves so that its end speed is nearest `speeds` (counts per master count)."""
    segments: list[ApcSegment] = []
    speed_in = Fraction(round(speeds[0] * (bounds[1] - bounds[0])), bounds[1] - bounds[0])
    for j in range(len(positions) - 1):
        a, m, b = bounds[2 * j], bounds[2 * j + 1], bounds[2 * j + 2]
        x1, x2 = m - a, b - m
        travel = positions[j + 1] - positions[j]
        y2a = round(speed_in * x1)
        # end speed = 2(D - D1)/X2 - (2 D1 - Y2a)/X1 (the Square1 ramps), solved for D1 and rounded to a count
        d1 = round((2 * travel / x2 + y2a / x1 - speeds[j + 1]) / (2 / x2 + 2 / x1))
        middle = Fraction(2 * d1 - y2a, x1)
        y2b = round(middle * x2)
        d2 = travel - d1
        segments += [ApcSegment(x1, d1 - y2a, SQUARE1, y2a), ApcSegment(x2, d2 - y2b, SQUARE1, y2b)]
        speed_in = Fraction(2 * d2 - y2b, x2)
    return segments


def _smooth_error(segments: list[ApcSegment], bounds: list[int], slave_counts, origin: float) -> float:
    """Largest |table − curve| at `_SMOOTH_PROBES` points inside each segment and at its ends (vectorised; the
    kernel's rounding adds at most half a count)."""
    u = np.linspace(0.0, 1.0, _SMOOTH_PROBES + 1)
    starts = np.cumsum([0] + [s.slave + s.slave2 for s in segments[:-1]])
    y1 = np.array([s.slave for s in segments], dtype=float)[:, None]
    y2 = np.array([s.slave2 for s in segments], dtype=float)[:, None]
    table = starts[:, None] + y1 * u ** 2 + y2 * u
    masters = np.asarray(bounds[:-1], dtype=float)[:, None] + np.diff(bounds)[:, None] * u
    return float(np.max(np.abs(table - (slave_counts(masters.ravel()).reshape(masters.shape) - origin))))


def _longest_run(masters: list[int], i: int, slave_counts, tolerance: float) -> int:
    """The farthest fix point j > i such that one law follows the curve from i to j within the tolerance
    (galloping, then bisection); i + 1 when even the next one needs splitting."""
    def fits(j: int) -> bool:
        return _best_law(masters[i], masters[j], slave_counts, masters[i:j + 1])[1] <= tolerance

    last = len(masters) - 1
    good, step = i + 1, 1
    while good + step <= last and fits(good + step):
        good += step
        step *= 2
    bad = min(good + step, last + 1)
    while bad - good > 1:
        middle = (good + bad) // 2
        if fits(middle):
            good = middle
        else:
            bad = middle
    return good


def _best_law(a: int, b: int, slave_counts, inner=()) -> tuple[int, float, int]:
    """(law, largest error, slave travel) of the law that follows the curve best from master a to b, compared at
    evenly spread points and at the fix points between."""
    ends = slave_counts([a, b])
    y0 = round(float(ends[0]))
    big_x, big_y = b - a, round(float(ends[1])) - y0
    xs = np.unique(np.concatenate([np.linspace(0, big_x, _PROBES).round(), np.asarray(inner, float) - a])
                   .astype(int))
    target = slave_counts(a + xs) - y0
    best_law, best_error = 0, float("inf")
    for law in range(len(LAW_NAMES)):
        values = np.array([law_value(law, int(x), big_x, big_y) for x in xs])
        error = float(np.max(np.abs(values - target)))
        if error < best_error:
            best_law, best_error = law, error
    return best_law, best_error, big_y


def _fit(a: int, b: int, slave_counts, tolerance: float, min_master: int, inner=()) -> tuple[list[ApcSegment], float]:
    """One segment a…b with its best law, or two halves when no law is within the tolerance."""
    law, error, big_y = _best_law(a, b, slave_counts, inner)
    if error <= tolerance or b - a < 2 * min_master:
        return [ApcSegment(b - a, big_y, law)], error
    middle = a + (b - a) // 2
    left, e1 = _fit(a, middle, slave_counts, tolerance, min_master)
    right, e2 = _fit(middle, b, slave_counts, tolerance, min_master)
    return left + right, max(e1, e2)


def _identifier(name: str) -> str:
    cleaned = "".join(ch if ch.isalnum() or ch == "_" else "_" for ch in name) or "Cam"
    return cleaned if cleaned[0].isalpha() else "Cam" + cleaned
