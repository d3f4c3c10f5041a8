"""Fuzz every reader a user's file reaches: APOSS programs, program images, DPL programs and each file format.

Run from the repository root:

    .venv/bin/python benchmarks/fuzz_files.py [--cases 600] [--seed 18]

For each format, --cases mutated files (edits of valid files: lines deleted, duplicated, swapped, truncated;
characters and numbers replaced by edge cases such as other scripts' digits, 5 000-digit numbers, NaN, 1e999;
invalid UTF-8; for images also the JSON body's values, types and instructions) go through the reader a user's file
goes through - written to a file and read from the path. A case passes when the reader returns or raises its own
error class; an accepted program image must also run for 50 ms on the embedded controller without an internal fault
(error 199) or a failed request, and an accepted DPL program for 50 ms on the simulated APC. Anything else is a crash.
Then the hostile shapes mutations do not reach (``hostile_cases``: sizes declared far beyond the data, zlib bombs,
100/101/5 000 parentheses, a BOM with CRLF) must each end in a one-line refusal naming the file and the limit, or be
read when valid (``fuzz_files_hostile_cases``, ``fuzz_files_hostile_crashes``).

Prints ``name: value unit`` lines per format (``fuzz_files_zbc_cases``, ``…_crashes``, ``…_slowest``) and in total
(``fuzz_files_cases``, ``fuzz_files_crashes``, ``fuzz_files_slowest``); goals: 0 crashes, slowest below 2 s. Exit
status 1 on a crash; each crash site goes to stderr with a reproducer. The generators are plain functions of a
``random.Random``-like object (``random``, ``randint``, ``choice``), shared with tests/test_file_fuzz.py and
tests/aposs/test_image_fuzz.py, which drive them with hypothesis.
"""

from __future__ import annotations

import argparse
import base64
import contextlib
import functools
import json
import random
import sys
import tempfile
import time
import traceback
import zlib
from collections.abc import Callable
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "benchmarks"))

import fuzz_compiler  # noqa: E402 - the program generators
from motiontool.aposs.driver import compile_source  # noqa: E402
from motiontool.aposs.image import ImageError, Op, ProgramImage  # noqa: E402

# --- seeds: valid files ---------------------------------------------------------------------------------------------
ZBA = """Date,2009:07:27 10:52
Widths, 150, 40, 40, 40, 70, 70, 70, 70, 70, 365
User,,130,Height,50,100,10,1000,"Maximum height of any unit",1
User, 132, Weight, 5, , 1, 20, "Maximum weight of any unit", 1
Group, 0, 0, "Quantity by Country", , , , 0
Array,0,1,Switzerland,5,10,0,5000,"This is the first value in array 0",1
Axis,1,3260,KPROP,30,30,0,100000,"Proportional factor",1
Array, 3, 5, "Test Value", 1.5, 0, 0, 1, "Test: 0 - No, 1 - Yes", 1
"""
TESTRUN = """APOSS Testrun
Program: tune.m
Interval: 2 ms
Time\tCPOS\tAPOS
0\t0\t0
2\t10\t8
4\t20\t27
"""
IMAGE_PROGRAMS = ["D12_hello.m", "F_C11_position_interrupts.m", "F_D20_functions.m", "F_D16_arrays.m",
                  "F_D19_doubles.m", "F_C08_control_flow.m", "F_C22_print.m", "D15_error_handler.m"]


