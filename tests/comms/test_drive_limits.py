"""The virtual drive against hostile clients (issue 24 item 5): every buffer and every decompression has a limit,
refused with a clear error to that client only, while other clients keep being served; and CiA 301 details of
the slcan line (item 6). The drive runs as its own process on loopback."""

from __future__ import annotations

import json
import socket
import time
import zlib

import pytest

from motiontool.comms import chunks
from motiontool.comms.canopen.slcan import parse_frame
from motiontool.comms.chunks import ACK, BUSY, DATA, ERROR, Frame, MasterChannel, SlaveChannel
from motiontool.comms.links import open_link
from motiontool.comms.protocol import LinkError
from motiontool.comms.wire import FLAG_ZLIB, HEADER, MAX_REQUEST_BYTES, REQUEST, VERSION, decode_response
from tests.comms.drive_process import drive_process

CANOPEN = "canopen:slcan:socket://127.0.0.1:0"


def peak_rss_mb(pid: int) -> float:
    with open(f"/proc/{pid}/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    raise AssertionError("no VmHWM")


def bomb(inflated: int) -> bytes:
    """A request message whose zlib body inflates to `inflated` bytes (zeros: 1 GiB compresses to ~1 MiB)."""
    packer = zlib.compressobj(9)
    block = bytes(1 << 20)
    body = b"".join(packer.compress(block) for _ in range(inflated >> 20)) + packer.flush()
    return HEADER.pack(VERSION, REQUEST, FLAG_ZLIB, 0, zlib.crc32(body)) + body


def message(body: dict) -> bytes:
    raw = json.dumps(body).encode()
    return HEADER.pack(VERSION, REQUEST, 0, 0, zlib.crc32(raw)) + raw


@pytest.mark.wire
def test_a_zlib_bomb_is_refused_to_its_sender_and_the_drive_stays_small():
    """Before, a 261 kB message drove the drive to 554 MB: the message layer inflated without a limit."""
    with drive_process("--node", "1") as drive:
        attacker, reader = open_link(drive.url + "#1"), open_link(drive.url + "#1")
        try:
            before = reader.call("read_parameter", key="32-60")
            answer = decode_response(attacker._exchange(bomb(1 << 30)))
            assert not answer.ok
            assert f"inflates to more than {MAX_REQUEST_BYTES} bytes" in answer.error
            assert reader.call("read_parameter", key="32-60") == before      # the other master is served
            assert attacker.status().program_state                     # and so is the attacker, afterwards
            assert peak_rss_mb(drive.proc.pid) <= 150
        finally:
            attacker.close()
            reader.close()


@pytest.mark.wire
def test_a_request_that_breaks_its_handler_is_refused_and_the_connection_goes_on():
    """`after: Infinity` (JSON as Python reads it) made int() raise OverflowError, which killed the connection's
    thread with a traceback on the drive's stderr."""
    with drive_process("--node", "1") as drive:
        link = open_link(drive.url + "#1")
        try:
            answer = decode_response(link._exchange(message({"s": 7, "id": 1, "op": "events",
                                                             "args": {"after": float("inf")}})))
            assert not answer.ok and "events: request refused (OverflowError" in answer.error
            assert link.status().program_state == "idle"
        finally:
            link.close()
        _, _, err = drive.stop()
    assert "Traceback" not in err


@pytest.mark.wire
def test_one_long_advance_is_refused_and_a_long_one_leaves_other_masters_served():
    """One `advance` of 10^9 ms blocked the drive for every other client (0 of 8 reads answered in 15 s)."""
    import threading

    from tests.comms.drive_process import PausableProxy

    with drive_process("--node", "1", "--clock", "virtual") as drive:
        proxy = PausableProxy(int(drive.url.rsplit(":", 1)[1]))   # the reader on a connection of its own
        stepper, reader = open_link(drive.url + "#1"), open_link(f"fc:socket://127.0.0.1:{proxy.port}#1")
        try:
            with pytest.raises(LinkError, match=r"advance: 1000000000 ms; one request advances 0\.\.60000 ms"):
                stepper.advance(10**9)
            worker = threading.Thread(target=stepper.advance, args=(60_000,))
            worker.start()
            answered = []
            while worker.is_alive() and len(answered) < 8:
                started = time.monotonic()
                reader.status()
                answered.append(time.monotonic() - started)
            worker.join()
            assert len(answered) >= 2, "the advance ended before a read was tried: make it longer"
            assert max(answered) < 2.0
        finally:
            stepper.close()
            reader.close()
            proxy.close()


@pytest.mark.wire
def test_two_links_of_one_process_to_one_node_take_turns_on_its_channel():
    """Two links to one node share the bus connection, and the node has one chunk channel on it: a status asked
    while the other link's long `advance` was answered BUSY took that answer ("answer to request N where M was
    expected")."""
    import threading

    with drive_process("--node", "1", "--clock", "virtual") as drive:
        stepper, reader = open_link(drive.url + "#1"), open_link(drive.url + "#1")
        failures = []

        def step():
            try:
                stepper.advance(60_000)
            except LinkError as exc:
                failures.append(exc)
        try:
            worker = threading.Thread(target=step)
            worker.start()
            while worker.is_alive():
                reader.status()
            worker.join()
            assert not failures
        finally:
            stepper.close()
            reader.close()


@pytest.mark.wire
def test_connections_beyond_the_limit_are_closed_and_said_once():
    """Every connection had a thread of its own and no limit: at ~1 700 new clients could not connect."""
    from motiontool.controller.fc.server import MAX_CONNECTIONS

    with drive_process("--node", "1") as drive:
        host, port = drive.url.removeprefix("fc:socket://").rsplit(":", 1)
        held = [socket.create_connection((host, int(port))) for _ in range(MAX_CONNECTIONS)]
        try:
            time.sleep(0.5)
            extra = [socket.create_connection((host, int(port))) for _ in range(5)]
            for sock in extra:
                sock.settimeout(5)
                assert sock.recv(10) == b""                  # closed by the drive
                sock.close()
        finally:
            for sock in held:
                sock.close()
        time.sleep(0.5)
        link = open_link(drive.url + "#1")                  # room again once they left
        try:
            assert link.status().program_state == "idle"
        finally:
            link.close()
        _, _, err = drive.stop()
    assert err.count("a connection was refused") == 1
    assert f"{MAX_CONNECTIONS} masters are connected already" in err


@pytest.mark.wire
def test_an_slcan_line_without_cr_is_not_kept_and_others_are_served():
    """An slcan line without CR grew without end (+106 MB)."""
    with drive_process("--node", "1", listen=CANOPEN) as drive:
        host, port = drive.url.removeprefix("canopen:slcan:socket://").rsplit(":", 1)
        link = open_link(drive.url + "#1")
        try:
            with socket.create_connection((host, int(port))) as flood:
                chunk = b"x" * 65536
                for _ in range(400):                          # 25 MiB without a CR
                    flood.sendall(chunk)
                assert link.status().program_state == "idle"
                flood.settimeout(5)
                assert b"\a" in flood.recv(4096)              # refused, as a bad command is
            assert peak_rss_mb(drive.proc.pid) <= 150
        finally:
            link.close()


@pytest.mark.parametrize("line", ["t-121AA", "t12 1AA", "t1211AAZZ", "t1211AA0", "t12", "t1239AABBCCDD",
                                  "T1FFFFFFF", "r12", "t1211A", "x1211AA", "t+121AA", "t1211aa12345"])
def test_the_slcan_parser_refuses_signs_spaces_and_trailing_junk(line):
    """python-can and Lawicel adapters send hex digits only: `t-121AA` was taken as id -0x12."""
    assert parse_frame(line) is None


@pytest.mark.parametrize("line, can_id, data, extended", [("t1211AA", 0x121, b"\xaa", False),
                                                          ("t1211AA1A2B", 0x121, b"\xaa", False),
                                                          ("T1FFFFFFF0", 0x1FFFFFFF, b"", True),
                                                          ("t7FF0", 0x7FF, b"", False)])
def test_the_slcan_parser_reads_frames_with_and_without_a_time_stamp(line, can_id, data, extended):
    msg = parse_frame(line)
    assert msg is not None and (msg.arbitration_id, bytes(msg.data), msg.is_extended_id) == (can_id, data, extended)


def test_data_chunks_without_last_are_refused_at_the_message_limit(monkeypatch):
    """DATA chunks without LAST were collected without end."""
    monkeypatch.setattr(chunks, "MAX_MESSAGE", 1000)
    slave = SlaveChannel(lambda message: message, 100)
    replies = [slave.on_frame(Frame(n, DATA, n == 0, False, n, bytes(100))) for n in range(15)]
    assert [r.op for r in replies[:10]] == [ACK] * 10
    assert replies[10].op == ERROR and replies[10].payload == b"message longer than 1000 bytes"
    assert slave._incoming is None                            # nothing kept after the refusal


def test_a_slave_that_answers_busy_forever_fails_the_exchange():
    """`run --link` to a drive that answered BUSY forever never returned."""
    master = MasterChannel(lambda frame: Frame(frame.seq, BUSY), 100, max_busy_s=0.3)
    started = time.monotonic()
    with pytest.raises(LinkError, match="has answered BUSY for 0.3 s"):
        master.exchange(b"request")
    assert time.monotonic() - started < 2.0


@pytest.mark.wire
def test_a_download_bigger_than_the_program_memory_is_refused_and_the_drive_stays_small():
    """A 1.9 kB download made the drive hold a program of gigabytes: the image's body may inflate to a file's limit
    (96 MiB); a controller's program memory is finite (DG 2639 "depending on available memory", DG 2669)."""
    import base64

    from motiontool.aposs.driver import compile_source
    from motiontool.controller.service import PROGRAM_MEMORY_BYTES

    img = compile_source('PRINT "x"\n').image.to_bytes()
    raw = json.loads(zlib.decompress(img[6:]))
    raw["code"] = "CODE"
    code = "[" + "44,0," * (8 << 20) + "50,0]"               # 40 MiB of JSON, some 100 kB compressed
    hostile = img[:6] + zlib.compress(json.dumps(raw).replace('"CODE"', code).encode())
    with drive_process("--node", "1") as drive:
        link = open_link(drive.url + "#1")
        try:
            with pytest.raises(LinkError, match=f"inflates to more than {PROGRAM_MEMORY_BYTES} bytes"):
                link.call("download", image=base64.b64encode(hostile).decode("ascii"))
            link.download(img)                                     # a real program still goes in
            assert peak_rss_mb(drive.proc.pid) <= 150
        finally:
            link.close()
