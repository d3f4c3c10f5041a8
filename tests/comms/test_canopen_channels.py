"""Two masters on one CANopen node (issue 24 item 4): the node's second SDO server (0x1201, DG 7317-7349) lets a
second master work beside the first (`…#NODE,sdo=2`); two masters on one channel are told so in words, never with a
raw SDO abort (decision N52). Against the drive process over loopback slcan."""

from __future__ import annotations

import contextlib
import subprocess
import sys
import threading
import time

import can
import pytest

from motiontool.comms.links import open_link
from motiontool.comms.protocol import LinkError
from tests.comms.drive_process import drive_process

pytestmark = pytest.mark.wire

LISTEN = "canopen:slcan:socket://127.0.0.1:0"
CALLS = 20


def _upload_1000(bus: can.BusABC, rx: int, tx: int) -> can.Message | None:
    """An SDO upload of 0x1000 sent on `rx`; the answer on `tx` within 1 s, else None."""
    bus.send(can.Message(arbitration_id=rx, data=bytes([0x40, 0x00, 0x10, 0, 0, 0, 0, 0]), is_extended_id=False))
    end = time.monotonic() + 1.0
    while time.monotonic() < end:
        msg = bus.recv(0.2)
        if msg is not None and msg.arbitration_id == tx:
            return msg
    return None


def test_the_second_sdo_server_answers_once_0x1201_is_valid():
    """DG 7321-7335: "SDO2-Tx = 0x681 - 0x6FF SDO2-Rx = 0x101 - 0x1FF … To enable the use of SDO2, you must first
    write the above addresses to the Objects ServerSdo2Parameters - Index 0x1201 Subindex 0x01 … and 0x02 … If you
    read these parameters, then you will get the above mentioned CobIds with the highest bit set." Before the write
    node 2 is silent on 0x102; after it answers there, on 0x682."""
    with drive_process("--node", "2", listen=LISTEN) as drive:
        bus = can.Bus(interface="slcan", channel=drive.url.removeprefix("canopen:slcan:"), sleep_after_open=0)
        try:
            assert _upload_1000(bus, 0x102, 0x682) is None
            for sub, cob in ((1, 0x102), (2, 0x682)):
                bus.send(can.Message(arbitration_id=0x602, is_extended_id=False,
                                     data=bytes([0x23, 0x01, 0x12, sub]) + cob.to_bytes(4, "little")))
            answer = _upload_1000(bus, 0x102, 0x682)
            assert answer is not None and answer.data[0] == 0x43
        finally:
            bus.shutdown()


def _params_calls(link, key: str, base: int, failures: list, barrier: threading.Barrier) -> None:
    """`params --set KEY=V --get KEY` and a link message, CALLS times; the value read must be the one written."""
    barrier.wait()
    for i in range(CALLS):
        try:
            link.write_parameter(key, base + i)
            value = link.read_parameter(key)
            if value != base + i:
                failures.append(f"{key} read {value} after writing {base + i}: an answer for the other master")
            link.call("status")
        except LinkError as exc:
            failures.append(str(exc))


def _two_masters(url: str, second: str, unread: list | None = None) -> tuple[list[str], list[str]]:
    """Two links, 20 interleaved params calls each; `unread` gets what the second link's SDO clients left queued."""
    first_link, second_link = open_link(url + "#1"), open_link(url + "#1" + second)
    failures: tuple[list[str], list[str]] = ([], [])
    barrier = threading.Barrier(2)
    try:
        threads = [threading.Thread(target=_params_calls, args=(link, key, base, out, barrier))
                   for link, key, base, out in ((first_link, "19-00", 1000, failures[0]),
                                                (second_link, "19-01", 2000, failures[1]))]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join(120)
        if unread is not None:
            unread += [client.responses.qsize() for client in second_link.remote.sdo_channels]
    finally:
        first_link.close()
        second_link.close()
    return failures


def test_a_master_on_sdo_channel_2_works_beside_one_on_channel_1(capfd):
    """Issue 24 item 4: "IDE + CLI on one node: 3 of 8 `params` calls fail with 'Unexpected response 0x10'" — with
    the second on `,sdo=2` every one of 20 interleaved calls of each master succeeds, and each reads its own value
    (the second link enables SDO 2 through channel 1 when it opens)."""
    with drive_process("--node", "1", listen=LISTEN) as drive:
        unread: list[int] = []
        failures = _two_masters(drive.url, ",sdo=2", unread)
    assert failures == ([], [])
    assert unread == [0, 0], "the first master's answers pile up in the second link's channel-1 client"
    assert "Transfer aborted" not in capfd.readouterr().err


