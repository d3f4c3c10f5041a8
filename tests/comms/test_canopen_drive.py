"""End to end over CANopen: `motiontool drive --listen canopen:slcan:socket://127.0.0.1:0` as its own process and
the link `canopen:slcan:socket://127.0.0.1:PORT#1` (issue 15 "Done when")."""

from __future__ import annotations

import functools
import os
import signal
import time

import can
import pytest

from motiontool.comms.links import open_link
from motiontool.comms.protocol import LinkError
from motiontool.headless import RunOptions
from tests.comms import test_drive_process as wire_tests
from tests.comms.drive_process import DrivePool, drive_process
from tests.comms.test_drive_process import run_both
from tests.test_samples import SAMPLES, parse_header

pytestmark = pytest.mark.wire

LISTEN = "canopen:slcan:socket://127.0.0.1:0"


@pytest.fixture(scope="module")
def pool():
    pool = DrivePool("--clock", "virtual", listen=LISTEN)
    yield pool
    pool.close()


@pytest.mark.parametrize("path", SAMPLES, ids=[p.stem for p in SAMPLES])
def test_sample_prints_over_canopen_exactly_what_the_embedded_run_prints(path, pool):
    """Issue 15: "`motiontool run FILE.m --link canopen:slcan:socket://127.0.0.1:PORT#1` prints what the embedded
    run prints for the samples"."""
    header = parse_header(path)
    drive = pool.take()
    try:
        options = RunOptions(seconds=header.seconds, settings=[f"{n}={v}" for n, v in header.settings],
                             inputs=[f"{n}={v}@{t}" for n, v, t in header.inputs])
        embedded, wire = run_both(path, options, drive.url + "#1")
        assert wire == embedded
        assert embedded[1], "the sample prints something"
    finally:
        code, _, err = drive.stop()
        assert code == 0, err


@pytest.mark.parametrize("wire_test", [
    wire_tests.test_every_parameter_reads_and_writes_over_the_wire,
    wire_tests.test_download_start_break_continue_and_the_debugger_over_the_wire,
    wire_tests.test_array_editor_and_cam_download_over_the_wire,
    wire_tests.test_polling_and_testsetp_scopes_over_the_wire,
], ids=lambda t: t.__name__.removeprefix("test_"))
def test_the_wire_links_end_to_end_checks_pass_over_canopen(wire_test, monkeypatch, tmp_path):
    """Issue 15: "parameters, arrays, download/start/break, debugger … work over it" — the same end-to-end checks
    the FC link passes (tests/comms/test_drive_process.py), with the drive listening on CANopen."""
    monkeypatch.setattr(wire_tests, "drive_process", functools.partial(drive_process, listen=LISTEN))
    if "tmp_path" in wire_test.__code__.co_varnames[:wire_test.__code__.co_argcount]:
        wire_test(tmp_path)
    else:
        wire_test()


def test_two_controllers_behind_one_drive_exchange_telegrams_over_the_simulated_bus(tmp_path):
    """Issue 15 item 5: the CAN bus is shared by the nodes of the virtual drive too; `run --node` over the link prints
    what the embedded bus prints (the order of lines of the same millisecond may differ between nodes)."""
    from tests.kernel.test_can_telegrams import CANOUT_EXAMPLE, DEFCANIN_EXAMPLE

    a, b = tmp_path / "a.m", tmp_path / "b.m"
    a.write_text(CANOUT_EXAMPLE)
    b.write_text(DEFCANIN_EXAMPLE)
    with drive_process("--clock", "virtual", "--node", "1", "--node", "2", listen=LISTEN) as drive:
        embedded, wire = run_both(a, RunOptions(seconds=1, nodes=[f"2:{b}"]), drive.url)
    assert embedded[0] == wire[0] == 0 and embedded[2] == wire[2] == ""
    assert sorted(wire[1].splitlines()) == sorted(embedded[1].splitlines()) == ["1: tx1 = 1", "2: CANIN 0: 21 41 at 22"]


def wait_for(condition, seconds: float) -> bool:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if condition():
            return True
        time.sleep(0.01)
    return condition()


