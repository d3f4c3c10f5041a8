"""Run the manuals' example programs of this folder on the simulated controller, through the embedded link as the
IDE and `motiontool run` do (tests/kernel/helpers.py)."""

from __future__ import annotations

from pathlib import Path

from tests.kernel.helpers import Run, start

MANUAL = Path(__file__).parent


def source(name: str) -> str:
    return (MANUAL / name).read_text(encoding="utf-8")


def run_manual(name: str, ms: int = 0, **kw) -> Run:
    """Start the program `name` (a file of this folder) and advance `ms` of controller time, in steps of 100 ms that
    stop once the program has ended."""
    run = start(source(name), **kw)
    for _ in range(0, ms, 100):
        if run.state != "running":
            break
        run.advance(100)
    return run


def variables(run: Run, *names: str) -> list:
    """The values of the program's variables (as the debugger reads them)."""
    return run.link.call("read_variables", names=list(names))
