"""Fuzzing the file readers a user's file reaches (.zbc, .dat, .zba, .zbo, Testrun .txt, trace CSV): a mutated file
is read or refused with the reader's own error, never a crash (issue 18, items 5 and 8). The mutations are those of
benchmarks/fuzz_files.py (other scripts' digits, 5 000-digit numbers, NaN, invalid UTF-8, truncation, repeated
lines, ...), driven by hypothesis-drawn bytes so that a failure shrinks.
The hostile shapes of benchmarks/fuzz_files.py (declared sizes, zlib bombs, deep parentheses, a BOM with CRLF) end
in a one-line refusal naming the file and the limit (issue 26 item 7).

MOTIONTOOL_FUZZ_FILES sets the number of cases per format (default 100)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, note, settings
from hypothesis import strategies as st

from tests.aposs.test_fuzz import ByteRandom
from tests.aposs.test_image_fuzz import fuzz_files

CASES = int(os.environ.get("MOTIONTOOL_FUZZ_FILES", "100"))
FILE_FORMATS = ["zbc", "dat", "zba", "zbo", "testrun", "trace"]


@pytest.mark.parametrize("fmt", FILE_FORMATS)
def test_mutated_files_are_read_or_refused_with_the_readers_error(fmt):
    @settings(max_examples=CASES, deadline=None, derandomize=True, database=None,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
    @given(st.binary(min_size=4, max_size=48).map(ByteRandom))
    def case(r):
        data = fuzz_files.mutate_file(r, r.choice(fuzz_files.SEEDS[fmt]))
        note(f"{fmt}: {data!r}")
        with tempfile.TemporaryDirectory() as folder:
            fuzz_files.check_file(fmt, data, Path(folder))

    case()


def test_mutated_dpl_programs_get_diagnostics_and_accepted_ones_run():
    """A DPL program (tests/dpl/programs mutated) is checked from its file with diagnostics, never an exception: a
    5 000-digit constant ended in Python's ValueError; one the checker accepts runs 50 ms on the simulated APC."""
    @settings(max_examples=max(CASES // 4, 10), deadline=None, derandomize=True, database=None,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
    @given(st.binary(min_size=4, max_size=48).map(ByteRandom))
    def case(r):
        data = fuzz_files.mutate_file(r, r.choice(fuzz_files.SEEDS["dpl"]))
        note(f"dpl: {data!r}")
        with tempfile.TemporaryDirectory() as folder:
            fuzz_files.check_dpl(data, Path(folder))

    case()


@pytest.mark.parametrize("name", [case[0] for case in fuzz_files.hostile_cases()])
def test_hostile_shapes_end_in_a_one_line_refusal_naming_the_file_and_the_limit(tmp_path, name):
    """Issue 26 item 7 (decisions R15-R17): sizes declared far beyond the data (.dat/.zbc 10^8, .zbo capacity 10^9),
    zlib bombs (a .zbo curve, a program image inflating past its 96 MiB limit), 100, 101 and 5 000 parentheses and a
    BOM with CRLF in DPL programs are refused in one line naming the file and the limit, or read when valid - never a
    traceback or a MemoryError. In process: every reader stops at its limit (the image at 96 MiB)."""
    _, fmt, data, words = next(case for case in fuzz_files.hostile_cases() if case[0] == name)
    fuzz_files.check_hostile(fmt, data, words, tmp_path)
