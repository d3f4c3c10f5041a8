"""Two or more simulated controllers on one CAN bus (kernel/simulation.py + kernel/canbus.py), programs from source."""

from __future__ import annotations

from motiontool.aposs.driver import compile_source
from motiontool.kernel.canbus import CanFrame
from motiontool.kernel.simulation import Simulation


def bus(programs: dict[int, str], settings: dict[int, dict] | None = None) -> Simulation:
    """A simulation with one controller per entry; each runs its program from tick 1."""
    sim = Simulation(list(programs))
    for node, source in programs.items():
        for key, value in (settings or {}).get(node, {}).items():
            sim[node].params.set(key, value, source="link")
        if source:
            result = compile_source(source, f"node{node}.m")
            assert result.ok, "\n".join(d.format() for d in result.diagnostics)
            sim[node].load(result.image)
            sim[node].start()
    return sim


def prints(sim: Simulation, node: int) -> list[str]:
    return [e.text for e in sim[node].events if e.kind == "print"]


def errors(sim: Simulation, node: int) -> list[int]:
    return [e.number for e in sim[node].events if e.kind == "error"]


def tap(sim: Simulation) -> list[tuple[int, CanFrame]]:
    """Every frame the controllers send, with the simulation time it left at."""
    frames: list[tuple[int, CanFrame]] = []
    sim.can_bus.outlets.append(lambda frame: frames.append((sim.time_ms, frame)))
    return frames
