"""The kernel's traces stay identical row for row (issue 30 item 1: a faster kernel must not change a result).

Every sample (its first 5 s), the Design Guide's CAM programs D07/D08, SYNCV/SYNCP/SYNCM programs and the CAM line
of benchmarks/kernel_rtf.py (1 axis interpolated, 8 axes on one EmbeddedBus with node 1's virtual master, tick by
tick and in 100 ms steps) are fingerprinted every ms (tests/kernel/trace_identity.py) and compared with the
fingerprints of the kernel before its optimisation (golden/trace_identity.json). A deliberate change of behaviour
regenerates the golden file with `python -m tests.kernel.trace_identity` and says why in its commit.
"""

from __future__ import annotations

import json

import pytest

from tests.kernel.trace_identity import GOLDEN, runs

GOLDEN_RUNS = json.loads(GOLDEN.read_text(encoding="utf-8"))
RUNS = dict(runs())


def test_every_golden_run_is_still_run():
    assert sorted(RUNS) == sorted(GOLDEN_RUNS)


@pytest.mark.parametrize("name", sorted(RUNS))
def test_trace_is_identical_row_for_row(name: str):
    got, want = RUNS[name](), GOLDEN_RUNS[name]
    assert got["ms"] == want["ms"]
    first = next((i for i, (a, b) in enumerate(zip(got["seconds"], want["seconds"], strict=True)) if a != b), None)
    assert first is None, f"{name}: the trace differs in second {first} (ms {first * 1000}..{first * 1000 + 999})"
    assert (got["prints"], got["print_count"]) == (want["prints"], want["print_count"]), f"{name}: PRINT output"