def test_a_stopped_drive_is_reported_within_the_heartbeat_time_and_the_link_is_back_after_sigcont():
    """Issue 15: "stopping the drive process (SIGSTOP) is reported within the heartbeat time and the link is back
    ≤ 2 s after SIGCONT"."""
    with drive_process(listen=LISTEN) as drive:
        link = open_link(drive.url + "#1,heartbeat=100,consumer=500")
        try:
            events = []
            link.subscribe(lambda e: events.append((time.monotonic(), e.text)) if e.kind == "connection" else None)
            assert link.read_parameter("KPROP") == 30
            assert wait_for(lambda: link._last_beat is not None, 5)
            stopped = time.monotonic()
            os.kill(drive.proc.pid, signal.SIGSTOP)
            try:
                assert wait_for(lambda: events, 3)
                lost_after = events[0][0] - stopped
                assert events[0][1].startswith("Lost connection") and lost_after <= 0.5 + 0.15
                with pytest.raises(LinkError):
                    link.read_parameter("KPROP")
            finally:
                resumed = time.monotonic()
                os.kill(drive.proc.pid, signal.SIGCONT)
            assert wait_for(lambda: len(events) >= 2, 5)
            assert "restored" in events[1][1] and events[1][0] - resumed <= 2.0
            assert link.alive and link.read_parameter("KPROP") == 30
        finally:
            link.close()


def test_any_python_can_client_reaches_the_drive_as_an_slcan_adapter():
    """Issue 15 item 4: "any python-can client connects with interface="slcan", channel="socket://127.0.0.1:PORT"
    exactly as to a USB-CAN adapter" — python-can's own slcan interface reads node 1's heartbeat and an SDO."""
    with drive_process("--node", "1", listen=LISTEN) as drive:
        channel = drive.url.removeprefix("canopen:slcan:")
        bus = can.Bus(interface="slcan", channel=channel, sleep_after_open=0)
        try:
            bus.send(can.Message(arbitration_id=0x601, data=bytes([0x40, 0x18, 0x10, 0x02, 0, 0, 0, 0]),
                                 is_extended_id=False))        # SDO upload 0x1018 sub 2: product code
            end = time.monotonic() + 5
            answer = None
            while time.monotonic() < end and answer is None:
                msg = bus.recv(0.5)
                if msg is not None and msg.arbitration_id == 0x581:
                    answer = msg
            assert answer is not None and answer.data[0] == 0x43 and int.from_bytes(answer.data[4:8], "little") == 305
        finally:
            bus.shutdown()


def test_free_run_of_four_txpdos_at_1_khz_over_the_slcan_drive_process():
    """Issue 15: "PDO Free Run work[s] over it" — four signals, one TxPDO each every millisecond (decision S30), from
    the drive process through its slcan server: every row of the controller's milliseconds arrives, stamped by the
    controller, none lost (the goal of benchmarks/link_canopen.py, here for 2 s of a moving axis)."""
    from motiontool.aposs.driver import compile_source

    with drive_process("--node", "1", listen=LISTEN) as drive:
        link = open_link(drive.url + "#1")
        try:
            link.download(compile_source("VEL 50\nACC 50\nDEC 50\nPOSA 100000\n", "m.m").image.to_bytes())
            link.start()
            packets = []
            link.subscribe(lambda e: packets.append(e.data) if e.kind == "samples" else None)
            link.call("stream", signals=["APOS", "CPOS", "4119", "AVEL"], interval_ms=1)
            assert wait_for(lambda: sum(len(p["time_ms"]) for p in packets) >= 2000, 30)
            link.call("stream", signals=[], interval_ms=1)
            times = [t for p in packets for t in p["time_ms"]]
            assert times == list(range(times[0], times[0] + len(times)))       # every ms, in order
            assert [row[2] for p in packets for row in p["values"]] == times    # sys_clock = the stamp
            cpos = [row[1] for p in packets for row in p["values"]]
            assert cpos[-1] > cpos[0] and cpos == sorted(cpos)                 # the axis moves forward
            assert packets[-1]["dropped"] == 0 and link.pdo_stream.rows_dropped == 0
        finally:
            link.close()
