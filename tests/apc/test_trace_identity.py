"""The APC's traces stay identical row for row (issue 30 item 1: a faster APC must not change a result).

The CTSync 8-drive CAM line and the single axis of benchmarks/apc_rtf.py, a line with faulty messages, the manual's
DPL programs (§6.4, §7.1-§7.6, tests/dpl/programs), CAM and digital lock selected by a freeze, a single-shot CAM
with re-arm, a delta-segment overrun, and position/speed/offset profiles with stops are fingerprinted every ms
(tests/apc/trace_identity.py) and compared with the fingerprints of the APC before its optimisation
(golden/trace_identity.json). A deliberate change of behaviour regenerates the golden file with
`python -m tests.apc.trace_identity` and says why in its commit.
"""

from __future__ import annotations

import json

import pytest

from tests.apc.trace_identity import GOLDEN, runs
from tests.trace_hash import first_different_second

GOLDEN_RUNS = json.loads(GOLDEN.read_text(encoding="utf-8"))
RUNS = dict(runs())


def test_every_golden_run_is_still_run():
    assert sorted(RUNS) == sorted(GOLDEN_RUNS)


@pytest.mark.parametrize("name", sorted(RUNS))
def test_trace_is_identical_row_for_row(name: str):
    got, want = RUNS[name](), GOLDEN_RUNS[name]
    difference = first_different_second(name, got, want)
    assert difference is None, difference
    assert (got["events"], got["event_count"]) == (want["events"], want["event_count"]), f"{name}: errors, trips"
