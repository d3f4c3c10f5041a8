"""Stretches of a steady CAM line (kernel/steady_line.py) give what the same ticks give one by one (issue 30 item 1).

Each case builds the same line twice and advances both by the same uneven steps: once as the bus does (stretches
where the line is steady), once with stretches switched off (every tick through controller_tick). After every step
every controller's whole state — every attribute reachable from it, floats by repr, histories, markers, the
program's stack, the CAN port — and the PRINT output must be the same; and the stretches must have run.
"""

from __future__ import annotations

import math
import random
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.aposs.driver import compile_source
from motiontool.camcurve import Curve, encode
from motiontool.controller.bus import EmbeddedBus
from motiontool.kernel import steady_line
from motiontool.kernel.plant import PlantConfig
from tests.kernel.trace_identity import CAM_POINTS, CAM_SETTINGS, VIRTUAL_MASTER

WAIT_INPUT = "WAITI 8 ON\nPRINT \"input\", APOS\nwait:\nDELAY 250\nPRINT MAPOS\nGOTO wait\n"
DELAY_LOOP = "again:\nDELAY 333\nPRINT APOS, CPOS\nGOTO again\n"


def program(size: int, master: bool | str, tail: str) -> str:
    code = master if isinstance(master, str) else VIRTUAL_MASTER if master else ""
    dims = [t for t in tail.splitlines(keepends=True) if t.startswith("DIM ")]  # DIM comes first (DG 6439)
    rest = "".join(t for t in tail.splitlines(keepends=True) if not t.startswith("DIM "))
    return (f"DIM stamping[{size}]\n{''.join(dims)}SETCURVE stamping\nDEFMCPOS 1000\nPOSA CURVEPOS\n"
            f"{code}SYNCC 0\nSYNCCSTART 0\n{rest}")


def line(axes: int, *, tail: str = WAIT_INPUT, settings: dict | None = None, plants: dict | None = None,
         interpolation: bool = False, masters: dict | None = None) -> tuple[EmbeddedBus, list[str]]:
    values = encode(Curve("stamping", 4000, CAM_POINTS, interpolation=interpolation, intervals=40))
    nodes = range(1, axes + 1)
    bus = EmbeddedBus({n: (plants or {}).get(n) for n in nodes}, master_node=1)
    prints: list[str] = []
    for node in bus.nodes:
        link = bus.link(node)
        link.subscribe(lambda e, node=node: prints.append(f"{node} {e.time_ms} {e.kind} {e.text}")
                       if e.kind in ("print", "error") else None)
        result = compile_source(program(len(values), (masters or {}).get(node, node == 1), tail), "cam.m")
        assert result.ok, result.diagnostics
        link.call("restore_arrays", arrays=[{"name": "stamping", "values": values}])
        for key, value in {**CAM_SETTINGS, **(settings or {})}.items():
            link.write_parameter(key, value)
        link.download(result.image.to_bytes())
        link.start()
    return bus, prints


def snapshot(obj, seen: set | None = None, depth: int = 0):
    """Every attribute reachable from obj (callables left out), floats by repr."""
    seen = set() if seen is None else seen
    if obj is None or isinstance(obj, (bool, int, str, bytes)):
        return obj
    if isinstance(obj, float):
        return repr(obj)
    if isinstance(obj, np.ndarray):
        return repr(obj.tolist())
    if callable(obj) and not hasattr(obj, "__dict__") or depth > 12 or isinstance(obj, type):
        return "-"
    if isinstance(obj, (tuple, frozenset)):  # values: equal ones may or may not be the same object
        items = sorted(obj, key=repr) if isinstance(obj, frozenset) else obj
        return [type(obj).__name__, *(snapshot(v, seen, depth + 1) for v in items)]
    if id(obj) in seen:
        return "seen"
    seen.add(id(obj))
    if isinstance(obj, dict):
        return [(snapshot(k, seen, depth + 1), snapshot(v, seen, depth + 1)) for k, v in obj.items()]
    if isinstance(obj, (list, set)) or hasattr(obj, "maxlen"):
        items = sorted(obj, key=repr) if isinstance(obj, set) else obj
        return [type(obj).__name__, *(snapshot(v, seen, depth + 1) for v in items)]
    fields = getattr(obj, "__dict__", None)
    if fields is None:
        slots = [name for cls in type(obj).__mro__ for name in getattr(cls, "__slots__", ())]
        if not slots:
            return re.sub(r" at 0x[0-9a-f]+", "", repr(obj))
        fields = {name: getattr(obj, name, None) for name in slots}
    return [type(obj).__name__, *((k, snapshot(v, seen, depth + 1)) for k, v in fields.items()
                                  if not callable(v) or hasattr(v, "__dict__") and not hasattr(v, "__func__"))]


