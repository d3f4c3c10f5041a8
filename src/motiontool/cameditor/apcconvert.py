"""Converting between MCO fix-point curves and APC CAM tables (spec §7.2) — Qt-free.

The two models differ: the MCO curve is a spline through absolute fix points (master in MU, slave in UU); an
APC table is a chain of relative segments in counts, each with one of six closed-form laws. Neither converts
exactly into the other, so both directions report the largest position error they introduce.

* APC → MCO: every segment is sampled into fix points (its ends and `points_per_segment` - 1 points inside); the
  editor's spline through them follows the laws closely, and the error is measured densely.
* MCO → APC: from each fix point the longest run of fix-point segments that one law follows within the tolerance
  becomes one APC segment (the law that fits best; same ends, so the positions are exact at those fix points);
  where not even a single fix-point segment fits, it is split in half, down to `min_master` counts (spec §7.2:
  "several short linear segments, error bounded").
"""

from __future__ import annotations

from dataclasses import dataclass

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
