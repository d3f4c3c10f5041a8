"""Export of curves to ASAM MDF 4 (.mf4) through asammdf, when it is installed (issue 8 "export curves to
txt/CSV (and MDF4 via asammdf if installed)"). asammdf is not a dependency of motiontool: without it the export
raises `Mdf4Unavailable` with a message saying what to install; nothing else imports it.

Each curve with data becomes one channel group (curves have their own time bases), named after the curve's
group ("Other Curves" for polled, derived and file curves) as acquisition name. Time is the controller clock
in seconds (MDF's master channel unit); values are exported as shown in the list, scaling applied and smoothing
not, like the CSV export (docs/formats/zbo.md).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from motiontool.scope.curves import OTHER_CURVES, Scope

MESSAGE = ("MDF4 export needs the optional package asammdf, which is not installed "
           "(install it into motiontool's environment: pip install asammdf). CSV export works without it.")


class Mdf4Unavailable(RuntimeError):
    pass


def export_mdf4(scope: Scope, path: Path | str) -> Path:
    """Write the curves with data to `path` (MDF 4.10); returns the path written."""
    try:
        import asammdf
    except ImportError:
        raise Mdf4Unavailable(MESSAGE) from None
    groups = {g.name for g in scope.groups}
    mdf = asammdf.MDF(version="4.10")
    try:
        for curve in scope.curves:
            t, y = curve.raw()
            if t.size == 0:
                continue
            signal = asammdf.Signal(samples=np.asarray(curve.scaled(y), dtype=np.float64),
                                    timestamps=np.asarray(t, dtype=np.float64) / 1000.0,
                                    name=curve.name, unit=curve.unit,
                                    comment=f"motiontool oscilloscope, source {curve.source.method} "
                                            f"{curve.source.signal}".strip())
            group = curve.source.group if curve.source.group in groups else OTHER_CURVES
            mdf.append([signal], acq_name=group, comment=curve.name)
        written = mdf.save(Path(path), overwrite=True)
    finally:
        mdf.close()
    return Path(written) if written else Path(path)
