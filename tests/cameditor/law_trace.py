"""A measured trace of a motion-law curve: the simulated controller runs SETCURVE / SYNCC on the curve's array
while the simulated master turns, and the stream of CMASTERCPOS (SYSVAR 4230, MU) and APOS (UU) is written the
way `motiontool run --trace` writes it."""

from __future__ import annotations

from pathlib import Path

from motiontool.camcurve import Curve, FixPoint, encode
from motiontool.controller.embedded import EmbeddedLink
from motiontool.headless import _write_csv
from motiontool.kernel.master import MasterConfig
from tests.kernel.helpers import start


def law_curve(interpolation: bool = False) -> Curve:
    """Dwell, cycloid rise by 1000 UU, dwell, modified-sine return over a 3600 MU cycle."""
    pts = (FixPoint(0, 0), FixPoint(900, 0, "P345"), FixPoint(1800, 1000, "CYCL"), FixPoint(2700, 1000, "P345"),
           FixPoint(3600, 0, "MSIN"))
    return Curve("drdr", 3600, pts, intervals=36, interpolation=interpolation)


def record_trace(path: Path, curve: Curve, seconds: float = 3.0) -> list[list[float]]:
    """Run the curve for `seconds` (master 3.6 qc/ms after a short ramp: one cycle per second) and write
    time_ms,4230,APOS rows every 2 ms to `path`."""
    values = encode(curve)
    link = EmbeddedLink(master=MasterConfig(velocity=3.6, acceleration=0.01))
    link.call("restore_arrays", arrays=[{"name": curve.name, "values": values}])
    rows: list[list[float]] = []

    def on_event(event) -> None:
        if event.kind == "samples":
            for t, sample in zip(event.data["time_ms"], event.data["values"], strict=True):
                rows.append([t, *sample])

    link.subscribe(on_event)
    link.call("stream", signals=["4230", "APOS"], interval_ms=2)
    source = f"DIM {curve.name}[{len(values)}]\nSETCURVE {curve.name}\nSYNCC 0\nSYNCCSTART 0\nidle:\nGOTO idle\n"
    run = start(source, link=link, settings={"FFVEL": 1000})
    for _ in range(int(seconds * 10)):
        run.advance(100)
    link.call("stream", signals=[], interval_ms=1)
    assert not run.errors, [e.text for e in run.errors]
    _write_csv(path, ["time_ms", "4230", "APOS"], rows)
    link.close()
    return rows
