"""`motiontool run`: compile a program, download it to the embedded controller over the link, run it in
virtual time and report exactly what the program printed (stdout) and the controller errors (stderr)."""

from __future__ import annotations

import contextlib
import math
import os
import re
import sys
import time
from dataclasses import replace
from pathlib import Path
from typing import TextIO

from motiontool import cliargs
from motiontool.aposs.driver import compile_source
from motiontool.cameditor.transfer import download_config
from motiontool.cliargs import BadNumber, parse_input, parse_setting, shown
from motiontool.comms.client import ControllerClient
from motiontool.comms.eventorder import TimeOrder
from motiontool.comms.links import LinkSpecError, parse_link_spec
from motiontool.comms.protocol import LinkError, LinkEvent
from motiontool.controller.embedded import EmbeddedLink
from motiontool.dpl.driver import is_dpl
from motiontool.fileio import atomic_write_text, check_writable, write_error
from motiontool.formats.zbc import ConfigError, read_config
from motiontool.headless_dpl import run_dpl
from motiontool.runsetup import (  # noqa: F401 - RunOptions and the exit codes are the run's interface
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

_NODE_PREFIX = re.compile(r"^\s*-?[0-9]+\s*:")


class PrintOutput:
    """Where PRINT lines go (stdout). A reader that stops reading (`motiontool run … | head`) closes the pipe:
    the run then ends quietly after the current step instead of failing with a traceback; nothing more is
    written and the exit status is the program's so far."""

    def __init__(self, stream: TextIO):
        self.stream = stream
        self.closed = stream is None  # stdout closed (`run … >&-`): Python has no sys.stdout, PRINT goes nowhere

    def line(self, text: str) -> None:
        if not self.closed:
            self._guarded(print, text, file=self.stream)

    def flush(self) -> None:
        if not self.closed:
            self._guarded(self.stream.flush)

    def _guarded(self, write, *args, **kw) -> None:
        try:
            write(*args, **kw)
        except BrokenPipeError:
            self.closed = True
            # the interpreter flushes stdout once more at exit: point it at /dev/null (Python docs, SIGPIPE)
            with contextlib.suppress(OSError, ValueError, AttributeError):
                os.dup2(os.open(os.devnull, os.O_WRONLY), self.stream.fileno())


def compile_program(path, options, err):
    """The program image, or None after printing the diagnostics (GCC style) on err."""
    result = compile_source(path=path, include_dirs=options.include_dirs)
    for d in result.diagnostics:
        print(d.format(), file=err)
    return result.image if result.ok else None


def load_config(options, err):
    """(True, the --config file or None); (False, None) when the file is refused (its message on err)."""
    if options.config is None:
        return True, None
    try:
        return True, read_config(options.config)
    except ConfigError as exc:
        print(str(exc), file=err)
        return False, None



def check_options(path: Path | None, options: RunOptions, err) -> bool:
    """What can be judged before anything is compiled: the numbers, node prefixes without --node, and whether
    every output file can be written (a long run must not end in a traceback). False after printing why."""
    problems = []
    try:  # numbers inside compound options, before anything is compiled (cliargs: ASCII digits, bounded)
        for value in [] if is_dpl_run(path, options) else options.inputs:  # a DPL run's: headless_dpl
            if not _NODE_PREFIX.match(value):
                parse_input(value)
            elif options.nodes:  # without --node the prefix itself is the problem (below)
                parse_input(value.split(":", 1)[1])
        cliargs.check_signals(options.signals)
        parse_link_spec(options.link or "sim")  # its address; the options are read when it opens (LinkSpecError)
    except (BadNumber, LinkSpecError) as exc:
        problems.append(str(exc))
    if not (math.isfinite(options.timeout) and 0 <= options.timeout <= MAX_SECONDS):
        problems.append(f"--timeout {options.timeout:g}: give a time in seconds, from 0 to {MAX_SECONDS}")
    if not (math.isfinite(options.seconds) and 0 < options.seconds <= MAX_SECONDS):
        problems.append(f"--seconds {options.seconds:g}: give a time in seconds, above 0 and at most {MAX_SECONDS}")
    if options.trace_interval_ms < 1:
        problems.append(f"--interval {options.trace_interval_ms}: the trace interval is at least 1 ms")
    if not options.nodes:
        for option, values, form in (("--set", options.settings, "KPROP=5"), ("--input", options.inputs, "3=1@100")):
            for value in values:
                if _NODE_PREFIX.match(value):
                    problems.append(f"{option} {value}: 'ID:' picks a controller, which needs --node (several "
                                    f"controllers); for the one controller write {option} {form}")
    for value in options.inputs:
        with contextlib.suppress(BadNumber):
            parsed = parse_input(value.split(":", 1)[1] if options.nodes and _NODE_PREFIX.match(value) else value)
            if parsed and parsed[2] > options.seconds * 1000:
                problems.append(f"--input {value}: {parsed[2]} ms is after the end of the run (--seconds "
                                f"{options.seconds:g})")
    for problem in problems:
        print(f"motiontool run: {problem}", file=err)
    return not problems and _outputs_writable(path, options, err)


def _outputs_writable(path: Path | None, options: RunOptions, err) -> bool:
    targets = [options.trace] if options.trace else []
    if options.record:
        targets += [_record_path(options.record, n) for n in _node_ids(path, options)] if options.nodes \
            else [options.record]
    for target in targets:
        try:
            check_writable(target)
        except OSError as exc:
            print(f"motiontool run: {write_error(target, exc)}", file=err)
            return False
    return True


def _node_ids(path: Path | None, options: RunOptions) -> list[int]:
    try:
        return sorted(_node_programs(path, options.nodes))
    except _Usage:
        return []  # reported later, with the other --node problems


def prepare_link(link, config, settings: list[str], inputs: list[str], options, err, node_ids: bool = False,
                 time_base: int = 0) -> bool:
    """Load --config, then --set and --input into one controller before its program starts; False after
    printing why on err (a command-line error: EXIT_REFUSED). ``node_ids``: the options were given as [ID:]…
    (several controllers); ``time_base``: the controller's time when the run starts (input times count from there)."""
    form = "[ID:]" if node_ids else ""
    if config is not None:
        try:
            download_config(link, config)
        except ConfigError as exc:
            print(f"{options.config}: {exc}", file=err)
            return False
    for setting in settings:
        try:
            parsed = parse_setting(setting)
        except BadNumber as exc:
            print(f"motiontool run: {exc}", file=err)
            return False
        if parsed is None:
            print(f"motiontool run: --set needs {form}NAME=VALUE, got '{shown(setting)}'", file=err)
            return False
        try:  # the controller refuses unknown, read-only and out-of-range parameters
            link.write_parameter(*parsed)
        except LinkError as exc:
            print(f"motiontool run: --set {setting}: {exc}", file=err)
            return False
    for spec in inputs:
        try:
            scheduled = parse_input(spec)
        except BadNumber as exc:
            print(f"motiontool run: {exc}", file=err)
            return False
        if scheduled is None:
            print(f"motiontool run: --input needs {form}N=V or {form}N=V@T (ms), got '{shown(spec)}'", file=err)
            return False
        try:  # the controller refuses inputs it does not have
            number, value, time_ms = scheduled
            link.schedule_input(number, value, time_base + time_ms)
        except LinkError as exc:
            print(f"motiontool run: --input {spec}: {exc}", file=err)
            return False
    return True


def is_dpl_run(path: Path | None, options: RunOptions) -> bool:
    """DPL programs on simulated APCs (headless_dpl): FILE.dpl or any --node ID:OTHER.dpl."""
    return is_dpl(path) or any(is_dpl(spec.partition(":")[2].strip()) for spec in options.nodes)


def run_program(path: Path | None, options: RunOptions, out: TextIO | None = None, err: TextIO | None = None) -> int:
    out, err = out or sys.stdout, err or sys.stderr  # looked up now: a caller may have redirected them
    if not check_options(path, options, err):
        return EXIT_REFUSED
    if is_dpl_run(path, options):
        return run_dpl(path, options, err)  # DPL programs run on the simulated APC (a CTSync line for several)
    if options.nodes:  # a multi-axis project: several controllers on one master signal
        return run_nodes(path, options, out, err)
    image = compile_program(path, options, err)
    loaded, config = load_config(options, err)
    if image is None or not loaded:
        return EXIT_COMPILE
    try:
        link = open_run_link(options.link, options.realtime, patience_s=options.timeout)
    except LinkError as exc:
        print(f"motiontool run: {exc}", file=err)
        return EXIT_REFUSED if isinstance(exc, LinkSpecError) else EXIT_CONTROLLER
    state = {"error": False}
    trace: TraceWriter | None = None
    output = PrintOutput(out)

    def on_event(event: LinkEvent) -> None:
        if event.kind == "print":
            output.line(event.text)
        elif event.kind == "error":
            where = f" (line {event.line})" if event.line else ""
            print(f"{event.text}{where}", file=err)
        elif event.kind == "program" and event.text == "program error":
            state["error"] = True
        elif event.kind == "samples" and trace is not None:
            trace.add(1, event.data)
        elif event.kind in ("message", "connection"):
            print(f"motiontool run: {event.text}", file=err)

    link.subscribe(on_event)
    try:
        time_base = link.status().time_ms
        if not prepare_link(link, config, options.settings, options.inputs, options, err, time_base=time_base):
            return EXIT_REFUSED
        if options.trace:  # the writer first: a running clock (--realtime) sends samples at once
            trace = TraceWriter(options.trace, [1], options.signals)
            link.stream(options.signals, interval_ms=options.trace_interval_ms)
        link.download(image.to_bytes(), name=image.name)
        link.start()
        run_until_stopped([link], options, time_base, output, lambda: trace is not None and trace.error is not None)
        output.flush()
        if trace is not None:
            link.stream([], interval_ms=1)
            link.flush_events()
            trace.commit()
            trace = None
        if options.record:
            _write_recordings(link, options.record)
    except LinkError as exc:
        print(f"motiontool run: {exc}", file=err)
        return EXIT_CONTROLLER
    except _OutputError as exc:  # the folder went away or the disk filled up during the run
        print(f"motiontool run: {exc}", file=err)
        return EXIT_REFUSED
    finally:
        if trace is not None:
            trace.discard()
        link.close()
    return EXIT_CONTROLLER if state["error"] else EXIT_OK


def open_run_link(spec: str | None, realtime: bool = False, node: int | None = None, patience_s: float = 0.0):
    """The controller of a run: the embedded simulator (virtual time unless `realtime`) or `--link SPEC`, with
    `node` as its address when given. A wire link waits up to `patience_s` for a lost connection to come back
    (`--timeout`): a stalled drive pauses the run instead of ending it (decision F30)."""
    from motiontool.comms.links import open_link
    from motiontool.controller import schemes

    schemes.register()  # a run from Python (not the command) opens `apcsim` and `sim,…` links too
    parsed = parse_link_spec(spec or "sim")
    if parsed.scheme == "sim" and not parsed.options:
        return EmbeddedLink(realtime_factor=1.0 if realtime else None)
    link = open_link(replace(parsed, node=node) if node is not None else parsed)
    if hasattr(link, "patience_s"):
        link.patience_s = patience_s
    return link


def run_until_stopped(links: list, options: RunOptions, time_base: int, output: PrintOutput,
                      failed=lambda: False, reached=lambda time_ms: None) -> None:
    """Controller time runs until every program has stopped or --seconds are up: the first link's `advance`
    moves a virtual clock (all nodes of one simulator share it), paced at real time with --realtime; a clock that
    runs by itself (a drive) is watched in 50 ms steps. Events are fetched after every step, before the status,
    and then ``reached(T)`` says that every link has delivered its events up to controller time T; a closed
    stdout or ``failed()`` (an output that cannot be written) ends the run after the step."""
    total = int(options.seconds * 1000)
    lead = links[0]
    virtual = lead.virtual_time
    step, elapsed = 50, 0
    started = time.monotonic()
    while elapsed < total:
        n = min(step, total - elapsed)
        if virtual:
            lead.advance(n)
            elapsed += n
            now = time_base + elapsed
            if options.realtime:  # pace virtual time at real time
                time.sleep(max(0.0, elapsed / 1000 - (time.monotonic() - started)))
        else:
            time.sleep(max(0.0, (elapsed + n) / 1000 - (time.monotonic() - started)))
            now = lead.status().time_ms  # read before the flush: every event up to it is then fetched
            elapsed = max(elapsed + 1, now - time_base)
        for link in links:
            link.flush_events()
        reached(now)
        if output.closed or failed() or all(link.status().program_state != "running" for link in links):
            if not virtual:  # a running clock: the last lines may have come between the flush and the status
                for link in links:
                    link.flush_events()
            break


def _write_csv(path: Path, header: list[str], rows: list[list]) -> None:
    lines = [",".join(header)] + [",".join(str(v) for v in row) for row in rows]
    atomic_write_text(path, "\n".join(lines) + "\n")


def _write_recordings(link: ControllerClient, path: Path) -> None:
    """Every TESTSETP recording as CSV: time_ms + one named column per recorded index; several
    recordings go to PATH, PATH-2.csv, … in the order they were started."""
    recordings = link.list_recordings()
    for n, info in enumerate(recordings):
        rec = link.upload_recording(info.index)
        target = path if n == 0 else path.with_name(f"{path.stem}-{n + 1}{path.suffix}")
        names = [f"{name} [{index}]" for name, index in zip(rec.names, rec.indices, strict=True)]
        rows = [[rec.start_ms + k * rec.interval_ms, *sample] for k, sample in enumerate(rec.samples)]
        _write_output(target, ["time_ms", *names], rows)
    if not recordings:  # still a file, so a script finds what it asked for
        _write_output(path, ["time_ms"], [])


def _write_output(path: Path, header: list[str], rows: list[list]) -> None:
    try:
        _write_csv(path, header, rows)
    except OSError as exc:
        raise _OutputError(write_error(path, exc)) from None


# --- several controllers (--node): a multi-axis project on one master signal (controller/bus.py) -------------------
def run_nodes(path: Path | None, options: RunOptions, out: TextIO | None = None, err: TextIO | None = None) -> int:
    """Several simulated controllers in lockstep (controller/bus.py, kernel/simulation.py): FILE.m on node 1 and every
    --node ID:PROGRAM.m; the virtual master (PULSVEL) of --master-node (default the lowest id) is the master input
    of all the others. stdout: every PRINT as `N: text`, stderr: controller errors as `N: error …`."""
    out, err = out or sys.stdout, err or sys.stderr
    try:
        programs = _node_programs(path, options.nodes)
        nodes = sorted(programs)
        settings = _per_node(options.settings, nodes, "--set")
        inputs = _per_node(options.inputs, nodes, "--input")
    except _Usage as exc:
        print(str(exc), file=err)
        return EXIT_REFUSED
    images = {n: compile_program(programs[n], options, err) for n in nodes}
    loaded, config = load_config(options, err)
    if None in images.values() or not loaded:
        return EXIT_COMPILE
    try:
        links, close = _node_links(nodes, options)
    except ValueError as exc:
        print(f"motiontool run: --master-node: {exc}", file=err)
        return EXIT_COMPILE
    except LinkError as exc:
        print(f"motiontool run: {exc}", file=err)
        return EXIT_REFUSED if isinstance(exc, LinkSpecError) else EXIT_CONTROLLER
    failed: set[int] = set()
    trace: TraceWriter | None = None
    output = PrintOutput(out)

    def show(n: int, event: LinkEvent) -> None:
        if event.kind == "print":
            output.line(f"{n}: {event.text}")
        elif event.kind == "error":
            where = f" (line {event.line})" if event.line else ""
            print(f"{n}: {event.text}{where}", file=err)
        else:
            print(f"{n}: motiontool run: {event.text}", file=err)

    # the nodes' lines in (time, node) order as the embedded bus prints them, whichever link delivered first
    order = TimeOrder(show)

    def listener(n: int):
        def on_event(event: LinkEvent) -> None:
            if event.kind == "connection":   # said while the run waits for the link, not held until it is back
                print(f"motiontool run: {event.text}", file=err)
            elif event.kind in ("print", "error", "message"):
                order.add(n, event)
            elif event.kind == "program" and event.text == "program error":
                failed.add(n)
            elif event.kind == "samples" and trace is not None:
                trace.add(n, event.data)
        return on_event

    try:
        time_base = links[nodes[0]].status().time_ms
        for n in nodes:
            link = links[n]
            link.subscribe(listener(n))
            if not prepare_link(link, config, settings[n], inputs[n], options, err, node_ids=True,
                                time_base=time_base):
                return EXIT_REFUSED
        if options.trace:
            trace = TraceWriter(options.trace, nodes, options.signals)
            for n in nodes:
                links[n].stream(options.signals, interval_ms=options.trace_interval_ms)
        for n in nodes:
            links[n].download(images[n].to_bytes(), name=images[n].name)
            links[n].start()
        run_until_stopped([links[n] for n in nodes], options, time_base, output,
                          lambda: trace is not None and trace.error is not None, order.release)
        order.release()
        output.flush()
        if trace is not None:
            for n in nodes:
                links[n].stream([], interval_ms=1)
                links[n].flush_events()
            trace.commit()
            trace = None
        if options.record:
            for n in nodes:
                _write_recordings(links[n], _record_path(options.record, n))
    except LinkError as exc:
        order.release()  # what arrived before the link failed, then why it ended
        print(f"motiontool run: {exc}", file=err)
        return EXIT_CONTROLLER
    except _OutputError as exc:  # the folder went away or the disk filled up during the run
        print(f"motiontool run: {exc}", file=err)
        return EXIT_REFUSED
    finally:
        order.release()
        if trace is not None:
            trace.discard()
        close()
    return EXIT_CONTROLLER if failed else EXIT_OK


def _record_path(record: Path, node: int) -> Path:
    return record.with_name(f"{record.stem}-node{node}{record.suffix}")


def _node_links(nodes: list[int], options: RunOptions):
    """({node: link}, close) for a run on several controllers: one embedded bus, or the --link interface with each
    node id as the address."""
    from motiontool.controller.bus import EmbeddedBus

    if parse_link_spec(options.link or "sim").scheme == "sim":
        bus = EmbeddedBus(nodes, master_node=options.master_node if options.master_node is not None else nodes[0])
        return {n: bus.link(n) for n in nodes}, bus.close
    if options.master_node is not None:
        raise ValueError("the drive wires its master signal (motiontool drive --master-node), not the run")
    links: dict = {}
    try:
        for n in nodes:
            links[n] = open_run_link(options.link, node=n, patience_s=options.timeout)
    except LinkError:
        for link in links.values():
            link.close()
        raise
    return links, lambda: [link.close() for link in links.values()]
