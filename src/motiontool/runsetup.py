"""What a `motiontool run` is given and what it writes, shared by the APOSS runs (headless.py) and the DPL runs
(headless_dpl.py): the options, the exit codes, the trace file, the `--node`/`[ID:]VALUE` forms. Neither run
module imports the other for these.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from motiontool import cliargs
from motiontool.cliargs import BadNumber, node_id, shown
from motiontool.fileio import AtomicFile, write_error

# 1: nothing ran - a compile error, a file or a command line that was refused (decisions R10); 2: the controller
# stopped the program with an error.
EXIT_OK, EXIT_COMPILE, EXIT_CONTROLLER = 0, 1, 2
EXIT_REFUSED = EXIT_COMPILE
MAX_SECONDS = cliargs.MAX_RUN_SECONDS  # ten days of virtual time


@dataclass
class RunOptions:
    seconds: float = 60.0
    settings: list[str] = field(default_factory=list)       # NAME=VALUE or 32-60=VALUE
    inputs: list[str] = field(default_factory=list)         # N=V@T
    include_dirs: list[Path] = field(default_factory=list)
    trace: Path | None = None
    signals: list[str] = field(default_factory=lambda: ["APOS", "CPOS", "TRACKERR"])
    trace_interval_ms: int = 1
    record: Path | None = None
    realtime: bool = False
    config: Path | None = None                              # .zbc/.cnf loaded before the start
    nodes: list[str] = field(default_factory=list)          # ID:PROGRAM.m: several controllers (run_nodes)
    master_node: int | None = None                          # whose PULSVEL is everyone's master (default lowest)
    link: str | None = None                                 # --link SPEC (comms/links.py); None = the simulator
    timeout: float = 30.0                                   # --timeout: how long a lost link may pause the run
    ctsync_wires: int = 2                                   # .dpl with --node: a 2- or 4-wire CTSync line


class _OutputError(Exception):
    """An output file of the run could not be written: ``cannot write PATH: reason`` (exit 1)."""


class TraceWriter:
    """--trace: rows go to the file while the program runs (an hour of 1 ms rows is some 2 GB in memory); the file
    appears, complete, only at the end (fileio.AtomicFile). With several controllers a row is written once every
    node has sent its samples for that time."""

    def __init__(self, path: Path, nodes: list[int], signals: list[str]):
        self.path = path
        self.nodes = nodes
        self.error: str | None = None  # the first failed write (the run stops; events cannot raise)
        self.file = AtomicFile(path)
        self.pending: dict[int, dict[int, list]] = {n: {} for n in nodes}
        self.latest = {n: -1 for n in nodes}
        self.empty = [""] * len(signals)
        header = ["time_ms", *signals] if len(nodes) == 1 else \
            ["time_ms", *(f"{n}:{s}" for n in nodes for s in signals)]
        self.file.write(",".join(header) + "\n")

    def add(self, node: int, data: dict) -> None:
        rows = self.pending[node]
        for t, values in zip(data["time_ms"], data["values"], strict=True):
            rows[t] = values
            self.latest[node] = max(self.latest[node], t)
        self.flush(min(self.latest.values()))

    def flush(self, until: float = math.inf) -> None:
        times = sorted({t for n in self.nodes for t in self.pending[n] if t <= until})
        lines = []
        for t in times:
            values = [v for n in self.nodes for v in self.pending[n].pop(t, self.empty)]
            lines.append(",".join(str(v) for v in [t, *values]) + "\n")
        if self.error is None:
            try:
                self.file.write("".join(lines))
            except OSError as exc:  # a full disk, a share gone: reported by the run, which then stops
                self.error = write_error(self.path, exc)

    def commit(self) -> None:
        """Put the complete file in place; raises _OutputError when that (or an earlier write) failed."""
        self.flush()
        if self.error is None:
            try:
                self.file.commit()
                return
            except OSError as exc:
                self.error = write_error(self.path, exc)
        raise _OutputError(self.error)

    def discard(self) -> None:
        self.file.discard()


_NODE = re.compile(r"^\s*([^:]*?)\s*:(.+)$")
_FOR_NODE = re.compile(r"^\s*(-?[0-9]{1,9})\s*:(.*)$")  # ASCII digits: \d would take "٢" as node 2


class _Usage(Exception):
    """A bad command line or file: the message goes to stderr, exit 1."""


def _node_programs(path: Path | None, specs: list[str]) -> dict[int, Path]:
    """FILE.m on node 1 (if given) and every --node ID:PROGRAM.m, in the order given."""
    programs: list[tuple[int, Path]] = [(1, path)] if path is not None else []
    for spec in specs:
        m = _NODE.match(spec)
        if not m:
            raise _Usage(f"motiontool run: --node needs ID:PROGRAM.m, got '{shown(spec)}'")
        try:  # the bus says the same; here before anything is compiled
            programs.append((node_id(m.group(1)), Path(m.group(2).strip())))
        except BadNumber as exc:
            raise _Usage(f"motiontool run: {exc}") from None
    nodes = [n for n, _ in programs]
    for n in nodes:
        if nodes.count(n) > 1:
            raise _Usage(f"motiontool run: node id {n} is given twice"
                         + (" (FILE.m runs on node 1)" if path is not None and n == 1 else ""))
    return dict(programs)


def _per_node(values: list[str], nodes: list[int], option: str) -> dict[int, list[str]]:
    """`[ID:]VALUE` options: with ID for that node, without for every node."""
    result: dict[int, list[str]] = {n: [] for n in nodes}
    for value in values:
        m = _FOR_NODE.match(value)
        if m:
            n = int(m.group(1))
            if n not in result:
                raise _Usage(f"motiontool run: {option} {value}: node {n} runs no program (nodes {nodes})")
            result[n].append(m.group(2))
        else:
            for n in nodes:
                result[n].append(value)
    return result
