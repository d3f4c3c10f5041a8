"""The FC 300 keypad (LCP) as a program sees it: INKEY reads the key codes that were pressed, ON KEYPRESSED fires
on each (CR 1701-1738, 2751-2773). The simulation has no keypad of its own: a host presses keys with press_key."""

from __future__ import annotations

from collections import deque

from motiontool.kernel.command_base import command
from motiontool.kernel.vm import Wait

NO_KEY = -1   # CR 1707: "–1 in case no character available"


def _keys(ctl) -> deque:
    # the keys belong to the controller, not to a program: a key pressed before the start is read by the program
    return vars(ctl).setdefault("lcp_keys", deque())


def press_key(ctl, code: int) -> None:
    """A key (or a combination: the sum of the codes, CR 1708-1710) pressed on the LCP."""
    _keys(ctl).append(code)
    ctl.interrupts.fire("KEYPRESSED")


class _KeyWait(Wait):
    def __init__(self, ctl, timeout_ms: int | None):
        self.keys = _keys(ctl)
        self.ctl = ctl
        self.end = None if timeout_ms is None else ctl.time_ms + timeout_ms

    def done(self) -> bool:
        if self.keys:
            self.value = self.keys.popleft()
            return True
        if self.end is not None and self.ctl.time_ms >= self.end:
            self.value = NO_KEY
            return True
        return False


@command("INKEY")
def inkey(ctl, vm, args):
    """CR 1703-1706: p = 0 wait for a key code, p > 0 wait at most p ms, p < 0 do not wait; "One key signal is read
    in per successful INKEY command"."""
    keys = _keys(ctl)
    if keys:
        return keys.popleft()
    if args[0] < 0:
        return NO_KEY
    return _KeyWait(ctl, args[0] if args[0] > 0 else None)