def _seeds() -> dict[str, list[str | bytes]]:
    from motiontool.camcurve.model import Curve, FixPoint
    from motiontool.formats.dat import dat_text
    from motiontool.formats.zbc import ArrayEntry, ConfigFile, config_text
    from motiontool.headless import _write_csv

    stamping = Curve("stamping", 4000, (FixPoint(0, 0, "C"), FixPoint(1500, 1200, "T"), FixPoint(2500, 2400, "T"),
                                        FixPoint(4000, 3600, "C")), intervals=40)
    config = ConfigFile(parameters={"32-60": 30, "19-00": 5})
    config.arrays.append(ArrayEntry("table", [1, -2, 3, 2147483647]))
    config.add_curve(stamping)
    with tempfile.TemporaryDirectory() as scratch:
        trace = Path(scratch) / "t.csv"
        _write_csv(trace, ["time_ms", "4230", "APOS", "TRACKERR"], [[t, 10 * t, t * t / 4, 0.5] for t in range(40)])
        trace_text = trace.read_text()
    examples = fuzz_compiler.EXAMPLES_DIR
    images = [compile_source(path=examples / name).image.to_bytes() for name in IMAGE_PROGRAMS]
    return {"zbc": [config_text(config)], "dat": [dat_text(stamping)], "zba": [ZBA],
            "zbo": [(REPO / "tests" / "scope" / "data" / "golden.zbo").read_text(encoding="utf-8")],
            "testrun": [TESTRUN], "trace": [trace_text], "image": images,
            "dpl": [p.read_text(encoding="utf-8") for p in sorted((REPO / "tests" / "dpl" / "programs").glob("*.dpl"))]}


SEEDS = _seeds()

# --- text mutations -------------------------------------------------------------------------------------------------
EDGE = ["\u0665\u0660", "\u00b2", "1_000", "9" * 5000, "-" + "9" * 40, "1e999", "-1e999", "nan", "inf", "NaN",
        "Infinity", "0x10", "-0", "+5", "", " ", "2147483648", "-2147483649", "4294967296", "1.5", ".", "-",
        "\ufeff", "\x00", "\u2013", "null", "true", "[]", "{}", '"', "'", ",", ";", "=", "\t", "\r", "#"]


def mutate_text(r, text: str) -> str:
    """1-4 edits: whole lines (delete, duplicate, swap, truncate the file), a number or word replaced by an edge case,
    characters inserted or deleted, a line repeated many times."""
    import re

    for _ in range(r.randint(1, 4)):
        lines = text.split("\n")
        i, j = r.randint(0, len(lines) - 1), r.randint(0, len(lines) - 1)
        k = r.randint(0, 9)
        if k == 0:
            del lines[i]
        elif k == 1:
            lines.insert(i, lines[i])
        elif k == 2:
            lines[i], lines[j] = lines[j], lines[i]
        elif k == 3:
            text = text[:r.randint(0, len(text))]
            continue
        elif k in (4, 5, 6):
            spans = [m.span() for m in re.finditer(r"[-+]?[0-9][0-9.eE+-]*|[A-Za-z_]+", lines[i])]
            if spans:
                a, b = r.choice(spans)
                lines[i] = lines[i][:a] + r.choice(EDGE) + lines[i][b:]
        elif k == 7:
            pos = r.randint(0, len(text))
            text = text[:pos] + r.choice(EDGE) + text[pos:]
            continue
        elif k == 8:
            pos = r.randint(0, len(text))
            text = text[:pos] + text[pos + r.randint(1, 8):]
            continue
        else:
            lines[i:i + 1] = [lines[i]] * r.choice([2, 50, 2000])
        text = "\n".join(lines)
    return text


def mutate_file(r, text: str) -> bytes:
    data = mutate_text(r, text).encode("utf-8")
    k = r.randint(0, 19)
    if k == 0:
        data = data.replace(b"\n", b"\r\n")
    elif k == 1:
        pos = r.randint(0, len(data))
        data = data[:pos] + bytes([r.randint(0x80, 0xFF)]) + data[pos:]  # invalid UTF-8
    elif k == 2:
        data = b"\xef\xbb\xbf" + data
    return data


# --- image mutations ------------------------------------------------------------------------------------------------
VALUES = [0, 1, -1, 2, 7, 50, 52, 10**6, 2**31, -(2**31) - 1, 2**63, 1.5, -0.0, "x", "", True, False, None, [], {},
          [1, 2], {"a": 1}, "NaN"]


