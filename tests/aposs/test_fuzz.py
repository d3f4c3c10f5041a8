"""Property-based fuzzing of the APOSS compiler: ANY input gives diagnostics, never an exception.

The generators live in benchmarks/compiler_fuzz as plain functions of a random.Random-like object, shared with
the 100 000-case benchmark. Here hypothesis drives them: it draws bytes, ByteRandom turns them into the generator's
choices, so a failure is shrunk (fewer and simpler choices) and replayed deterministically. The report shows the
generated source of a failing example ("source: ...").

Properties (fuzz.check_compile): compile_source returns; every diagnostic has a known severity and formats; a
diagnostic in the input file lies inside it (1 <= line <= lines + 1, col >= 1); without errors there is an image and
ProgramImage.from_bytes(image.to_bytes()) == image; with errors there is no image. Generated valid programs must
compile without errors (every fourth also as a debug build).

MOTIONTOOL_FUZZ_EXAMPLES sets the total number of generated cases (default 2400), shared out as in SHARES.
"""

from __future__ import annotations

import importlib.util
import os
import random
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, event, given, note, settings
from hypothesis import strategies as st

from motiontool.aposs.driver import compile_source

# Compiler crashes the fuzzer found that are not fixed yet: (exception, file under src/motiontool, function, source
# line) of the crash site as fuzz.crash_site computes it (the innermost package frame; for a RecursionError the frame
# that recurses), then a minimal reproducer. Only these exact sites are tolerated by compile_checked;
# test_known_crashes_still_crash fails as soon as one is fixed, so that its entry gets deleted.
KNOWN_CRASHES: list[tuple[str, str, str, str, str]] = [
    # Empty: the crashes the fuzzer found (non-finite constants in round/sin/cos/tan, macro calls nested 500
    # deep) are fixed; test_former_crashes_give_diagnostics keeps their reproducers.
]
_KNOWN_SITES = {entry[:4] for entry in KNOWN_CRASHES}


def _load_generators():
    """The package benchmarks/compiler_fuzz, loaded from its path (benchmarks/ is not on sys.path)."""
    if "compiler_fuzz" in sys.modules:  # benchmarks/fuzz_files.py (test_image_fuzz) imports it by name
        return sys.modules["compiler_fuzz"]
    path = Path(__file__).resolve().parents[2] / "benchmarks" / "compiler_fuzz" / "__init__.py"
    spec = importlib.util.spec_from_file_location("compiler_fuzz", path, submodule_search_locations=[str(path.parent)])
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


fuzz = _load_generators()

TOTAL = int(os.environ.get("MOTIONTOOL_FUZZ_EXAMPLES", "2400"))
SHARES = {"token_stream": 0.30, "mutated_example": 0.25, "semantic_soup": 0.15, "valid_program": 0.15,
          "locations": 0.13, "deep_nesting": 0.02}


