"""`motiontool run FILE.dpl`: DPL programs on simulated APCs (Unidrive SP with SM-Applications, docs/dpl.md), one
or several on one CTSync line; the command line, output files and exit codes are those of headless.py."""

from __future__ import annotations

import re
from pathlib import Path
from typing import TextIO

from motiontool.cliargs import PARAMETER_VALUE, BadNumber, shown, whole
from motiontool.comms.protocol import LinkError, LinkEvent
from motiontool.dpl.driver import check_source, is_dpl
from motiontool.fileio import write_error
from motiontool.headless import (
    EXIT_COMPILE,
    EXIT_CONTROLLER,
    EXIT_OK,
    EXIT_REFUSED,
    MAX_SECONDS,
    RunOptions,
    TraceWriter,
    _node_programs,
    _OutputError,
    _per_node,
    _Usage,
)

MCO_SIGNALS = ["APOS", "CPOS", "TRACKERR"]
DPL_SIGNALS = ["APC_FB_POS", "APC_TOT_POS_REF", "APC_POS_ERROR"]
_DPL_SET = re.compile(r"^#?([0-9]{1,2})\.([0-9]{1,2})=([^@]+)(?:@(.+))?$")  # numbers: cliargs.whole


def run_dpl(path: Path | None, options: RunOptions, err: TextIO) -> int:
    """`motiontool run FILE.dpl [--node ID:OTHER.dpl …]`: check the programs, download each to a simulated APC
    (several: one CTSync line, the drives in lockstep) and run them for --seconds. `--set [ID:]MM.PP=VALUE[@MS]`
    writes a drive parameter before the start or at MS ms (#1.11 = 0/1 is the drive's run command); trace columns
    are read parameters (alias or number) or drive parameters (18.12), 'ID:SIGNAL' with several nodes. A DPL
    program prints nothing: stderr gets the diagnostics and run-time errors ('ID: …' with several nodes); exit 1
    on a check error, 2 on a run-time error."""
    from motiontool.comms.dpl_program import dpl_line
    from motiontool.dpl.image import DplImage

    try:
        programs = _node_programs(path, options.nodes)
        nodes = sorted(programs)
        settings = _per_node(options.settings, nodes, "--set")
    except _Usage as exc:
        print(str(exc), file=err)
        return EXIT_COMPILE
    several = len(nodes) > 1
    if options.link not in (None, "sim", "apcsim") or options.config or options.inputs or options.record \
            or options.master_node is not None or not all(is_dpl(p) for p in programs.values()):
        print("motiontool run: DPL programs run on the embedded APC simulator, all of them .dpl (no --link, "
              "--config, --input, --record or --master-node: the program names the CTSync master, #81.06 = 25)",
              file=err)
        return EXIT_COMPILE
    checked = {n: check_source(path=programs[n]) for n in nodes}
    for n in nodes:
        for d in checked[n].diagnostics:
            print(d.format(), file=err)
    if not all(c.ok for c in checked.values()):
        return EXIT_COMPILE
    writes = []
    for n in nodes:
        for setting in settings[n]:
            m = _DPL_SET.match(setting.replace(" ", ""))
            if not m:
                print(f"motiontool run: --set needs {'[ID:]' if several else ''}MM.PP=VALUE or MM.PP=VALUE@MS for "
                      f"a DPL program, got '{setting}'", file=err)
                return EXIT_COMPILE
            try:
                value = whole(m.group(3), f"--set {m.group(1)}.{m.group(2)}", *PARAMETER_VALUE, hex=True, sep="=")
                at = whole(m.group(4) or "0", f"--set {shown(setting)}: time", 0, MAX_SECONDS * 1000)
            except BadNumber as exc:
                print(f"motiontool run: {exc}", file=err)
                return EXIT_COMPILE
            writes.append((at, n, f"{int(m.group(1))}.{int(m.group(2)):02d}", value))
    writes.sort(key=lambda w: w[0])
    signals = DPL_SIGNALS if options.signals == MCO_SIGNALS else options.signals
    failed: list[int] = []
    try:  # rows go to the file as they come (an hour of 1 ms rows was 656 MB in memory; decisions R6, R18)
        trace = TraceWriter(options.trace, nodes, list(signals)) if options.trace else None
    except OSError as exc:
        print(f"motiontool run: {write_error(options.trace, exc)}", file=err)
        return EXIT_REFUSED

    def listener(n: int):
        prefix = f"{n}: " if several else ""

        def on_event(event: LinkEvent) -> None:
            if event.kind == "error":
                print(prefix + event.text, file=err)
            elif event.kind == "program" and event.text == "program error":
                failed.append(n)
            elif event.kind == "samples" and trace is not None:
                trace.add(n, event.data)
        return on_event

    bus = dpl_line(len(nodes))
    links = {n: bus.link(k) for k, n in enumerate(nodes, start=1)}
    try:
        for n, link in links.items():
            link.subscribe(listener(n))
        while writes and writes[0][0] == 0:
            _, n, key, value = writes.pop(0)
            links[n].write_parameter(key, value)
        for n, link in links.items():
            if options.trace:
                link.call("stream", signals=signals, interval_ms=options.trace_interval_ms)
            link.download(DplImage(str(programs[n]), checked[n].source).to_bytes(), name=programs[n].name)
        for link in links.values():
            link.start()
        _advance_with_writes(bus, links, writes, int(options.seconds * 1000), options.realtime, failed, trace)
        if trace is not None:
            for link in links.values():
                link.call("stream", signals=[], interval_ms=1)
                link.flush_events()
            trace.commit()
            trace = None
    except LinkError as exc:
        print(f"motiontool run: {exc}", file=err)
        return EXIT_CONTROLLER
    except _OutputError as exc:  # a full disk, a file-size limit: the old file stays
        print(f"motiontool run: {exc}", file=err)
        return EXIT_REFUSED
    finally:
        bus.close()
        if trace is not None:  # not committed: the old file stays
            trace.discard()
    return EXIT_CONTROLLER if failed else EXIT_OK


def _advance_with_writes(bus, links: dict, writes: list, total: int, realtime: bool, failed: list,
                        trace: TraceWriter | None = None) -> None:
    """Virtual time for the whole line in steps of at most 50 ms, stopping at every timed parameter write; ends
    early after a run-time error or a failed trace write (reported by the trace's commit)."""
    import time

    elapsed, started = 0, time.monotonic()
    while elapsed < total and not failed and (trace is None or trace.error is None):
        step = min(50, total - elapsed, *(t - elapsed for t, *_ in writes[:1]))
        bus.advance(step)
        elapsed += step
        while writes and writes[0][0] <= elapsed:
            _, n, key, value = writes.pop(0)
            links[n].write_parameter(key, value)
        for link in links.values():
            link.flush_events()
        if realtime:
            time.sleep(max(0.0, elapsed / 1000 - (time.monotonic() - started)))