def _paths(node, path=()):
    yield path
    if isinstance(node, dict):
        for key, value in node.items():
            yield from _paths(value, (*path, key))
    elif isinstance(node, list) and len(node) < 64:
        for k, value in enumerate(node):
            yield from _paths(value, (*path, k))


def _get(node, path):
    for step in path:
        node = node[step]
    return node


def mutate_image(r, data: bytes) -> bytes:
    """Edits of the JSON body (a value replaced by another type or an edge value, a key deleted or added, list items
    deleted or duplicated, instructions replaced, swapped, deleted or made from random numbers), or of the bytes."""
    if r.randint(0, 9) == 0:  # the container's bytes
        data = bytearray(data)
        for _ in range(r.randint(1, 4)):
            if not data:  # an earlier edit cut everything: nothing left to edit
                break
            k = r.randint(0, 2)
            pos = r.randint(0, len(data) - 1)
            if k == 0:
                data[pos] = r.randint(0, 255)
            elif k == 1:
                del data[pos:pos + r.randint(1, 16)]
            else:
                data = data[:pos]
        return bytes(data)
    raw = json.loads(zlib.decompress(data[6:]))
    for _ in range(r.randint(1, 3)):
        k = r.randint(0, 9)
        code = raw["code"]
        n = len(code) // 2
        if k <= 3 and n:  # instructions
            pc = r.randint(0, n - 1)
            kind = r.randint(0, 4)
            if kind == 0:
                code[2 * pc] = r.randint(0, 53)
            elif kind == 1:
                code[2 * pc + 1] = r.choice([r.randint(-2, 40), r.randint(0, n + 2), 2**31])
            elif kind == 2:
                other = r.randint(0, n - 1)
                code[2 * pc:2 * pc + 2], code[2 * other:2 * other + 2] = code[2 * other:2 * other + 2], \
                    code[2 * pc:2 * pc + 2]
            elif kind == 3:
                del code[2 * pc:2 * pc + 2]
            else:
                code[2 * pc:2 * pc] = [r.choice(list(Op)).value, r.randint(-1, 8)]
            continue
        paths = [p for p in _paths(raw) if p and p[0] != "code"]
        path = r.choice(paths)
        parent = _get(raw, path[:-1])
        if k <= 6:
            parent[path[-1]] = r.choice(VALUES)
        elif k == 7:
            del parent[path[-1]]
        elif k == 8 and isinstance(parent, list):
            parent.insert(path[-1], parent[path[-1]])
        elif isinstance(parent, dict):
            parent["extra"] = 1
    text = json.dumps(raw, separators=(",", ":"))
    if r.randint(0, 9) == 0:
        text = text.replace("1.5", "NaN", 1)
    return data[:6] + zlib.compress(text.encode())


# --- readers ------------------------------------------------------------------------------------------------------
def _reader(fmt: str) -> tuple[Callable[[Path], object], tuple[type[BaseException], ...], str]:
    """(read PATH, the reader's own error classes, file suffix)."""
    if fmt == "zbc":
        from motiontool.formats.zbc import ConfigError, read_config
        return read_config, (ConfigError,), ".zbc"
    if fmt == "dat":
        from motiontool.formats.dat import DatError, read_dat
        return read_dat, (DatError,), ".dat"
    if fmt == "zba":
        from motiontool.formats.zba import ZbaError, read_zba
        return read_zba, (ZbaError,), ".zba"
    if fmt == "zbo":
        from motiontool.scope.zbo import ZboError, load
        return load, (ZboError,), ".zbo"
    if fmt == "testrun":
        from motiontool.scope.testrun import BadTestrunFile, NotTestrun, read_testrun
        return read_testrun, (BadTestrunFile, NotTestrun), ".txt"
    if fmt == "trace":
        from motiontool.cameditor.trace import TraceError, read_trace
        return read_trace, (TraceError,), ".csv"
    raise KeyError(fmt)


