"""The kernel's traces stay identical row for row (issue 30 item 1: a faster kernel must not change a result).

Every sample (its first 5 s), the Design Guide's CAM programs D07/D08, SYNCV/SYNCP/SYNCM programs and the CAM line
of benchmarks/kernel_rtf.py (1 axis interpolated, 8 axes on one EmbeddedBus with node 1's virtual master, tick by
tick and in 100 ms steps) are fingerprinted every ms (tests/kernel/trace_identity.py) and compared with the
fingerprints of the kernel before its optimisation (golden/trace_identity.json). A deliberate change of behaviour
regenerates the golden file with `python -m tests.kernel.trace_identity` and says why in its commit.
"""

from __future__ import annotations

import json

import pytest

from motiontool.kernel import tick
from motiontool.kernel.plant import PlantConfig
from tests.kernel.trace_identity import GOLDEN, cam_bus, row, runs
from tests.trace_hash import first_different_second

GOLDEN_RUNS = json.loads(GOLDEN.read_text(encoding="utf-8"))
RUNS = dict(runs())


def test_every_golden_run_is_still_run():
    assert sorted(RUNS) == sorted(GOLDEN_RUNS)


@pytest.mark.parametrize("name", sorted(RUNS))
def test_trace_is_identical_row_for_row(name: str):
    got, want = RUNS[name](), GOLDEN_RUNS[name]
    difference = first_different_second(name, got, want)
    assert difference is None, difference
    assert (got["prints"], got["print_count"]) == (want["prints"], want["print_count"]), f"{name}: PRINT output"


# the position law's other terms, a slower law, the control window, a drive with friction or blocked, POSERRTIME
VARIANTS = {
    "I and D terms, FFACC": ({"KINT": 200, "KILIM": 500, "KDER": 300, "FFACC": 200}, None),
    "TIMER 3": ({"TIMER": 3, "KPROP": 60}, None),
    "control window": ({"REGWMIN": 5, "REGWMAX": 50}, None),
    "friction": ({}, PlantConfig(friction=0.3, speed_tau_ms=9.0)),
    "blocked drive, POSERRTIME": ({"POSERR": 300, "POSERRTIME": 400}, PlantConfig(blocked=True)),
}


@pytest.mark.parametrize("name", sorted(VARIANTS))
def test_the_fused_cam_tick_equals_the_general_one(name: str, monkeypatch):
    """kernel/tick.py's steady CAM tick against Axis.tick + CamMotion.step + Plant.step on settings the golden
    runs do not vary: the same rows, every ms, on both axes of a two-node line."""
    settings, plant = VARIANTS[name]

    def rows() -> list:
        bus = cam_bus(2, settings=settings, plant=plant)
        controllers = [bus.simulation[n] for n in bus.nodes]
        out = []
        for _ in range(3000):
            bus.advance(1)
            out.append([row(c) for c in controllers])
        return out

    steady, fused_tick = [], tick.steady_cam_tick
    with monkeypatch.context() as m:     # counted: the comparison proves nothing if the fused tick never runs
        m.setattr(tick, "steady_cam_tick", lambda axis: steady.append(fused_tick(axis)) or steady[-1])
        fused = rows()
    with monkeypatch.context() as m:
        m.setattr(tick, "steady_cam_tick", lambda axis: False)
        general = rows()
    assert fused == general
    assert sum(steady) > len(steady) // 2
