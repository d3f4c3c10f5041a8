"""Running the points of a sweep: each on a fresh simulated controller (an MCO 305, or an APC for a DPL program),
one after the other, on local processes (concurrent.futures) or on a Dask distributed cluster. Whatever runs
them, a point's row depends only on the job and the point, so the CSV is the same byte for byte."""

from __future__ import annotations

import os
import signal
from array import array
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from motiontool.comms.protocol import LinkError, LinkEvent
from motiontool.sweep.measures import EvaluationError, evaluate, format_value, parse
from motiontool.sweep.points import SweepError

STEP_MS = 50  # as `motiontool run`: the end of the program is noticed within 50 ms of virtual time


@dataclass(frozen=True)
class SweepJob:
    """What every point runs: the compiled program and how to measure it (picklable: it travels to workers)."""
    kind: str                              # "aposs" (MCO 305) or "dpl" (APC)
    image: bytes                           # the program image (aposs) or the checked DPL image
    name: str                              # the program's file name
    keys: tuple[str, ...]                  # varied parameters, as the controller's link takes them
    measures: tuple[str, ...]
    seconds: float
    settings: tuple[tuple[str, int], ...] = ()  # --set, written before the varied values
    interval_ms: int = 1

    def signals(self) -> list[str]:
        names: list[str] = []
        for text in self.measures:
            names += [s for s in parse(text).signals if s not in names]
        return names


Row = tuple[tuple[str, ...], str]  # (measures as written, error or "")


def open_controller(kind: str):
    """(link, advance(ms), close) of a fresh simulated controller in virtual time."""
    if kind == "dpl":  # as `motiontool run FILE.dpl`: a CTSync line, here of one drive
        from motiontool.controller.dpl_program import dpl_line

        bus = dpl_line(1)
        return bus.link(1), bus.advance, bus.close
    from motiontool.controller.embedded import EmbeddedLink

    link = EmbeddedLink()
    return link, link.advance, link.close


def run_point(job: SweepJob, values: Sequence[int]) -> Row:
    """One point's row. Never raises (but KeyboardInterrupt): a failed point is a row with its error."""
    try:
        return _run_point(job, tuple(values))
    except Exception as exc:  # noqa: BLE001 - one point's fault must not lose the sweep
        return (), one_line(f"{type(exc).__name__}: {exc}")


def one_line(text: object) -> str:
    return " ".join(str(text).split())


@dataclass
class Recorded:
    """One point's run as recorded: times in ms from the program's start and each signal's values."""
    t: np.ndarray
    series: dict[str, np.ndarray]
    errors: list[str]              # the controller's first error, with its line
    refused: str = ""              # a varied or --set value the controller refused: nothing ran


def record_run(job: SweepJob, values: Sequence[int], signals: Sequence[str]) -> Recorded:
    """Run `job` at one point on a fresh controller, recording `signals` every `job.interval_ms` (the sweep
    records the measures' signals; the IDE's sweep view opens a point's run in the scope with more)."""
    signals = list(signals)
    times, samples = array("d"), array("d")  # 8 bytes a value, no object per row: an hour of 3 signals is 115 MB
    errors: list[str] = []

    def on_event(event: LinkEvent) -> None:
        if event.kind == "samples":
            times.extend(event.data["time_ms"])
            for row in event.data["values"]:
                samples.extend(row)
        elif event.kind == "error" and not errors:  # the first error stops the program; later ones follow from it
            errors.append(event.text + (f" (line {event.line})" if event.line else ""))

    link, advance, close = open_controller(job.kind)
    link.subscribe(on_event)
    try:
        time_base = link.status().time_ms
        for key, value in (*job.settings, *zip(job.keys, values, strict=True)):
            try:
                link.write_parameter(key, value)
            except LinkError as exc:
                return Recorded(np.zeros(0), {}, [], one_line(f"{key}={value}: {exc}"))
        if signals:
            link.stream(signals, interval_ms=job.interval_ms)
        link.download(job.image, name=job.name)
        link.start()
        total, elapsed = int(job.seconds * 1000), 0
        while elapsed < total:
            n = min(STEP_MS, total - elapsed)
            advance(n)
            elapsed += n
            link.flush_events()
            if errors or link.status().program_state != "running":
                break
        link.stream([], interval_ms=1)  # sends the samples still buffered
        link.flush_events()
    finally:
        close()
    t = np.frombuffer(times, dtype=float) - time_base
    table = np.frombuffer(samples, dtype=float).reshape(len(times), len(signals))
    return Recorded(t, {name: table[:, k] for k, name in enumerate(signals)}, errors)