class Crash(Exception):
    pass


def check_file(fmt: str, data: bytes, folder: Path) -> None:
    """Read ``data`` as a user's file of format ``fmt``; raises Crash (or the crash itself) when it is one."""
    read, expected, suffix = _reader(fmt)
    path = folder / f"case{suffix}"
    path.write_bytes(data)
    with contextlib.suppress(expected):
        read(path)


def check_image(data: bytes) -> None:
    """Refused with ImageError, or accepted and run for 50 ms without an internal fault or a failed request."""
    from motiontool.comms.protocol import LinkError
    from motiontool.controller.embedded import EmbeddedLink

    try:
        ProgramImage.from_bytes(data)
    except ImageError:
        return
    link = EmbeddedLink()
    faults = []
    link.subscribe(lambda e: faults.append(e.text) if e.kind == "error" and e.number == 199 else None)
    try:
        link.download(data, name="fuzz")
        link.start()
        link.advance(50)
    except LinkError as exc:
        if "internal error" in str(exc) or "no program" not in str(exc):
            raise Crash(f"the link failed: {exc}") from None
    finally:
        link.close()
    if faults:
        raise Crash(f"internal fault: {faults[0]}")


def check_dpl(data: bytes, folder: Path) -> None:
    """A DPL program (the APC's language) read from its file by the checker `motiontool check` uses: diagnostics,
    never an exception; a program the checker accepts is downloaded to the simulated APC over its link and runs
    for 50 ms, where a refusal is a LinkError and a program's fault an error event - anything else is a crash."""
    from motiontool.comms.protocol import LinkError
    from motiontool.controller.dpl_program import dpl_link
    from motiontool.dpl.driver import check_source
    from motiontool.dpl.image import DplImage

    path = folder / "case.dpl"
    path.write_bytes(data)
    checked = check_source(path=path)
    if not checked.ok:
        return
    link = dpl_link()
    try:
        link.download(DplImage(path.name, checked.source).to_bytes(), name=path.name)
        link.start()
        link.advance(50)
    except LinkError as exc:
        if "internal" in str(exc):
            raise Crash(f"the link failed: {exc}") from None
    finally:
        link.close()


def check_program(text: str) -> None:
    fuzz_compiler.check_compile(text)


