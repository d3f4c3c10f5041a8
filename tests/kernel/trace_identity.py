"""Runs for test_trace_identity.py: programs on the kernel, fingerprinted every ms (issue 30 item 1).

A run's fingerprint is one sha256 per simulated second of its rows (each row: time, APOS, CPOS, the commanded and
the actual velocity, the speed reference, the plant position, mode, program state, error, outputs, MAPOS, for every
node), plus one sha256 of all PRINT lines with their times; floats by repr, so a change in the last bit shows.
`python -m tests.kernel.trace_identity` writes the golden file from the kernel as it is.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable, Iterator
from pathlib import Path

from motiontool.aposs.driver import compile_source
from motiontool.camcurve import Curve, FixPoint, encode
from motiontool.controller.bus import EmbeddedBus
from motiontool.controller.embedded import EmbeddedLink
from motiontool.kernel.master import MasterConfig
from tests.kernel.test_cam_examples import MARKER, QC_PER_MU, STAMPING, run_example, start_conveyor
from tests.test_samples import SAMPLES, parse_header
from tests.trace_hash import SecondHashes, text_hash

GOLDEN = Path(__file__).parent / "golden" / "trace_identity.json"
SAMPLE_MS = 5_000  # each sample's first 5 s (tests/test_samples.py runs them for their whole Test-seconds)

# the CAM line of benchmarks/kernel_rtf.py: DG stamping curve (fix points, MCO >= 5.00) on node 1's virtual master
CAM_POINTS = (FixPoint(0, 0), FixPoint(1500, 1200, "T"), FixPoint(2500, 2400, "T"), FixPoint(4000, 3600))
CAM_SETTINGS = {"SYNCFACTM": 2048, "SYNCFACTS": 55, "POSFACT_Z": 25, "POSFACT_N": 9, "ENCODER": 500,
                "FFVEL": 1000, "DFLTVEL": 100, "DFLTACC": 100}
VIRTUAL_MASTER = "PULSACC 100000\nPULSVEL 37236\n"
LOOP = "wait:\nDELAY 100\nGOTO wait\n"
SYNC_PROGRAMS = {  # tests/kernel/test_sync.py's SYNCV / SYNCP / SYNCM programs on a virtual master
    "syncv": "PULSACC 50000\nPULSVEL 20000\nVEL 100\nACC 100\nDEC 50\nSYNCV\nDELAY 1500\nMOTOR STOP\nPRINT AXEND\n"
             "CONTINUE\nDELAY 100\nPRINT AXEND\n" + LOOP,
    "syncp_syncm": "PULSVEL 1000\nVEL 100\nACC 100\nDEC 100\nMOVESYNCORIGIN 600\nSYNCP\nDELAY 1000\n"
                   "PRINT CPOS - (MAPOS - 100000)\nMOVESYNCORIGIN -200\nDELAY 500\nSYNCP\nDELAY 500\n"
                   "PRINT CPOS - (MAPOS - 100000)\nMOTOR STOP\nDELAY 200\nc = CPOS\nm = MAPOS\nSYNCM\nDELAY 500\n"
                   "PRINT CPOS - c - (MAPOS - m)\n" + LOOP,
}


def row(c) -> tuple:
    axis = c.axis
    pg, plant = axis.profile, axis.plant
    return (c.time_ms, axis.apos, pg.position, pg.velocity, plant.velocity, axis.reference, plant.position,
            axis.mode, c.program_state, c.error, sorted(c.io.outputs.items()), c.master.mapos)


class Fingerprint:
    def __init__(self) -> None:
        self.prints: list[str] = []
        self._rows = SecondHashes()

    def add(self, rows: list[tuple]) -> None:
        self._rows.add(rows)

    def result(self) -> dict:
        return {**self._rows.finish(), "prints": text_hash(self.prints), "print_count": len(self.prints)}


def _listen(link, fp: Fingerprint, node: int = 0) -> None:
    link.subscribe(lambda e: fp.prints.append(f"{node} {e.time_ms} {e.kind} {e.text}")
                   if e.kind in ("print", "error") else None)


def trace_link(link: EmbeddedLink, ms: int, fp: Fingerprint) -> dict:
    """Tick the link's controller `ms` times as its advance does, fingerprinting every ms."""
    tick, c = link.service.tick, link.service.controller
    for _ in range(ms):
        tick()
        fp.add([row(c)])
    link.close()
    return fp.result()


def run_sample(path: Path) -> dict:
    header = parse_header(path)
    result = compile_source(path=path)
    assert result.ok and result.image is not None
    link, fp = EmbeddedLink(), Fingerprint()
    _listen(link, fp)
    for name, value in header.settings:
        link.write_parameter(name, value)
    for number, value, at in header.inputs:
        link.call("schedule_input", number=number, value=value, time_ms=at)
    link.download(result.image.to_bytes())
    link.start()
    return trace_link(link, min(SAMPLE_MS, int(header.seconds * 1000)), fp)


