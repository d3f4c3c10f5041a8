"""Fuzzing program images: ANY mutated image is refused with ImageError (naming its place) or runs on the embedded
controller without an internal fault (issue 18, item 6). The mutations (benchmarks/fuzz_files.py: values, types and
instructions of the JSON body, bytes of the container) are driven by hypothesis-drawn bytes, so a failure shrinks.

MOTIONTOOL_FUZZ_IMAGES sets the number of cases (default 300); the benchmark runs thousands."""

from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

from hypothesis import HealthCheck, given, note, settings
from hypothesis import strategies as st

from tests.aposs.test_fuzz import ByteRandom


def _load_fuzz_files():
    path = Path(__file__).resolve().parents[2] / "benchmarks" / "fuzz_files.py"
    spec = importlib.util.spec_from_file_location("motiontool_fuzz_files", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


fuzz_files = _load_fuzz_files()
CASES = int(os.environ.get("MOTIONTOOL_FUZZ_IMAGES", "300"))


@settings(max_examples=CASES, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(st.binary(min_size=8, max_size=64).map(ByteRandom))
def test_mutated_images_are_refused_or_run_without_an_internal_fault(r):
    data = fuzz_files.mutate_image(r, r.choice(fuzz_files.SEEDS["image"]))
    note(f"image: {data!r}")
    fuzz_files.check_image(data)
