"""`motiontool run`: compile a program, download it to the embedded controller over the link, run it in
virtual time and report exactly what the program printed (stdout) and the controller errors (stderr)."""

from __future__ import annotations

import csv
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import TextIO

from motiontool.aposs.driver import compile_source
from motiontool.cameditor.transfer import download_config
from motiontool.cameditor.zbc import ConfigError, read_config
from motiontool.comms.embedded import EmbeddedLink
from motiontool.comms.protocol import LinkError, LinkEvent

EXIT_OK, EXIT_COMPILE, EXIT_CONTROLLER = 0, 1, 2
_INPUT = re.compile(r"^(\d+)=(-?\d+)(?:@(\d+))?$")


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


def run_program(path: Path, options: RunOptions, out: TextIO = sys.stdout, err: TextIO = sys.stderr) -> int:
    result = compile_source(path=path, include_dirs=options.include_dirs)
    for d in result.diagnostics:
        print(d.format(), file=err)
    if not result.ok:
        return EXIT_COMPILE
    config = None
    if options.config is not None:
        try:
            config = read_config(options.config)
        except ConfigError as exc:
            print(str(exc), file=err)
            return EXIT_COMPILE
    link = EmbeddedLink(realtime_factor=1.0 if options.realtime else None)
    state = {"error": False}
    trace_rows: list[list] = []

    def on_event(event: LinkEvent) -> None:
        if event.kind == "print":
            print(event.text, file=out)
        elif event.kind == "error":
            where = f" (line {event.line})" if event.line else ""
            print(f"{event.text}{where}", file=err)
        elif event.kind == "program" and event.text == "program error":
            state["error"] = True
        elif event.kind == "samples":
            for t, values in zip(event.data["time_ms"], event.data["values"], strict=True):
                trace_rows.append([t, *values])

    link.subscribe(on_event)
    try:
        if config is not None:
            try:
                download_config(link, config)
            except ConfigError as exc:
                print(f"{options.config}: {exc}", file=err)
                return EXIT_COMPILE
        for setting in options.settings:
            key, _, value = setting.partition("=")
            if not value:
                print(f"motiontool run: --set needs NAME=VALUE, got '{setting}'", file=err)
                return EXIT_COMPILE
            try:
                number = int(value, 0)
            except ValueError:
                print(f"motiontool run: --set {key}: '{value}' is not a whole number", file=err)
                return EXIT_COMPILE
            link.write_parameter(key.strip(), number)
        for spec in options.inputs:
            m = _INPUT.match(spec.strip())
            if not m:
                print(f"motiontool run: --input needs N=V or N=V@T (ms), got '{spec}'", file=err)
                return EXIT_COMPILE
            number, value, at = int(m.group(1)), int(m.group(2)), int(m.group(3) or 0)
            link.call("schedule_input", number=number, value=value, time_ms=at)
        if options.trace:
            link.call("stream", signals=options.signals, interval_ms=options.trace_interval_ms)
        link.download(result.image.to_bytes(), name=result.image.name)
        link.start()
        total = int(options.seconds * 1000)
        step = 50
        elapsed = 0
        while elapsed < total:
            n = min(step, total - elapsed)
            if options.realtime:
                import time
                time.sleep(n / 1000)
            else:
                link.advance(n)
            elapsed += n
            if link.status().program_state != "running":
                break
        if options.trace:
            link.call("stream", signals=[], interval_ms=1)
            _write_csv(options.trace, ["time_ms", *options.signals], trace_rows)
        if options.record:
            _write_recordings(link, options.record)
    except LinkError as exc:
        print(f"motiontool run: {exc}", file=err)
        return EXIT_CONTROLLER
    finally:
        link.close()
    return EXIT_CONTROLLER if state["error"] else EXIT_OK


def _write_csv(path: Path, header: list[str], rows: list[list]) -> None:
    from motiontool.fileio import atomic_write_text

    lines = [",".join(header)] + [",".join(str(v) for v in row) for row in rows]
    atomic_write_text(path, "\n".join(lines) + "\n")


def _write_recordings(link: EmbeddedLink, path: Path) -> None:
    """Every TESTSETP recording as CSV: time_ms + one named column per recorded index; several
    recordings go to PATH, PATH-2.csv, … in the order they were started."""
    recordings = link.call("list_recordings")
    for n, info in enumerate(recordings):
        rec = link.call("upload_recording", index=info["index"])
        target = path if n == 0 else path.with_name(f"{path.stem}-{n + 1}{path.suffix}")
        names = [f"{name} [{index}]" for name, index in zip(rec["names"], rec["indices"], strict=True)]
        rows = [[rec["start_ms"] + k * rec["interval_ms"], *sample] for k, sample in enumerate(rec["samples"])]
        _write_csv(target, ["time_ms", *names], rows)
    if not recordings:
        with open(path, "w", newline="", encoding="utf-8") as f:
            csv.writer(f).writerow(["time_ms"])
