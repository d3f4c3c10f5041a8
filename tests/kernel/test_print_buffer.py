"""The PRINT output buffer is bounded like the drive's: a full buffer makes PRINT wait, so a PRINT flood cannot
stall real time, Break or the IDE (issue 18, item 9; decisions K82). The IDE's side: tests/ui/test_print_flood.py."""

from __future__ import annotations

from motiontool.kernel.controller import PRINT_BUFFER_LINES
from tests.kernel.helpers import start

FLOOD = 'main:\nPRINT "line ", TIME\nGOTO main\n'


def test_print_waits_while_the_output_buffer_is_full():
    """The command line's link takes every line each ms: at most a buffer of lines per ms, then PRINT waits."""
    run = start(FLOOD)
    run.advance(5)
    assert len(run.prints) == 5 * PRINT_BUFFER_LINES
    assert run.print_times == [t for t in range(1, 6) for _ in range(PRINT_BUFFER_LINES)]
    assert run.state == "running"


def test_lines_printed_before_an_error_come_before_it():
    run = start('PRINT "one"\nPRINT "two"\nSET SWPOSLIMACT 1\nPOSA 600000\n')
    run.advance(100)
    events = [(e.kind, e.text) for e in run.controller.events if e.kind in ("print", "error")]
    assert events[:3] == [("print", "one"), ("print", "two"), ("error", "error 111: SW end limit")]
