"""The samples print what their headers say on a controller that has been up for hours (issue 23 item 5), not
only on one that has just been switched on: the IDE's controller has been running since the IDE started and a
real one for hours, so a sample that reads TIME as "ms since the start" (07 printed 10800502 ms, 27 never gave
up at TIME < 5000) measures from a `t0 = TIME - 1` of its own.

The controller's clock is set to 3 h before the download instead of ticking an idle controller through 3 h of
virtual time (10.8 million ticks per sample, about 15 s each): an idle controller with the default (standing)
master keeps nothing else that depends on the clock's value. The Test-inputs times count from the download."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.test_samples import SAMPLES, parse_header, run_sample

THREE_HOURS_MS = 3 * 3600 * 1000


@pytest.mark.parametrize("path", [pytest.param(path, id=path.stem) for path in SAMPLES])
def test_sample_runs_as_its_header_says_after_three_hours_uptime(path: Path):
    header = parse_header(path)
    outcome = run_sample(path, header, uptime_ms=THREE_HOURS_MS)
    assert outcome.errors == (header.expect_errors or []), f"controller errors: {outcome.errors}"
    if header.expect:
        assert outcome.prints == header.expect
    assert outcome.state == header.expect_end
