"""An APOSS window closed while it connects (found by review): the connect waits for the controller off the GUI
thread (decision I34) and the window's closeEvent can run meanwhile (a timer, or the close the window system asked
for, is not held back like clicks and keys). The closed window's session must not attach the controller once the
answer comes: the controller is no one's, its link goes back to the registry, and the last window's registry closes
it (decision I35)."""

from __future__ import annotations

import threading

import pytest
from PySide6.QtCore import QTimer

from tests.ui.gui_thread_check import HOLD, checking


@pytest.fixture
def checked(window):
    yield from checking(window)


def closing_during(op: str, close) -> threading.Event:
    """Holds the next `op` request; once it is on the line, `close()` runs from a timer, then it goes through."""
    arrived, through = threading.Event(), threading.Event()
    HOLD[op] = (arrived, through)

    def look() -> None:
        if not arrived.is_set():
            QTimer.singleShot(20, look)
            return
        close()
        through.set()

    QTimer.singleShot(0, look)
    return through


def test_a_window_closed_while_it_connects_does_not_attach_the_controller(checked, qtbot):
    registry, session = checked.controllers, checked.connection.session
    through = closing_during("identify", checked.close)
    try:
        checked.actions_by_text["Break"].trigger()     # Esc: connect to the default controller (DG 2054-2062)
    finally:
        through.set()
    qtbot.waitUntil(lambda: not checked.isVisible(), timeout=20_000)
    assert not checked.bridge.connected and checked.bridge.link is None
    assert not session.connected
    assert registry.owners == {}
    assert session not in registry.sessions
    assert registry.interfaces == {}    # the last window closed: its registry closed the link opened meanwhile


def test_a_second_window_closed_while_it_connects_leaves_the_controller_to_the_others(checked, qtbot):
    """Another window shares the registry: the link opened for the closed one stays open, held by no one."""
    other = type(checked)(settings=checked.settings, realtime_factor=checked.realtime_factor,
                          controllers=checked.controllers)
    other.ask_to_save = False
    qtbot.addWidget(other)
    other.show()
    registry, session = other.controllers, other.connection.session
    through = closing_during("identify", other.close)
    try:
        other.actions_by_text["Break"].trigger()
    finally:
        through.set()
    qtbot.waitUntil(lambda: not other.isVisible(), timeout=20_000)
    assert not other.bridge.connected and not session.connected
    assert registry.owners == {}
    assert registry.sessions == [checked.connection.session]
    link = registry.interfaces[registry.default.key].links[1]
    assert link.alive
    checked.actions_by_text["Break"].trigger()          # the first window takes it
    qtbot.waitUntil(lambda: checked.bridge.connected, timeout=20_000)
    assert checked.bridge.link is link