def _run_point(job: SweepJob, values: tuple[int, ...]) -> Row:
    measures = [parse(text) for text in job.measures]
    run = record_run(job, values, job.signals())
    if run.refused:
        return (), run.refused
    out, problems = [], list(run.errors)
    for n, measure in enumerate(measures, start=1):
        try:
            out.append(format_value(evaluate(measure, run.t, run.series)))
        except EvaluationError as exc:
            out.append("")
            problems.append(f"measure {n}: {exc}")
    return tuple(out), one_line("; ".join(problems))


# --- executors -------------------------------------------------------------------------------------------------
Progress = Callable[[int, Row], None]


def run_points(job: SweepJob, points: Sequence[Sequence[int]], done: dict[int, Row], progress: Progress,
               jobs: int = 1, executor: str = "local") -> None:
    """Run every point not yet in `done`, putting each row there (by index) as it comes and telling `progress`.
    KeyboardInterrupt passes through with `done` holding the rows finished so far."""
    todo = [k for k in range(len(points)) if k not in done]
    if executor.startswith("dask:"):
        results = _dask(executor.removeprefix("dask:"), job, points, todo)
    elif jobs <= 1:
        results = ((k, run_point(job, points[k])) for k in todo)
    else:
        results = _processes(jobs, job, points, todo)
    for k, row in results:
        done[k] = row
        progress(k, row)


def _ignore_sigint() -> None:
    """Workers leave Ctrl+C to the sweep, which keeps the rows done and stops them (a terminal sends SIGINT to
    the whole process group)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _processes(jobs: int, job: SweepJob, points, todo: list[int]) -> Iterator[tuple[int, Row]]:
    from concurrent.futures import ProcessPoolExecutor, as_completed

    pool = ProcessPoolExecutor(max_workers=jobs, initializer=_ignore_sigint)
    futures = {pool.submit(run_point, job, points[k]): k for k in todo}
    try:
        for future in as_completed(futures):
            exc = future.exception()
            yield futures[future], future.result() if exc is None else ((), one_line(f"worker: {exc!r}"))
    finally:  # done, interrupted or abandoned: nothing of the sweep may outlive it
        processes = list((getattr(pool, "_processes", None) or {}).values())
        pool.shutdown(wait=False, cancel_futures=True)
        if not all(future.done() for future in futures):
            # ProcessPoolExecutor cannot stop a running call before Python 3.14 (terminate_workers): the points
            # still running would hold the exit up for as long as they take
            for process in processes:
                process.terminate()
        pool.shutdown(wait=True)


def _dask(address: str, job: SweepJob, points, todo: list[int]) -> Iterator[tuple[int, Row]]:
    try:
        import distributed
    except ImportError:
        raise SweepError("--executor dask: needs the package 'distributed' (pip install 'motiontool[cluster]')") \
            from None
    try:
        client = distributed.Client(address, timeout=10)
    except (OSError, TimeoutError, ValueError) as exc:
        raise SweepError(f"--executor dask:{address}: no Dask scheduler answers there ({one_line(exc)})") from None
    try:
        futures = client.map(run_point, [job] * len(todo), [points[k] for k in todo], pure=False)
        index = {future.key: k for future, k in zip(futures, todo, strict=True)}
        try:
            for future in distributed.as_completed(futures):
                k = index[future.key]
                if future.status == "finished":
                    yield k, future.result()
                else:
                    yield k, ((), one_line(f"worker: {future.exception()!r}"))
        finally:
            client.cancel(futures)
    finally:
        client.close()


def default_jobs() -> int:
    """All the cores this process may use."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
