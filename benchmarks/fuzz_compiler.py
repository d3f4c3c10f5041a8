"""Fuzz the APOSS compiler with generated programs: no input may raise, every input only gives diagnostics.

Run from the repository root:

    .venv/bin/python benchmarks/fuzz_compiler.py [--cases 100000] [--seed 305] [--jobs N]

Prints ``name: value unit`` lines (``fuzz_cases``, ``fuzz_rate``, ``fuzz_crashes`` …). Exit status 1 if any input
raised an exception or broke a property; then each distinct crash site goes to stderr with its count, a shrunk
reproducer and the last frames of the traceback. The cases are split into units of CHUNK cases with their own
seeds, so the cases (and the findings) do not depend on --jobs.

The generators and the properties live in the package benchmarks/compiler_fuzz; they are plain functions of a
``random.Random``-like object ``r`` (only ``r.random()``, ``r.randint()`` and ``r.choice()`` are used). This script
drives them with ``random.Random``; ``tests/aposs/test_fuzz.py`` drives the very same functions with
hypothesis-drawn bytes, which shrink.

Generators (share of the benchmark's cases in GENERATORS):
  token_stream     text from a vocabulary of keywords, command names, identifiers, numbers (decimal, hex, octal,
                   doubles, characters), strings, operators, preprocessor lines, comments, junk characters and
                   newlines;
  mutated_example  an example program of tests/aposs/manual with 1-4 random edits (lines deleted, duplicated,
                   swapped, moved or borrowed; characters deleted or inserted; tokens replaced, deleted, duplicated
                   or swapped; the text truncated);
  semantic_soup    a grammar-generated program with wrong names, types, arities, constants and definitions
                   sprinkled in; most stay parseable, so they reach the checks and the code generator;
  valid_program    a grammar-generated program that must compile without errors (every fourth also as a debug
                   build);
  deep_nesting     very deep or very long constructs (parentheses, unary chains, blocks, macros, lines).

Properties (check_compile): compile_source returns; every diagnostic has a known severity, formats, and - when it
is in the input file - 1 <= line <= lines + 1 and col >= 1; with no error there is an image and
ProgramImage.from_bytes(image.to_bytes()) == image, with an error there is none.
"""


from __future__ import annotations

import argparse
import os
import random
import re
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from compiler_fuzz import (
    EXAMPLES_DIR,
    GENERATORS,
    INPUT_PATH,
    REPO,
    TOKEN_RE,
    PropertyViolation,
    check_compile,
    crash_site,
    deep_nesting,
    last_frames,
    mutated_example,
    token_stream,
)

# benchmarks/fuzz_files.py reaches the generators through `import fuzz_compiler`
__all__ = ["EXAMPLES_DIR", "check_compile", "deep_nesting", "main", "mutated_example", "token_stream"]

# --- the benchmark ---------------------------------------------------------------------------------------------------
CHUNK = 500  # cases per work unit; each unit has its own seed, so the result does not depend on --jobs


def outcome(text: str, must_compile: bool) -> tuple | None:
    """None if all is well, else a key naming the failure: the crash site or the broken property."""
    try:
        check_compile(text, must_compile=must_compile)
    except PropertyViolation as exc:
        return ("property", str(exc).split("\n")[0].split(":")[0], "", "")
    except Exception as exc:  # noqa: BLE001 - every exception is a finding
        return crash_site(exc)
    return None


def describe_failure(text: str, must_compile: bool) -> str:
    """The broken property with the diagnostics, or the last frames of the traceback."""
    try:
        check_compile(text, must_compile=must_compile)
    except PropertyViolation as exc:
        return str(exc)
    except Exception as exc:  # noqa: BLE001
        return last_frames(exc)
    return "(no failure)"


def run_unit(unit: tuple[str, int, int, int]) -> tuple[str, int, float, dict, dict]:
    """Run `count` cases of one generator from the seed (seed, name, index): (name, count, seconds, failure
    counts by key, first failing text by key)."""
    name, seed, index, count = unit
    generate, _ = GENERATORS[name]
    r = random.Random(f"{seed}:{name}:{index}")
    must = name == "valid_program"
    counts: dict[tuple, int] = {}
    first: dict[tuple, str] = {}
    start = time.perf_counter()
    for _ in range(count):
        text = generate(r)
        key = outcome(text, must)
        if key is not None:
            counts[key] = counts.get(key, 0) + 1
            first.setdefault(key, text)
    return name, count, time.perf_counter() - start, counts, first


