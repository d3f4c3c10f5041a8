"""The window's Session without Qt (issue 27 item 5, decision I35): connect, select, release, lost, close, and the
events the Qt adapter shows. Runs in the environment without Qt too (`make test-headless`)."""

from __future__ import annotations

import threading

import pytest

from motiontool.comms.protocol import LinkError
from motiontool.session.controllers import ControllerRegistry, InterfaceConfig
from motiontool.session.session import Session, SessionEvent


@pytest.fixture
def registry():
    reg = ControllerRegistry(realtime_factor=1.0)
    yield reg
    reg.close()


def listen(session: Session) -> list[SessionEvent]:
    events: list[SessionEvent] = []
    session.listeners.append(events.append)
    return events


def test_select_connects_and_says_the_identity(registry):
    session = Session(registry)
    events = listen(session)
    assert session.select(2)
    assert session.connected and session.controller_id == 2 and session.interface_key == "sim"
    assert session.identity is not None and session.identity.product
    assert registry.owners[("sim", 2)] is session
    [event] = events
    assert (event.kind, event.controller_id, event.interface) == ("connected", 2, "sim")
    assert event.message == (f"Connected to controller 2 [Simulator] {session.identity.product}, "
                             f"{session.identity.firmware or '?'}")


def test_a_controller_that_does_not_exist_is_a_failed_event_and_nothing_changes(registry):
    session = Session(registry)
    assert session.select(1)
    events = listen(session)
    assert not session.select(9)
    assert [(e.kind, e.controller_id, e.message) for e in events] == [
        ("failed", 9, "Connection to controller 9 failed: no controller 9 on the simulated interface")]
    assert session.connected and session.controller_id == 1 and registry.owners[("sim", 1)] is session


def test_a_port_that_cannot_be_opened_fails_with_its_own_words(registry):
    session = Session(registry)
    events = listen(session)
    registry.set_default(InterfaceConfig(kind="fc", port="/nonexistent/motiontool-tty", first=1, last=1))
    assert not session.select(1)
    [event] = events
    assert event.kind == "failed" and event.message.startswith("Connection to controller 1 failed: ")
    assert "/nonexistent/motiontool-tty" in event.message
    assert not session.connected


def test_selecting_a_controller_another_session_holds_moves_it(registry):
    # DG 2546: "selecting a controller that is already connected to another APOSS Window will cause that
    # controller to be switched from the other APOSS Window to this APOSS Window."
    first, second = Session(registry), Session(registry)
    first_events = listen(first)
    assert first.select(1)
    link = first.link
    assert second.select(1)
    assert [(e.kind, e.message) for e in first_events[1:]] == [
        ("disconnected", "Controller 1 moved to another APOSS window")]
    assert not first.connected and second.link is link and link.alive   # the link stays open: it moved
    assert registry.owners[("sim", 1)] is second


def test_switching_controllers_leaves_the_first_for_others(registry):
    session = Session(registry)
    assert session.select(1) and session.select(3)
    assert ("sim", 1) not in registry.owners and registry.owners[("sim", 3)] is session
    assert dict(registry.open_links())[1].alive   # the controller left keeps running its program


def test_a_lost_session_stays_bound_and_reconnects_to_the_same_controller(registry):
    # DG 2066: "the window will remain "associated" with that controller. Pressing [Esc] (or executing any command
    # that needs to talk to the controller) will cause the APOSS Window to attempt to reconnect to the same
    # controller."
    registry.set_default(InterfaceConfig(kind="sim", first=1, last=4))
    session = Session(registry)
    assert session.select(3)
    events = listen(session)
    session.lost()
    assert not session.connected and session.controller_id == 3 and session.lost_reason == "no answer"
    assert [(e.kind, e.message) for e in events] == [
        ("lost", "Lost connection to controller 3 (Simulator)! Press Esc or Reconnect to connect again.")]
    assert session.connect_default()
    assert session.connected and session.controller_id == 3 and session.lost_reason == ""
    assert events[-1].kind == "connected"


def test_connect_default_does_nothing_while_connected(registry):
    session = Session(registry)
    assert session.connect_default() and session.controller_id == 1
    events = listen(session)
    assert session.connect_default()
    assert events == []


def test_the_requests_run_where_the_runner_puts_them_and_the_state_changes_in_the_callers_thread(registry):
    session = Session(registry)
    asked: list[str] = []
    threads: dict[str, threading.Thread] = {}

    def on_a_thread(doing, work):
        asked.append(doing)
        box: list = []

        def job():
            threads["work"] = threading.current_thread()
            box.append(work())
        worker = threading.Thread(target=job)
        worker.start()
        worker.join()
        return box[0]

    session.listeners.append(lambda event: threads.setdefault("event", threading.current_thread()))
    assert session.select(4, run=on_a_thread)
    assert asked == ["Connecting to controller 4 …"]
    assert threads["work"] is not threading.current_thread() and threads["event"] is threading.current_thread()


def test_a_failing_runner_is_a_failed_event(registry):
    session = Session(registry)
    events = listen(session)

    def refuses(_doing, _work):
        raise LinkError("timeout")
    assert not session.select(1, run=refuses)
    assert [(e.kind, e.message) for e in events] == [("failed", "Connection to controller 1 failed: timeout")]


def test_close_interface_disconnects_silently(registry):
    session = Session(registry)
    assert session.select(2)
    events = listen(session)
    registry.close(interface="sim")
    assert [(e.kind, e.message) for e in events] == [("disconnected", "")]
    assert not session.connected and session.controller_id == 2


def test_the_last_session_closing_closes_every_link(registry):
    first, second = Session(registry), Session(registry)
    assert first.select(1) and second.select(2)
    links = [link for _, link in registry.open_links()]
    first.close()
    assert all(link.alive for link in links) and registry.sessions == [second]
    second.close()
    assert registry.sessions == [] and registry.interfaces == {}
    assert not any(link.alive for link in links)


def test_a_session_closed_while_it_connects_attaches_nothing(registry):
    """The window closed while `run` waited for the controller (its closeEvent runs inside the wait): nothing is
    attached, no one owns the controller; the last session's registry closes the link opened after its close."""
    other, session = Session(registry), Session(registry)
    events = listen(session)

    def closing_first(_doing, work):
        session.close()
        return work()

    assert not session.select(1, run=closing_first)
    assert not session.connected and registry.owners == {} and events == []
    assert registry.link(1).alive            # the other session may take it
    other.close()
    last = Session(registry)

    def closing_first_last(_doing, work):
        last.close()
        return work()

    assert not last.select(1, run=closing_first_last)
    assert registry.interfaces == {} and not last.connected
