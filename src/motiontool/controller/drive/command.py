"""`motiontool drive`: simulated controllers in their own process behind one or more listeners, until SIGINT/SIGTERM.

    motiontool drive --listen fc:socket://127.0.0.1:0 --node 1:master.m --node 2 [--clock virtual]

Every listener prints one line ``listening on URL`` (URL is what a master gives to ``--link``) once it serves; the
process then runs until it is interrupted or terminated and stops cleanly (listeners closed, exit status 0).
"""

from __future__ import annotations

import os
import re
import signal
import sys
import threading
from dataclasses import dataclass, field
from pathlib import Path
from typing import TextIO

from motiontool.cliargs import node_id
from motiontool.comms.protocol import LinkError
from motiontool.controller.drive.listeners import open_listener
from motiontool.controller.drive.simulator import VirtualDrive

_NODE = re.compile(r"^\s*([^:]*?)\s*(?::(.+))?$")  # the id is read by cliargs.node_id (ASCII digits, 1..32)
MAX_SPEED = 1000.0          # --speed: a realtime factor beyond this is no longer real time
MAX_TIMEOUT_S = 24 * 3600.0  # --timeout


@dataclass
class DriveOptions:
    listen: list[str] = field(default_factory=list)
    nodes: list[str] = field(default_factory=list)          # ID or ID:PROGRAM.m
    master_node: int | None = None
    clock: str = "realtime"
    speed: float = 1.0
    timeout_s: float | None = None
    timeout_reaction: str = "stop"
    include_dirs: list[Path] = field(default_factory=list)
    stop_with_parent: bool = False     # end when stdin reaches EOF or the parent process goes away


def _node_specs(specs: list[str]) -> dict[int, Path | None]:
    nodes: dict[int, Path | None] = {}
    for spec in specs or ["1"]:
        m = _NODE.match(spec)
        if not m:
            raise ValueError(f"--node needs ID or ID:PROGRAM.m, got '{spec}'")
        n = node_id(m.group(1))
        if n in nodes:
            raise ValueError(f"--node {n} is given twice")
        nodes[n] = Path(m.group(2).strip()) if m.group(2) else None
    return nodes


def build_drive(options: DriveOptions, err: TextIO = sys.stderr) -> VirtualDrive | None:
    """The drive with its programs installed, or None after printing why on err."""
    from motiontool.aposs.driver import compile_source

    try:
        programs = _node_specs(options.nodes)
        drive = VirtualDrive(sorted(programs), master_node=options.master_node, clock=options.clock,
                             speed=options.speed, timeout_s=options.timeout_s,
                             timeout_reaction=options.timeout_reaction)
    except ValueError as exc:
        print(f"motiontool drive: {exc}", file=err)
        return None
    for n, path in programs.items():
        if path is None:
            continue
        result = compile_source(path=path, include_dirs=options.include_dirs)
        for d in result.diagnostics:
            print(d.format(), file=err)
        if not result.ok:
            return None
        assert result.image is not None  # compile_source leaves it None only with an error
        drive.install_program(n, result.image)
    return drive


def _watch_parent(stop: threading.Event) -> None:
    """Set `stop` when stdin ends (the parent closed its pipe or died) or the parent process changes (orphaned)."""
    parent = os.getppid()

    def stdin_ends() -> None:
        # the file descriptor, not sys.stdin: a thread blocked in a buffered read holds its lock, and the
        # interpreter aborts when it finds that lock taken at exit
        try:
            while os.read(0, 4096):
                pass
        except OSError:
            pass
        stop.set()

    def parent_gone() -> None:
        while not stop.wait(0.5):
            if os.getppid() != parent:
                stop.set()

    threading.Thread(target=stdin_ends, name="drive-stdin", daemon=True).start()
    threading.Thread(target=parent_gone, name="drive-parent", daemon=True).start()


def run_drive(options: DriveOptions, out: TextIO | None = None, err: TextIO | None = None) -> int:
    out, err = out or sys.stdout, err or sys.stderr  # looked up now: a caller may have redirected them
    drive = build_drive(options, err)
    if drive is None:
        return 1
    stop = threading.Event()
    previous = {sig: signal.signal(sig, lambda *_: stop.set()) for sig in (signal.SIGINT, signal.SIGTERM)}
    listeners = []
    try:
        try:
            for spec in options.listen:
                listeners.append(open_listener(spec, drive))
        except LinkError as exc:
            print(f"motiontool drive: {exc}", file=err)
            return 1
        drive.start()
        if options.stop_with_parent:
            _watch_parent(stop)
        for listener in listeners:
            print(f"listening on {listener.url}", file=out, flush=True)
        while not stop.wait(0.2):
            pass
        return 0
    finally:
        for listener in listeners:
            listener.close()
        drive.stop()
        for sig, handler in previous.items():
            signal.signal(sig, handler)