def shrink(text: str, key: tuple, must_compile: bool, budget: float = 10.0) -> str:
    """A smaller text with the same failure key (time-boxed): repeatedly drop runs of lines, then of tokens, then
    of characters, runs halving in length down to 1, until nothing more can go."""
    deadline = time.perf_counter() + budget
    splitters = [(lambda t: t.split("\n"), "\n"), (lambda t: re.findall(r"\s+|" + TOKEN_RE.pattern, t), ""),
                 (list, "")]
    progress = True
    while progress and time.perf_counter() < deadline:
        progress = False
        for split, joiner in splitters:
            parts = split(text)
            chunk = max(1, len(parts) // 2)
            while chunk >= 1 and time.perf_counter() < deadline:
                i = 0
                while i + chunk <= len(parts) and time.perf_counter() < deadline:
                    candidate = parts[:i] + parts[i + chunk:]
                    if candidate and outcome(joiner.join(candidate), must_compile) == key:
                        parts, progress = candidate, True
                    else:
                        i += 1 if chunk <= 2 else chunk
                chunk //= 2
            text = joiner.join(parts)
    return text


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cases", type=int, default=100_000, help="total number of generated programs")
    parser.add_argument("--seed", type=int, default=305)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="worker processes")
    args = parser.parse_args(argv)
    units = []
    for name, (_, share) in GENERATORS.items():
        cases = args.cases * share // 1000
        if name == "token_stream":  # the rounding remainder
            cases += args.cases - sum(args.cases * s // 1000 for _, s in GENERATORS.values())
        units += [(name, args.seed, i, min(CHUNK, cases - i * CHUNK)) for i in range((cases + CHUNK - 1) // CHUNK)]
    start = time.perf_counter()
    if args.jobs > 1:
        with ProcessPoolExecutor(args.jobs) as pool:
            results = list(pool.map(run_unit, units))
    else:
        results = [run_unit(u) for u in units]
    elapsed = time.perf_counter() - start
    done = sum(r[1] for r in results)
    counts: dict[tuple, int] = {}
    first: dict[tuple, tuple[str, str]] = {}
    for name, _, _, unit_counts, unit_first in results:
        for key, n in unit_counts.items():
            counts[key] = counts.get(key, 0) + n
            first.setdefault(key, (name, unit_first[key]))
    crashes = sum(n for k, n in counts.items() if k[0] != "property")
    print(f"fuzz_cases: {done} cases")
    print(f"fuzz_jobs: {args.jobs} count")
    print(f"fuzz_time: {elapsed:.1f} s")
    print(f"fuzz_rate: {done / elapsed:.0f} cases/s")
    for name in GENERATORS:
        n = sum(r[1] for r in results if r[0] == name)
        seconds = sum(r[2] for r in results if r[0] == name)
        print(f"fuzz_rate_{name}: {n / seconds if seconds else 0:.0f} cases/s per process ({n} cases)")
    print(f"fuzz_crashes: {crashes} count")
    print(f"fuzz_crash_sites: {sum(1 for k in counts if k[0] != 'property')} count")
    print(f"fuzz_property_failures: {sum(n for k, n in counts.items() if k[0] == 'property')} count")
    where = Path(INPUT_PATH).relative_to(REPO)
    for key, (name, text) in first.items():
        must = name == "valid_program"
        small = text if key[0] == "property" and must else shrink(text, key, must)
        print(f"\n=== {counts[key]} x {key[0]} {key[1]} {key[2]}: {key[3]}", file=sys.stderr)
        print(f"first from {name} ({len(text)} chars), shrunk to {len(small)} chars; reproduce with", file=sys.stderr)
        print(f"compile_source({small!r}, {str(where)!r})", file=sys.stderr)
        print(describe_failure(small, must), file=sys.stderr)
    return 1 if counts else 0


if __name__ == "__main__":
    sys.exit(main())
