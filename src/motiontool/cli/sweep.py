"""`motiontool sweep`: the command line of a parameter sweep (the model is motiontool.sweep, docs/sweep.md)."""

from __future__ import annotations

import argparse
import csv
import io
import sys
import time
from pathlib import Path

from motiontool.cliargs import MAX_RUN_SECONDS, PARAMETER_VALUE, BadNumber, number_option, same_file, shown
from motiontool.sweep.points import MAX_POINTS, SweepError

EXIT_INTERRUPTED = 130  # 128 + SIGINT, as a shell reports a program stopped by Ctrl+C
PROG = "motiontool sweep"


def add_parser(sub) -> argparse.ArgumentParser:
    p = sub.add_parser("sweep", help="run a program once per point of a parameter grid and measure each run",
                       description="Runs FILE.m (or FILE.dpl on a simulated APC) on a fresh simulated controller "
                                   "once per point: the grid of every --vary, the lines of --points, or --random "
                                   "points; writes one CSV row per point (point, the parameters, the measures, "
                                   "error). Exit 0 when every point ran (a failed point is a row with its error), 1 "
                                   "when nothing ran (a refused option or program), 130 after Ctrl+C (the rows "
                                   "done are written). docs/sweep.md")
    p.add_argument("file", type=Path, metavar="FILE.m|FILE.dpl")
    p.add_argument("--vary", action="append", default=[], metavar="KEY=LO:HI:STEP",
                   help="a parameter and its values, e.g. 32-60=20:80:5 (FILE.dpl: 18.11=0:1000:100); repeatable")
    p.add_argument("--points", type=Path, metavar="POINTS.csv",
                   help="instead of a grid: a header of parameters, then one point per line")
    number_option(p, "--random", lo=1, hi=MAX_POINTS, integer=True, metavar="N",
                  help="instead of a grid: N points drawn uniformly in the --vary ranges (on the STEP grid if given)")
    number_option(p, "--seed", lo=0, hi=PARAMETER_VALUE[1], integer=True, default=0,
                  help="of --random (default 0): the same seed draws the same points")
    p.add_argument("--measure", action="append", default=[], metavar="EXPR",
                   help="a number per run, e.g. 'max(abs(TRACKERR))' or 'settle_time(APOS, 204800, 10)'; repeatable")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="a parameter every point starts with (before the varied ones)")
    number_option(p, "--seconds", lo=0, hi=MAX_RUN_SECONDS, above=True, default=60.0,
                  help="virtual time of each run at most (default 60); a run ends earlier when its program does")
    number_option(p, "--jobs", "-j", lo=1, hi=1024, integer=True, metavar="N",
                  help="local processes (default: every core)")
    p.add_argument("--executor", default="local", metavar="local|dask:tcp://HOST:PORT",
                   help="where the points run: here (default) or on a Dask distributed cluster's scheduler")
    p.add_argument("--include", "-I", action="append", type=Path, default=[], metavar="DIR")
    p.add_argument("-o", "--output", type=Path, required=True, metavar="OUT.csv")
    return p