def first_difference(a, b, path: str = "") -> str | None:
    """Where two snapshots first differ, as a path of attribute names."""
    if isinstance(a, tuple) and isinstance(b, tuple) and len(a) == len(b) == 2:
        return first_difference(a[1], b[1], path) if a[0] == b[0] else f"{path}: {a[0]} != {b[0]}"
    if type(a) is not type(b) or not isinstance(a, list) or len(a) != len(b):
        return None if a == b else f"{path}: {a!r:.200} != {b!r:.200}"
    for i, (x, y) in enumerate(zip(a, b, strict=True)):
        name = x[0] if isinstance(x, tuple) and len(x) == 2 and isinstance(x[0], str) else str(i)
        found = first_difference(x, y, f"{path}.{name}")
        if found:
            return found
    return None


def compare(build, steps: list[int], monkeypatch, inputs: dict | None = None) -> int:
    """Advance two copies of a line by `steps`; their states after every step are the same. The ticks that ran
    in stretches."""
    stretched: list[int] = []
    run = steady_line.run

    def counted(sim, ms):
        stretched.append(run(sim, ms))
        return stretched[-1]

    results = []
    for patched in (counted, lambda sim, ms: 0):
        monkeypatch.setattr(steady_line, "run", patched)
        bus, prints = build()
        sim, states, elapsed = bus.simulation, [], 0
        for step in steps:
            for at, (node, number) in (inputs or {}).items():
                if elapsed <= at < elapsed + step:
                    bus.link(node).call("schedule_input", number=number, value=1, time_ms=at)
            bus.advance(step)
            elapsed += step
            states.append((sim.time_ms, [snapshot(sim[n]) for n in sim.nodes]))
        results.append((states, prints))
    monkeypatch.setattr(steady_line, "run", run)
    (stretch_states, stretch_prints), (tick_states, tick_prints) = results
    for (time_a, a), (time_b, b) in zip(stretch_states, tick_states, strict=True):
        assert time_a == time_b
        assert a == b, f"after {time_a} ms: {first_difference(a, b)}"
    assert stretch_prints == tick_prints
    return sum(stretched)


def uneven(total: int, seed: int) -> list[int]:
    rng, steps = random.Random(seed), []
    while sum(steps) < total:
        steps.append(rng.choice([1, 7, 15, 16, 40, 100, 333, 700, 2500]))
    return steps


def test_the_benchmark_line_in_uneven_steps(monkeypatch):
    """Engaging, ramping up and the steady line with its index pulses (Markers.tick inside stretches), a WAITI
    that an input ends later (DG: WAITI waits for the input), then a DELAY loop printing."""
    ticks = compare(lambda: line(4), uneven(9000, 1), monkeypatch, inputs={6100: (2, 8), 6400: (3, 8)})
    assert ticks > 4000


VARIANTS = {  # what the benchmark's line does not vary (tests/kernel/test_trace_identity.py's VARIANTS)
    "I and D terms, FFACC": {"settings": {"KINT": 200, "KILIM": 500, "KDER": 300, "FFACC": 200}},
    "I term at KILIM": {"settings": {"KINT": 2000, "KILIM": 1}},
    "TIMER 3": {"settings": {"TIMER": 3, "KPROP": 60}},
    "friction": {"plants": {2: PlantConfig(friction=0.3, speed_tau_ms=9.0)}},
    "interpolation points": {"interpolation": True},
    "DELAY loop": {"tail": DELAY_LOOP},
}


@pytest.mark.parametrize("name", sorted(VARIANTS))
def test_variants(name: str, monkeypatch):
    assert compare(lambda: line(3, **VARIANTS[name]), uneven(6000, 2), monkeypatch) > 2500


def test_a_tracking_error_on_one_node_ends_the_stretch_of_all(monkeypatch):
    """Node 3's motor lags more than the others': its tracking error passes POSERR for a while in every curve
    cycle, which it counts towards POSERRTIME (DG 8913-8933) and forgets below it. Each time the stretch of all
    nodes ends there, and the nodes run before node 3 in it are run again to that tick."""
    build = lambda: line(4, settings={"POSERR": 30, "POSERRTIME": 10000},  # noqa: E731
                         plants={3: PlantConfig(speed_tau_ms=40.0)})
    assert compare(build, uneven(7000, 3), monkeypatch) > 2500
    bus, _ = build()
    bus.advance(5000)
    counts = []
    for _ in range(1000):
        bus.advance(1)
        counts.append(bus.simulation[3].axis._poserr_count)
    assert max(counts) > 0 and min(counts) == 0 and not bus.simulation[3].error


def test_a_counted_tracking_error_is_forgotten_below_poserr(monkeypatch):
    """A tick within POSERR sets the count of ticks beyond it back to 0 (Axis.tick), in a stretch too."""
    def build():
        bus, prints = line(2, settings={"POSERRTIME": 10000})
        bus.advance(3000)
        bus.simulation[2].axis._poserr_count = 7  # as after 7 ticks beyond POSERR (Axis._monitor)
        return bus, prints
    assert compare(build, [100, 400], monkeypatch) > 400