def test_two_masters_on_one_sdo_channel_are_told_so_in_words(capfd):
    """Two masters on channel 1 take each other's answers: every call either succeeds or fails with the words
    naming the channel and the way out, never an SDO abort code or python-canopen's 'Unexpected response'."""
    with drive_process("--node", "1", listen=LISTEN) as drive:
        failures = _two_masters(drive.url, "")
    for text in failures[0] + failures[1]:
        assert text == "another master uses SDO channel 1 of CANopen node 1; use ,sdo=2 on one of them", text
    assert "Transfer aborted" not in capfd.readouterr().err


def test_params_takes_the_sdo_option_on_the_command_line():
    """`motiontool params --link canopen:…#1,sdo=2 --get KPROP` reads through the second channel; `sdo=3` is refused
    in one line naming the option."""
    with drive_process("--node", "1", listen=LISTEN) as drive:
        good = subprocess.run([sys.executable, "-m", "motiontool", "params", "--link", drive.url + "#1,sdo=2",
                               "--get", "KPROP"], capture_output=True, text=True, timeout=120)
        bad = subprocess.run([sys.executable, "-m", "motiontool", "params", "--link", drive.url + "#1,sdo=3",
                              "--get", "KPROP"], capture_output=True, text=True, timeout=120)
    assert (good.returncode, good.stdout, good.stderr) == (0, "32-60 KPROP 30\n", "")
    assert bad.returncode == 1 and len(bad.stderr.splitlines()) == 1 and "option sdo" in bad.stderr, bad.stderr


def test_a_link_on_sdo_channel_2_comes_back_when_its_drive_restarts():
    """A restarted node has SDO 2 NOT_VALID again (DG 7329-7331): the link on `,sdo=2` enables it again when the
    node is back, and reads through it."""
    import socket

    from tests.comms.drive_process import DriveProcess

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    listen = f"canopen:slcan:socket://127.0.0.1:{port}"
    first = DriveProcess("--node", "1", listen=listen)
    link = open_link(first.url + "#1,sdo=2,timeout=0.3")
    link.subscribe(lambda event: None)      # a watching master (the IDE): the link guards the node
    second = None
    try:
        assert link.read_parameter("KPROP") == 30
        first.proc.kill()
        first.proc.wait(10)
        second = DriveProcess("--node", "1", listen=listen)
        assert second.url
        deadline = time.monotonic() + 15
        while True:      # back: it reads, and it has said so (the set-up after a restart reads too, meanwhile)
            with contextlib.suppress(LinkError):
                if link.read_parameter("KPROP") == 30 and link.alive:
                    break
            assert time.monotonic() < deadline, "the link did not come back on SDO 2 within 15 s"
            time.sleep(0.2)
    finally:
        link.close()
        if second is not None:
            second.stop()


def test_eight_params_calls_on_sdo_2_beside_a_polling_ide():
    """The issue's case: an IDE polls node 1 on channel 1 (a status every 50 ms) while `params` runs 8 times
    (open, read 8 parameters, close). Each `params` on `,sdo=2` succeeds, the first enabling SDO 2 through channel
    1 in a pause of the IDE's; the IDE sees at most the collision said in words."""
    from motiontool.paramdb import database

    keys = [p.number for p in database()][:8]
    with drive_process("--node", "1", listen=LISTEN) as drive:
        ide = open_link(drive.url + "#1")
        stop, ide_failures, polls = threading.Event(), [], [0]

        def poll():
            while not stop.wait(0.05):
                try:
                    ide.status()
                    polls[0] += 1
                except LinkError as exc:
                    ide_failures.append(str(exc))
        poller = threading.Thread(target=poll)
        poller.start()
        failures = []
        try:
            for _ in range(8):
                try:
                    link = open_link(drive.url + "#1,sdo=2")
                    try:
                        for key in keys:
                            link.read_parameter(key)
                    finally:
                        link.close()
                except LinkError as exc:
                    failures.append(str(exc))
        finally:
            stop.set()
            poller.join(30)
            ide.close()
    assert failures == []
    assert polls[0] > 0
    for text in ide_failures:
        assert text == "another master uses SDO channel 1 of CANopen node 1; use ,sdo=2 on one of them", text