def run(args: argparse.Namespace) -> int:
    from motiontool.fileio import check_writable, write_error
    from motiontool.sweep import runner
    from motiontool.sweep.setup import prepare

    try:
        keys, points = _points(args)
        if args.executor != "local" and not args.executor.startswith("dask:"):
            raise SweepError(f"--executor {shown(args.executor)}: give local or dask:tcp://HOST:PORT")
        check_writable(args.output)
        job = prepare(args.file, keys, args.measure, _settings(args.set), args.seconds, args.include, sys.stderr)
    except SweepError as exc:
        print(f"{PROG}: {exc}", file=sys.stderr)
        return 1
    except OSError as exc:
        print(f"{PROG}: {write_error(args.output, exc)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted before the first point; nothing was written", file=sys.stderr)
        return EXIT_INTERRUPTED
    if job is None:  # the program did not compile: its diagnostics are out
        return 1
    done: dict = {}
    progress = _Progress(len(points))
    interrupted = False
    try:
        runner.run_points(job, points, done, progress.point, jobs=args.jobs or runner.default_jobs(),
                          executor=args.executor)
    except KeyboardInterrupt:
        interrupted = True
    except SweepError as exc:  # the cluster cannot be reached
        print(f"{PROG}: {exc}", file=sys.stderr)
        return 1
    finally:
        progress.end()
    try:
        write_csv(args.output, keys, args.measure, points, done)
    except OSError as exc:
        print(f"{PROG}: {write_error(args.output, exc)}", file=sys.stderr)
        return 1
    failed = sum(1 for row in done.values() if row[1])
    end = "interrupted: " if interrupted else ""
    print(f"{PROG}: {end}{len(done)} of {len(points)} points in {args.output}, {failed} with an error",
          file=sys.stderr)
    return EXIT_INTERRUPTED if interrupted else 0


def _points(args: argparse.Namespace) -> tuple[list[str], list[tuple[int, ...]]]:
    from motiontool.sweep import points as grid

    varies = [grid.parse_vary(text, n) for n, text in enumerate(args.vary, start=1)]
    grid.check_keys([v.key for v in varies], "--vary")
    if args.points is not None:
        if varies or args.random is not None:
            raise SweepError("--points: the file gives the points; no --vary or --random with it")
        if same_file(args.points, args.output):
            raise SweepError(f"--points {args.points} is the output file (-o); nothing was written")
        return grid.read_points(args.points)
    if not varies:
        raise SweepError("give the parameters to vary: --vary KEY=LO:HI:STEP (or --points FILE.csv)")
    keys = [v.key for v in varies]
    if args.random is not None:
        return keys, grid.random_points(varies, args.random, args.seed)
    return keys, grid.grid(varies)


def _settings(texts: list[str]) -> list[tuple[str, int]]:
    from motiontool.cliargs import parse_setting

    settings = []
    for text in texts:
        try:
            parsed = parse_setting(text)
        except BadNumber as exc:
            raise SweepError(str(exc)) from None
        if parsed is None:
            raise SweepError(f"--set needs KEY=VALUE, got '{shown(text)}'")
        settings.append(parsed)
    return settings


def write_csv(path: Path, keys: list[str], measures: list[str], points, done: dict) -> None:
    """The rows done, in point order, written at once (fileio: a complete file or the old one)."""
    from motiontool.fileio import atomic_write_text

    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(["point", *keys, *measures, "error"])
    for k in sorted(done):
        values, error = done[k]
        writer.writerow([k + 1, *points[k], *(values or [""] * len(measures)), error])
    atomic_write_text(path, text.getvalue())


class _Progress:
    """`sweep: 12/16 points, 1 failed` on stderr: rewritten in place on a terminal, else a line at most every
    2 s (a log file does not fill up with thousands of lines)."""

    def __init__(self, total: int):
        self.total, self.count, self.failed = total, 0, 0
        self.tty = sys.stderr.isatty()
        self.started = self.shown = time.monotonic()
        self.pending = False

    def point(self, index: int, row) -> None:
        self.count += 1
        self.failed += bool(row[1])
        now = time.monotonic()
        if self.tty or self.count == 1 or now - self.shown >= 2.0:
            self._show(now)
        else:
            self.pending = True

    def _show(self, now: float) -> None:
        rate = self.count / max(now - self.started, 1e-9)
        line = f"sweep: {self.count}/{self.total} points, {self.failed} failed, {rate:.1f} runs/s"
        print(f"\r{line}" if self.tty else line, end="" if self.tty else "\n", file=sys.stderr, flush=True)
        self.shown, self.pending = now, False

    def end(self) -> None:
        if self.pending:
            self._show(time.monotonic())
        if self.tty and self.count:
            print(file=sys.stderr)
