"""A link request of the oscilloscope off the GUI thread (issue 27 item 2: the window never waits for the wire).
`PollJob` runs one at a time (a poll asked again while one is on the line is left out); `wait(window, text,
request)` is for Start/Stop, Single Shot, TESTSETP and Tune, which need the answer before they go on: the IDE's
`waiting` (motiontool.qtjobs, decision I34), so the window paints, says `text`, shows a busy cursor, and a Start
clicked again meanwhile is dropped, not run once the first has ended."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from motiontool.qtjobs.jobs import PollJob
from motiontool.qtjobs.waiting import waiting

__all__ = ["PollJob", "wait"]


def wait(window, text: str, request: Callable[[], Any]) -> Any:
    """`request()` on a thread; returns its answer or raises what it raised (a LinkError or ValueError; anything
    else as a LinkError saying what failed)."""
    return waiting(window, text, request)