def fuzz_settings(share: str):
    return settings(max_examples=max(1, round(TOTAL * SHARES[share])), deadline=None, derandomize=True,
                    database=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


class ByteRandom:
    """The part of random.Random the generators use (randint, choice, random), read from hypothesis-drawn bytes.

    Much faster than st.randoms() (one draw per example), and hypothesis shrinks the bytes towards shorter and
    smaller, i.e. towards fewer tokens and the first choices; when the bytes run out every choice is the first."""

    def __init__(self, data: bytes):
        self.data = data
        self.pos = 0

    def _take(self, size: int) -> int:
        chunk = self.data[self.pos:self.pos + size]
        self.pos += size
        return int.from_bytes(chunk.ljust(size, b"\0"), "big")

    def randint(self, a: int, b: int) -> int:
        span = b - a + 1
        return a if span <= 1 else a + self._take((span.bit_length() + 7) // 8) % span

    def choice(self, seq):
        return seq[self.randint(0, len(seq) - 1)]

    def random(self) -> float:
        return self._take(2) / 65536


def randoms(min_size: int, max_size: int):
    """A ByteRandom over min_size..max_size bytes (what the generator typically consumes)."""
    return st.binary(min_size=min_size, max_size=max_size).map(ByteRandom)


def compile_checked(text: str, must_compile: bool = False):
    """fuzz.check_compile, tolerating only the crash sites listed in KNOWN_CRASHES (then None)."""
    note(f"source: {text!r}")
    try:
        return fuzz.check_compile(text, must_compile=must_compile)
    except fuzz.PropertyViolation:
        raise
    except Exception as exc:
        site = fuzz.crash_site(exc)
        if site in _KNOWN_SITES:
            event(f"known crash: {site[0]} in {site[1]} {site[2]}")
            return None
        raise


@fuzz_settings("token_stream")
@given(randoms(64, 600))
def test_random_token_streams_give_diagnostics(r):
    compile_checked(fuzz.token_stream(r))


@fuzz_settings("mutated_example")
@given(randoms(8, 64))
def test_mutated_examples_give_diagnostics(r):
    compile_checked(fuzz.mutated_example(r))


@fuzz_settings("semantic_soup")
@given(randoms(256, 3000))
def test_programs_with_wrong_names_types_and_constants_give_diagnostics(r):
    compile_checked(fuzz.semantic_soup(r))


@fuzz_settings("deep_nesting")
@given(randoms(2, 8))
def test_deep_and_long_constructs_give_diagnostics(r):
    compile_checked(fuzz.deep_nesting(r))


@fuzz_settings("locations")
@given(randoms(32, 2000), st.sampled_from(["token_stream", "mutated_example", "semantic_soup"]))
def test_diagnostic_locations_lie_inside_the_source(r, generator):
    text = getattr(fuzz, generator)(r)
    result = compile_checked(text)
    if result is None:
        return
    lines = text.count("\n") + 1
    for d in result.diagnostics:
        if d.loc.file == fuzz.INPUT_PATH:
            assert 1 <= d.loc.line <= lines + 1, d.format()
            assert d.loc.col >= 1, d.format()
        event(f"{d.severity} in {'the input' if d.loc.file == fuzz.INPUT_PATH else 'another file'}")


@fuzz_settings("valid_program")
@given(randoms(256, 3000))
def test_generated_valid_programs_compile_and_round_trip(r):
    text = fuzz.valid_program(r)
    result = compile_checked(text, must_compile=True)
    if result is not None:  # a known crash is reported by its own test
        assert len(result.image) > 0
        event(f"{len(text.splitlines()) // 20 * 20}+ lines")


def test_valid_program_generator_covers_the_constructs():
    """The round-trip test is only worth its time if the generator writes every construct."""
    r = random.Random(7)
    text = "\n".join(fuzz.valid_program(r) for _ in range(150)).upper()
    for construct in ("DIM ", "#PRAGMA NOIMPLICIT", "#DEFINE", "LONG ", "DOUBLE ", "IF ", "ELSEIF ", "ELSE\n",
                      "ENDIF", "WHILE ", "ENDWHILE", "REPEAT", "UNTIL ", "SWITCH ", "CASE ", "DEFAULT:", "ENDSWITCH",
                      "BREAK", "PRINT ", "GOSUB ", "SUBMAINPROG", "SUBPROG ", "RETURN", "ENDPROG", "RETURN(",
                      "GOTO ", "LOOP ", "ON INT", "SYSVAR[", "[] = ", "++", "#IF", "#ELSE", "#ENDIF", " EXP "):
        assert construct in text, construct


@pytest.mark.parametrize("source", [
    "a = round(1e308 * 10.0)", "a = round((1e308 * 10.0) - (1e308 * 10.0))", "a = sin(1e308 * 10.0)",
    "#define F(x) x\na = " + "F(" * 600 + "1" + ")" * 600,
])
def test_former_crashes_give_diagnostics(source):
    result = compile_source(source, "known.m")
    assert result.errors


def test_nested_comment_is_reported_where_it_is():
    result = compile_source("a = 1\n/* multi\nline /* nested */", "f.m")
    assert (result.errors[0].loc.line, result.errors[0].loc.col) == (3, 6)


def test_known_crashes_still_crash():
    """Each KNOWN_CRASHES entry documents a live bug; when it is fixed, delete the entry."""
    for *site, source in KNOWN_CRASHES:
        try:
            compile_source(source, "known.m")
        except Exception as exc:
            assert list(fuzz.crash_site(exc)) == site, f"{site} now crashes elsewhere: {fuzz.crash_site(exc)}"
        else:
            raise AssertionError(f"fixed, delete it from KNOWN_CRASHES: {site}")
