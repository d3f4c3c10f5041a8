"""The one pacing loop (controller/pacing.py, issue 27 item 4) under its two hosts: the embedded link and the virtual
drive. Rounds are driven with a stand-in wall clock where the numbers matter; real threads are waited on by
condition, never by a fixed sleep (the machine is loaded)."""

import sys
import threading
import time

from motiontool.controller.drive.simulator import VirtualDrive
from motiontool.controller.embedded import EmbeddedLink
from motiontool.controller.pacing import BURST, SWITCH_INTERVAL_S, PacedClock, hand_over_quickly


class Wall:
    def __init__(self):
        self.now = 64.0

    def __call__(self):
        return self.now


def wait_until(condition, timeout=10.0):
    deadline = time.monotonic() + timeout
    while not condition():
        assert time.monotonic() < deadline, "condition not met in time"
        time.sleep(0.005)


def test_a_clock_behind_catches_up_in_bursts_and_idles_when_on_time():
    wall, bursts = Wall(), []
    clock = PacedClock("t", 2.0, bursts.append, clock=wall)
    clock._start = wall.now
    wall.now += 0.5                          # 1000 ticks due at twice real time
    rounds = [clock.round() for _ in range(6)]
    assert rounds == [BURST] * 5 + [0] and bursts == rounds and clock.ticks == 1000
    assert clock.stalls == 0 and clock.dropped == 0
    wall.now += 0.00390625                   # 7.8 ticks due (a binary fraction: no rounding in the test)
    assert clock.round() == 7


def test_max_lag_drops_what_is_far_behind_and_reports_the_stall():
    """The virtual drive's policy (10 bursts): a suspended process does not race to catch up afterwards."""
    wall, stalls, ran = Wall(), [], []
    clock = PacedClock("t", 1.0, ran.append, max_lag=10 * BURST, on_stall=stalls.append, clock=wall)
    clock._start = wall.now
    wall.now += 10.0                         # 10 000 ticks due
    assert clock.round() == BURST
    assert stalls == [10_000 - BURST] and clock.stalls == 1 and clock.dropped == 9_800 and clock.ticks == 10_000
    assert clock.round() == 0 and sum(ran) == BURST
    wall.now += 2 * BURST / 1000             # behind, but within the lag: caught up, nothing dropped
    assert [clock.round(), clock.round()] == [BURST, BURST] and clock.stalls == 1


def test_the_thread_runs_under_its_name_and_stops_cleanly():
    ticks = []
    clock = PacedClock("pacing-test", 5.0, ticks.append)
    clock.start()
    try:
        wait_until(lambda: sum(ticks) >= 100)
        assert clock.running and clock._thread.name == "pacing-test" and clock._thread.daemon
    finally:
        clock.stop()
    assert not clock.running and not clock._thread.is_alive()   # stop() waited for the thread's end


def test_the_switch_interval_is_set_once_per_process_by_the_first_clock():
    """Why: a paced host holds the GIL for bursts of ticks; a request from another thread would wait Python's
    default 5 ms switch interval (pacing.py). Set once, not by each host's constructor."""
    hand_over_quickly()
    assert sys.getswitchinterval() <= SWITCH_INTERVAL_S + 1e-9
    before = sys.getswitchinterval()
    try:
        sys.setswitchinterval(0.002)          # the process chose otherwise afterwards: a new host leaves it
        link = EmbeddedLink(realtime_factor=1.0)
        drive = VirtualDrive([1], clock="realtime")
        drive.start()
        link.close()
        drive.stop()
        assert abs(sys.getswitchinterval() - 0.002) < 1e-9
    finally:
        sys.setswitchinterval(before)


def test_both_hosts_report_a_fault_in_a_tick_and_keep_their_clock_running():
    link = EmbeddedLink(realtime_factor=5.0)
    events = []
    link.subscribe(lambda e: events.append(e.text) if e.kind == "message" else None)
    service_tick = link.service.tick
    failed = threading.Event()

    def tick_once_failing():
        if not failed.is_set():
            failed.set()
            raise RuntimeError("boom")
        service_tick()
    link.service.tick = tick_once_failing
    try:
        wait_until(lambda: events)
        assert events == ["internal simulator fault: RuntimeError: boom"]
        t0 = link.status().time_ms
        wait_until(lambda: link.status().time_ms > t0 + 50)
        assert link.alive
    finally:
        link.close()
    assert not link.alive

    drive = VirtualDrive([1, 2], clock="realtime", speed=5.0)
    simulation_tick = drive.simulation.tick
    failed.clear()

    def simulation_once_failing():
        if not failed.is_set():
            failed.set()
            raise RuntimeError("bang")
        simulation_tick()
    drive.simulation.tick = simulation_once_failing
    drive.start()
    try:
        wait_until(lambda: all(node.events.seq for node in drive.nodes.values()))
        t0 = drive.simulation.time_ms
        wait_until(lambda: drive.simulation.time_ms > t0 + 50)
    finally:
        drive.stop()
    texts = [event.text for node in drive.nodes.values() for _, event in node.events._events]
    assert texts == ["internal simulator fault: RuntimeError: bang"] * 2