# --- hostile shapes (issue 26 item 7; decisions R15-R17) -----------------------------------------------------------
def deflated_zeros(size: int) -> bytes:
    """``size`` zero bytes deflated in 1 MiB steps (100 MiB: some 100 KB, a fraction of a second)."""
    deflate = zlib.compressobj(9)
    chunk = bytes(1 << 20)
    parts = [deflate.compress(chunk) for _ in range(size // len(chunk))]
    return b"".join(parts) + deflate.compress(bytes(size % len(chunk))) + deflate.flush()


@functools.cache
def hostile_cases() -> list[tuple[str, str, bytes, tuple[str, ...] | None]]:
    """(name, format, file's bytes, words) for the shapes the mutations do not reach: sizes declared far beyond the
    data, compressed bombs, deep parentheses, a BOM with CRLF. ``words`` are what the one-line refusal must say (the
    limit; a file's refusal also names its path), None for a file that must be read."""
    from motiontool.aposs.image import MAGIC, MAX_BODY_BYTES
    from motiontool.camcurve.model import MAX_ARRAY_ELEMENTS, MAX_INTERVALS
    from motiontool.dpl.parser import MAX_NESTING
    from motiontool.scope.zbo import MAX_SAMPLES

    dat, zbc, zbo = SEEDS["dat"][0], SEEDS["zbc"][0], SEEDS["zbo"][0]
    bomb = base64.b64encode(deflated_zeros(4 << 20)).decode("ascii")  # 4 MiB for 4 values (32 bytes)

    def zbo_with(capacity=None, **data) -> bytes:
        doc = json.loads(zbo)
        curve = doc["curves"][0]
        if capacity is not None:
            curve["capacity"] = capacity
        curve["data"].update(data)
        return json.dumps(doc).encode()

    def dpl(depth: int) -> bytes:
        return ("Initial {\n    x% = " + "(" * depth + "1" + ")" * depth + "\n}\n").encode()

    count = json.loads(zbo)["curves"][0]["data"]["count"]
    deeper = (f"nested deeper than {MAX_NESTING} levels",)
    return [
        ("dat intervals 10^8", "dat", dat.replace("intervals = 40", "intervals = 100000000").encode(),
         ("intervals", str(MAX_INTERVALS))),
        ("dat elements 10^8", "dat", dat.replace("elements = 92", "elements = 100000000").encode(),
         ("elements", str(MAX_ARRAY_ELEMENTS))),
        ("zbc intervals 10^8", "zbc", zbc.replace("intervals = 40", "intervals = 100000000").encode(),
         ("intervals", str(MAX_INTERVALS))),
        ("zbc size 10^8", "zbc", zbc.replace("size = 4\n", "size = 100000000\n").encode(),
         ("size", str(MAX_ARRAY_ELEMENTS))),
        ("zbo capacity 10^9", "zbo", zbo_with(capacity=10**9), ("capacity", str(MAX_SAMPLES))),
        ("zbo values bomb", "zbo", zbo_with(values=bomb), ("data.values", f"more than the {count} values")),
        ("zbo time bomb", "zbo", zbo_with(time_ms=bomb), ("data.time_ms", f"more than the {count} values")),
        ("image body bomb", "image", MAGIC + bytes([1]) + deflated_zeros(MAX_BODY_BYTES + (4 << 20)),
         (f"more than {MAX_BODY_BYTES} bytes",)),
        (f"dpl {MAX_NESTING} parentheses", "dpl", dpl(MAX_NESTING), None),
        (f"dpl {MAX_NESTING + 1} parentheses", "dpl", dpl(MAX_NESTING + 1), deeper),
        ("dpl 5000 parentheses", "dpl", dpl(5000), deeper),
        ("dpl BOM and CRLF", "dpl", b"\xef\xbb\xbfInitial {\r\n    x% = 1\r\n}\r\n", None),
    ]


def check_hostile(fmt: str, data: bytes, words: tuple[str, ...] | None, folder: Path) -> None:
    """A hostile shape ends in one line naming the file (images come as bytes, without one) and the limit, or is
    read when ``words`` is None; anything else - a traceback, a MemoryError, a wrong message - is a Crash."""
    def refused(message: str, path: Path | None) -> None:
        if words is None:
            raise Crash(f"a valid file was refused: {message}")
        missing = [w for w in ((str(path),) if path else ()) + words if w not in message]
        if "\n" in message or missing:
            raise Crash(f"the refusal {message!r} does not say {missing or 'it in one line'}")

    if fmt == "image":
        try:
            ProgramImage.from_bytes(data)
        except ImageError as exc:
            refused(str(exc), None)
            return
    elif fmt == "dpl":
        from motiontool.dpl.driver import check_source

        path = folder / "case.dpl"
        path.write_bytes(data)
        checked = check_source(path=path)
        if checked.diagnostics:
            refused(checked.diagnostics[0].format(), path)
            return
    else:
        read, expected, suffix = _reader(fmt)
        path = folder / f"case{suffix}"
        path.write_bytes(data)
        try:
            read(path)
        except expected as exc:
            refused(str(exc), path)
            return
    if words is not None:
        raise Crash(f"accepted; expected a refusal saying {words}")


# --- one case per generator -----------------------------------------------------------------------------------------
def program_case(r) -> str:
    return r.choice([fuzz_compiler.token_stream, fuzz_compiler.mutated_example, fuzz_compiler.deep_nesting])(r)


def run_case(fmt: str, r, folder: Path) -> tuple[str, object]:
    """Make one case (returned, for the report) and check it."""
    if fmt == "program":
        case = program_case(r)
        check_program(case)
    elif fmt == "image":
        case = mutate_image(r, r.choice(SEEDS["image"]))
        check_image(case)
    elif fmt == "dpl":
        case = mutate_file(r, r.choice(SEEDS[fmt]))
        check_dpl(case, folder)
    else:
        case = mutate_file(r, r.choice(SEEDS[fmt]))
        check_file(fmt, case, folder)
    return fmt, case


FORMATS = ["program", "image", "dpl", "zbc", "dat", "zba", "zbo", "testrun", "trace"]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=600, help="cases per format (default 600)")
    parser.add_argument("--seed", type=int, default=18)
    args = parser.parse_args(argv)
    total = {"cases": 0, "crashes": 0, "slowest": 0.0}
    crashes: dict[tuple, tuple[str, object, str]] = {}
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        for fmt in FORMATS:
            r = random.Random(f"{args.seed}-{fmt}")
            count, slowest, slowest_state = 0, 0.0, None
            for _ in range(args.cases):
                state = r.getstate()
                start = time.perf_counter()
                try:
                    run_case(fmt, r, folder)
                except Exception as exc:  # noqa: BLE001 - every escape is a finding
                    frames = traceback.extract_tb(exc.__traceback__)
                    inner = next((f for f in reversed(frames) if "/motiontool/" in f.filename), frames[-1])
                    key = (fmt, type(exc).__name__, Path(inner.filename).name, inner.lineno)
                    if key not in crashes:
                        replay = random.Random()
                        replay.setstate(state)
                        _, case = _make(fmt, replay)
                        crashes[key] = (fmt, case, "".join(traceback.format_exception(exc)[-3:]))
                    count += 1
                if time.perf_counter() - start > slowest:
                    slowest, slowest_state = time.perf_counter() - start, state
            print(f"fuzz_files_{fmt}_cases: {args.cases} cases")
            print(f"fuzz_files_{fmt}_crashes: {count} count")
            print(f"fuzz_files_{fmt}_slowest: {slowest:.3f} s")
            replay = random.Random()
            replay.setstate(slowest_state)
            case = _make(fmt, replay)[1]
            print(f"# slowest {fmt} case ({len(case)} chars/bytes): {case[:120]!r}", file=sys.stderr)
            total["cases"] += args.cases
            total["crashes"] += count
            total["slowest"] = max(total["slowest"], slowest)
        hostile = 0
        for name, fmt, data, words in hostile_cases():
            try:
                check_hostile(fmt, data, words, folder)
            except Exception as exc:  # noqa: BLE001 - every escape is a finding
                hostile += 1
                print(f"\n=== hostile {name}\n{''.join(traceback.format_exception(exc)[-3:])}", file=sys.stderr)
        print(f"fuzz_files_hostile_cases: {len(hostile_cases())} cases")
        print(f"fuzz_files_hostile_crashes: {hostile} count")
    print(f"fuzz_files_cases: {total['cases']} cases")
    print(f"fuzz_files_crashes: {total['crashes']} count")
    print(f"fuzz_files_slowest: {total['slowest']:.3f} s")
    for key, (fmt, case, trace) in crashes.items():
        shown = case if isinstance(case, str) else repr(case)
        print(f"\n=== {key}\n{trace}case ({fmt}, {len(case)} chars/bytes): {shown[:2000]!r}", file=sys.stderr)
    return 1 if crashes or hostile else 0


def _make(fmt: str, r):
    """The case run_case would make from r, without checking it (for the report)."""
    if fmt == "program":
        return fmt, program_case(r)
    if fmt == "image":
        return fmt, mutate_image(r, r.choice(SEEDS["image"]))
    return fmt, mutate_file(r, r.choice(SEEDS[fmt]))


if __name__ == "__main__":
    sys.exit(main())
