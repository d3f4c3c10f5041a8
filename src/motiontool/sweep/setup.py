"""Before the first point: the program compiled once, the measures read, and every varied parameter and measured
signal tried on a controller, so that a typing slip is one line naming the option instead of a sweep of errors."""

from __future__ import annotations

import re
from pathlib import Path
from typing import TextIO

from motiontool.cliargs import shown
from motiontool.comms.protocol import LinkError
from motiontool.sweep.measures import MeasureError, parse
from motiontool.sweep.points import SweepError
from motiontool.sweep.runner import SweepJob, one_line, open_controller

_DPL_KEY = re.compile(r"#?([0-9]{1,2})[.\-]([0-9]{1,2})")  # 18.11, #18.11 or 18-11 (the LCP's spelling)


def prepare(path: Path, keys: list[str], measures: list[str], settings: list[tuple[str, int]], seconds: float,
            include_dirs: list[Path], err: TextIO) -> SweepJob | None:
    """The job every point runs; None after the compiler's diagnostics on `err`; SweepError for a refused option."""
    from motiontool.dpl.driver import is_dpl

    if not measures:
        raise SweepError("give at least one --measure, e.g. --measure 'max(abs(TRACKERR))'")
    for n, text in enumerate(measures, start=1):
        try:
            parse(text)
        except MeasureError as exc:
            raise SweepError(f"{_measure(text, n)}, position {exc.position}: {exc}") from None
    kind = "dpl" if is_dpl(path) else "aposs"
    compiled = _compile(path, kind, include_dirs, err)
    if compiled is None:
        return None
    if kind == "dpl":
        keys, settings = [_dpl_key(k, "--vary") for k in keys], [(_dpl_key(k, "--set"), v) for k, v in settings]
    job = SweepJob(kind, compiled, path.name, tuple(keys), tuple(measures), seconds, tuple(settings))
    _try_on_controller(job)
    return job


def _measure(text: str, n: int) -> str:
    return f"--measure '{shown(text)}' (number {n})"


def _dpl_key(key: str, option: str) -> str:
    m = _DPL_KEY.fullmatch(key)
    if m is None:
        raise SweepError(f"{option} {shown(key)}: a DPL program's drive parameter is MM.PP, e.g. 18.11")
    return f"{int(m.group(1))}.{int(m.group(2)):02d}"


def _compile(path: Path, kind: str, include_dirs: list[Path], err: TextIO) -> bytes | None:
    if kind == "dpl":
        from motiontool.dpl.driver import check_source
        from motiontool.dpl.image import DplImage

        checked = check_source(path=path)
        for d in checked.diagnostics:
            print(d.format(), file=err)
        return DplImage(str(path), checked.source).to_bytes() if checked.ok else None
    from motiontool.aposs.driver import compile_source

    result = compile_source(path=path, include_dirs=include_dirs)
    for d in result.diagnostics:
        print(d.format(), file=err)
    return result.image.to_bytes() if result.ok and result.image is not None else None


def _try_on_controller(job: SweepJob) -> None:
    """Read every varied parameter, write every --set and stream every signal once, on a controller of its own."""
    link, _, close = open_controller(job.kind)
    try:
        for key in job.keys:
            _ask(f"--vary {key}", link.read_parameter, key)
        for key, value in job.settings:
            _ask(f"--set {key}={value}", link.write_parameter, key, value)
        for n, text in enumerate(job.measures, start=1):
            for name in parse(text).signals:
                where = f"{_measure(text, n)}, position {text.find(name) + 1}"
                _ask(where, lambda s: link.stream([s], interval_ms=1), name)
    finally:
        close()


def _ask(what: str, request, *args) -> None:
    try:
        request(*args)
    except (LinkError, ValueError) as exc:
        raise SweepError(f"{what}: {one_line(exc)}") from None
