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
from motiontool.runsetup import (
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
    (several: one CTSync line of --ctsync-wires 2 or 4, the drives in lockstep) and run them for --seconds.
    `--set [ID:]MM.PP=VALUE[@MS]` writes a drive parameter before the start or at MS ms (#1.11 = 0/1 is the
    drive's run command, #3.34 the encoder's lines); `--input [ID:]NAME=V[@MS]` sets DIGIN0 (the freeze input)
    or gives a marker pulse (`_inputs`); trace columns are read parameters (alias or number) or drive parameters
    (18.12), 'ID:SIGNAL' with several nodes. A DPL program prints nothing: stderr gets the diagnostics and
    run-time errors ('ID: …' with several nodes); exit 1 on a check error or a refused option, 2 on a run-time
    error (a node leaving the line's POS rate is one)."""
    from motiontool.apc.ctsync import MAX_NODES_2WIRE, MAX_NODES_4WIRE, CTSyncRateError
    from motiontool.controller.dpl_program import dpl_line
    from motiontool.dpl.image import DplImage

    try:
        programs = _node_programs(path, options.nodes)
        nodes = sorted(programs)
        settings = _per_node(options.settings, nodes, "--set")
        inputs = _inputs(_per_node(options.inputs, nodes, "--input"), len(nodes) > 1, options.seconds)
    except _Usage as exc:
        print(str(exc), file=err)
        return EXIT_COMPILE
    several = len(nodes) > 1
    if options.link not in (None, "sim", "apcsim") or options.config or options.record \
            or options.master_node is not None or not all(is_dpl(p) for p in programs.values()):
        print("motiontool run: DPL programs run on the embedded APC simulator, all of them .dpl (no --link, "
              "--config, --record or --master-node: the program names the CTSync master, #81.06 = 25)",
              file=err)
        return EXIT_COMPILE
    four_wire = options.ctsync_wires == 4
    limit = MAX_NODES_4WIRE if four_wire else MAX_NODES_2WIRE
    if len(nodes) > limit:  # L2078; the bus says the same, here before anything is checked
        hint = f" (--ctsync-wires 4 allows {MAX_NODES_4WIRE})" if not four_wire and len(nodes) <= MAX_NODES_4WIRE \
            else ""
        print(f"motiontool run: {len(nodes)} nodes: a {options.ctsync_wires}-wire CTSync line takes at most {limit} "
              f"without repeaters{hint}", file=err)
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
    trace: TraceWriter | None = None
    if options.trace:
        try:  # rows go to the file as they come (an hour of 1 ms rows was 656 MB in memory; decisions R6, R18)
            trace = TraceWriter(options.trace, nodes, list(signals))
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

    bus = dpl_line(len(nodes), four_wire=four_wire)
    links = {n: bus.link(k) for k, n in enumerate(nodes, start=1)}
    try:
        for n, link in links.items():
            link.subscribe(listener(n))
        while writes and writes[0][0] == 0:
            _, n, key, value = writes.pop(0)
            try:  # the drive refuses a value out of its range (#3.34 = 0): a refused option, nothing ran
                links[n].write_parameter(key, value)
            except LinkError as exc:
                print(f"motiontool run: --set {f'{n}:' if several else ''}{key}={value}: {exc}", file=err)
                return EXIT_REFUSED
        for at, n, name, value in inputs:
            links[n].schedule_input(name, value, at)
        for n, link in links.items():
            if options.trace:
                link.stream(signals, interval_ms=options.trace_interval_ms)
            link.download(DplImage(str(programs[n]), checked[n].source).to_bytes(), name=programs[n].name)
        for link in links.values():
            link.start()
        try:
            _advance_with_writes(bus, links, writes, int(options.seconds * 1000), options.realtime, failed, trace)
        except CTSyncRateError as exc:  # L2077: a run-time error of the line, the trace keeps what ran
            print(f"motiontool run: {exc.describe([f'{n} ({programs[n].name})' for n in nodes])}", file=err)
            failed.append(nodes[exc.odd[0]])
        if trace is not None:
            for link in links.values():
                link.stream([], interval_ms=1)
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


_INPUT = re.compile(r"^([^=@]+)=([^=@]+)(?:@([^=@]+))?$")


def _inputs(per_node: dict[int, list[str]], several: bool, seconds: float) -> list[tuple[int, int, str, int]]:
    """(time ms, node, input, value) of each `--input [ID:]NAME=V[@MS]`, in time order: DIGIN0 (or 0) = 0/1, the
    freeze input T10, whose edge #81.43 picks and #81.42 passes to the freeze counters (L1076); REF_MARKER=1 or
    FB_MARKER=1, a marker pulse on that encoder (the marker "as an additional high speed Freeze/registration
    input", L633). _Usage for any other form, a number out of range or a time after the end of the run."""
    from motiontool.controller.apc_service import apc_input

    result = []
    for n, specs in per_node.items():
        for spec in specs:
            m = _INPUT.match(spec.replace(" ", ""))
            if not m:
                raise _Usage(f"motiontool run: --input needs {'[ID:]' if several else ''}NAME=V or NAME=V@MS for a "
                             f"DPL program (DIGIN0, REF_MARKER, FB_MARKER), got '{shown(spec)}'")
            what = f"--input {shown(spec)}:"
            try:
                value = whole(m.group(2), f"{what} value", 0, 1)
                at = whole(m.group(3) or "0", f"{what} time", 0, MAX_SECONDS * 1000)
                name = apc_input(m.group(1), value)
            except BadNumber as exc:
                raise _Usage(f"motiontool run: {exc}") from None
            except ValueError as exc:
                raise _Usage(f"motiontool run: --input {shown(spec)}: {exc}") from None
            if at > seconds * 1000:
                raise _Usage(f"motiontool run: --input {shown(spec)}: {at} ms is after the end of the run (--seconds "
                             f"{seconds:g})")
            result.append((at, n, name, value))
    return sorted(result, key=lambda i: (i[0], i[1]))


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