def test_a_blocked_drive_stops_with_error_108(monkeypatch):
    """POSERRTIME ms beyond POSERR: error 108 (DG 8913-8933) at the same tick with stretches as without."""
    build = lambda: line(4, settings={"POSERR": 300, "POSERRTIME": 40},  # noqa: E731
                         plants={3: PlantConfig(blocked=True)})
    compare(build, uneven(5000, 4), monkeypatch)
    bus, prints = build()
    bus.advance(5000)
    assert bus.simulation[3].error is not None and any(p.startswith("3 ") and "error" in p for p in prints)


def test_a_stretch_asked_one_tick_before_a_delay_ends(monkeypatch):
    """The next tick ends a DELAY: no stretch can run, the tick runs generally."""
    def build():
        bus, prints = line(2, tail=DELAY_LOOP)
        bus.advance(3000)
        sim = bus.simulation
        end = min(sim[n].vm.wait.end for n in sim.nodes)
        bus.advance(end - 1 - sim.time_ms)
        return bus, prints
    compare(build, [50, 400], monkeypatch)


def test_a_control_window_never_runs_in_stretches(monkeypatch):
    assert compare(lambda: line(2, settings={"REGWMIN": 5, "REGWMAX": 50}), [3000, 100], monkeypatch) == 0


MASTERS = {  # review of ccc414c: master speeds the benchmark's line does not have
    "negative master speed": {1: "PULSACC 100000\nPULSVEL -37236\n"},
    "a second node's own PULSVEL": {3: "PULSACC 50000\nPULSVEL 20000\n"},
    "curve cycles out of phase": {1: VIRTUAL_MASTER, 2: "DEFMCPOS 2500\n", 3: "DEFMCPOS 1700\n"},
}


@pytest.mark.parametrize("name", sorted(MASTERS))
def test_master_speeds(name: str, monkeypatch):
    assert compare(lambda: line(3, masters=MASTERS[name]), uneven(6000, 5), monkeypatch) > 2500


def test_requests_between_advances(monkeypatch):
    """A parameter written and the virtual master stopped ([Esc], DG 10782) between two advances: the next
    stretch starts from what they changed."""
    def build():
        bus, prints = line(3)
        bus.advance(3000)
        bus.link(2).write_parameter("KPROP", 90)
        bus.advance(500)
        bus.simulation[1].master.stop_virtual()
        return bus, prints
    assert compare(build, [1, 40, 700, 2500], monkeypatch) > 2500


def test_print_output_taken_line_by_line(monkeypatch):
    """A link that takes one PRINT line per ms (a paced link's rate): the lines a DELAY loop prints leave over
    the next ticks, each at its own time, so the line is not steady while any is left."""
    def build():
        bus, prints = line(2, tail="again:\nDELAY 150\n" + "PRINT APOS\n" * 40 + "GOTO again\n")
        for node in bus.nodes:
            bus.simulation[node].output_per_tick = 1
        return bus, prints
    assert compare(build, uneven(5000, 6), monkeypatch) > 1500


def test_an_armed_interrupt_keeps_the_line_general(monkeypatch):
    """ON PERIOD n every n ms (DG 6325-6351) while the program waits in WAITI: a tick may run the handler, so
    no stretch runs; the handler's PRINT comes at the same ms."""
    tail = "ON PERIOD 170 GOSUB beat\nWAITI 8 ON\nPRINT 0\nSUBMAINPROG\nSUBPROG beat\nPRINT APOS\nRETURN\n" \
        "ENDPROG\n"
    assert compare(lambda: line(2, tail=tail), [2000, 333, 700], monkeypatch) == 0


def test_a_software_limit_reached_in_the_line(monkeypatch):
    """POSLIMIT active (SWPOSLIMACT): the CAM axis reaching it stops with error 111 (DG 10213) at the same ms."""
    build = lambda: line(2, settings={"POSLIMIT": 30000, "SWPOSLIMACT": 1})  # noqa: E731
    compare(build, uneven(6000, 7), monkeypatch)
    bus, prints = build()
    bus.advance(6000)
    assert any(" error " in p for p in prints)


@settings(max_examples=200, deadline=None)
@given(st.floats(-1e9, 1e9), st.lists(st.floats(-1e4, 1e4), min_size=1, max_size=300))
def test_accumulate_adds_in_sequence(start: float, increments: list[float]):
    """The stretch's master positions: numpy's running sum is the tick's `position = position + v`, bit for bit."""
    steps = np.array([start, *increments])
    position, expected = start, []
    for v in increments:
        position = position + v
        expected.append(position)
    assert np.add.accumulate(steps)[1:].tolist() == expected
    assert [math.floor(p) for p in expected] == np.floor(np.add.accumulate(steps)[1:]).astype(int).tolist()


def test_a_testsetp_recording_runs_tick_by_tick(monkeypatch):
    """TESTSETP/TESTSTART record every interval (DG 7121-7135): while the recorder runs, no stretch; after it, the
    line runs in stretches again and the array holds the same samples."""
    tail = "DIM rec[4500]\nTESTSETP 2 4097 4098 4102 rec\nTESTSTART 0\n" + WAIT_INPUT  # 3 s of samples
    assert compare(lambda: line(2, tail=tail), uneven(6500, 9), monkeypatch) > 1000

