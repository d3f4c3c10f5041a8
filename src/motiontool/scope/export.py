"""Export of curves to CSV (DG 5887-5905, ide-spec 6.52, 7.9)."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np

from motiontool.fileio import atomic_write_text
from motiontool.scope.curves import OTHER_CURVES, Curve, Scope


def export_csv_text(scope: Scope) -> str:
    """DG 5891-5905: row 1 each group's or curve's name followed by an empty cell, row 2 "X,Y" for every
    column pair, then data rows where group columns stay empty and each curve has its own time and value.
    Values are exported as shown in the list (scaling applied; smoothing, a display aid, is not)."""
    blocks: list[tuple[str, Curve | None]] = []
    for g in scope.groups:
        blocks.append((g.name, None))
        blocks += [(c.name, c) for c in scope.members(g.name)]
    others = [c for c in scope.curves if not c.source.group or c.source.group not in {g.name for g in scope.groups}]
    if others:
        blocks.append((OTHER_CURVES, None))
        blocks += [(c.name, c) for c in others]
    data: list[tuple[np.ndarray, np.ndarray] | None] = []
    for _, curve in blocks:
        if curve is None:
            data.append(None)
        else:
            t, y = curve.raw()
            data.append((t, curve.scaled(y)))
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow([cell for name, _ in blocks for cell in (name, "")])
    w.writerow(["X", "Y"] * len(blocks))
    rows = max((d[0].size for d in data if d is not None), default=0)
    for i in range(rows):
        row = []
        for d in data:
            if d is None or i >= d[0].size:
                row += ["", ""]
            else:
                row += [_fmt(d[0][i]), _fmt(d[1][i])]
        w.writerow(row)
    return out.getvalue()


def _fmt(v: float) -> str:
    return str(int(v)) if float(v).is_integer() and abs(v) < 1e15 else repr(float(v))


def export_csv(scope: Scope, path: Path | str) -> None:
    atomic_write_text(path, export_csv_text(scope))