def run_source(source: str, ms: int) -> dict:
    result = compile_source(source, "identity.m")
    assert result.ok, [d.format() for d in result.diagnostics]
    link, fp = EmbeddedLink(), Fingerprint()
    _listen(link, fp)
    link.download(result.image.to_bytes())
    link.start()
    return trace_link(link, ms, fp)


def run_manual_cam(program: Path, curve_factory, switch_off_at: int | None = None, **kw) -> dict:
    """DG 1474-1494 (D07) / the printing with marker (D08) as tests/kernel/test_cam_examples.py runs them: HOME,
    SETCURVE, POSA CURVEPOS, then the conveyor starts; D08's input 4 switches it off (SYNCCSTOP)."""
    fp = Fingerprint()
    run = run_example(program, curve_factory(), **kw)
    _listen(run.link, fp)
    start_conveyor(run.controller)
    if switch_off_at is not None:
        run.link.call("schedule_input", number=4, value=1, time_ms=run.controller.time_ms + switch_off_at)
    return trace_link(run.link, 6000, fp)


def cam_program(size: int, master: bool) -> str:
    return (f"DIM stamping[{size}]\nSETCURVE stamping\nDEFMCPOS 1000\nPOSA CURVEPOS\n"
            f"{VIRTUAL_MASTER if master else ''}SYNCC 0\nSYNCCSTART 0\nWAITI 8 ON\n")


def cam_bus(axes: int, interpolation: bool = False, settings: dict | None = None, plant=None) -> EmbeddedBus:
    values = encode(Curve("stamping", 4000, CAM_POINTS, interpolation=interpolation, intervals=40))
    nodes = range(1, axes + 1)
    bus = EmbeddedBus(dict.fromkeys(nodes, plant) if plant else nodes, master_node=1)
    for node in bus.nodes:
        link = bus.link(node)
        result = compile_source(cam_program(len(values), node == 1), "cam.m")
        assert result.ok
        link.call("restore_arrays", arrays=[{"name": "stamping", "values": values}])
        for key, value in {**CAM_SETTINGS, **(settings or {})}.items():
            link.write_parameter(key, value)
        link.download(result.image.to_bytes())
        link.start()
    return bus


def run_cam_bus(axes: int, ms: int, interpolation: bool = False, chunk: int = 1) -> dict:
    """The benchmark's CAM line from power-up (engaging, ramping up, steady), advanced `chunk` ms at a time
    through the bus (rows only at chunk ends when chunk > 1: the fingerprint then differs by design)."""
    bus, fp = cam_bus(axes, interpolation), Fingerprint()
    for node in bus.nodes:
        _listen(bus.link(node), fp, node)
    controllers = [bus.simulation[n] for n in bus.nodes]
    for _ in range(ms // chunk):
        bus.advance(chunk)
        fp.add([row(c) for c in controllers])
    return fp.result()


def runs() -> Iterator[tuple[str, Callable[[], dict]]]:
    for path in SAMPLES:
        yield f"sample {path.name}", lambda path=path: run_sample(path)
    yield "manual D07_cam_stamping", lambda: run_manual_cam(STAMPING, _stamping)
    yield "manual D08_cam_marker_correction", lambda: run_manual_cam(
        MARKER, _marker, switch_off_at=4000, master=MasterConfig(marker_period_qc=4000 * QC_PER_MU,
                                                                 marker_offset_qc=20000),
        settings={"SYNCMPULSM": 2375, "SYNCMWINM": 200, "SYNCMTYPM": 2})
    for name, source in SYNC_PROGRAMS.items():
        yield f"sync {name}", lambda source=source: run_source(source, 4000)
    yield "cam 1 axis interpolated", lambda: run_cam_bus(1, 4000, interpolation=True)
    yield "cam 8 axes", lambda: run_cam_bus(8, 4000)
    yield "cam 8 axes in 100 ms steps", lambda: run_cam_bus(8, 4000, chunk=100)


def _stamping():
    from tests.camcurve.conftest import stamping_curve
    return stamping_curve()


def _marker():
    from tests.camcurve.conftest import marker_curve
    return marker_curve()


def main() -> None:
    golden = {name: run() for name, run in runs()}
    GOLDEN.parent.mkdir(exist_ok=True)
    GOLDEN.write_text(json.dumps(golden, indent=0, sort_keys=True) + "\n", encoding="utf-8")
    print(f"wrote {GOLDEN} ({len(golden)} runs)", file=sys.stderr)


if __name__ == "__main__":
    main()
