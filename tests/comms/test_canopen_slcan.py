"""The slcan (Lawicel ASCII) TCP server of the virtual drive (controller/canopen/slcan_server.py) and the link's
reader of it (comms/canopen/slcan.py), against a raw socket, python-can's `virtual` bus on the server's side and
python-can's own slcan interface."""

from __future__ import annotations

import itertools
import socket
import sys
import time

import can
import pytest

from motiontool.comms.canopen import slcan
from motiontool.controller.canopen import slcan_server

pytestmark = pytest.mark.wire

_names = itertools.count(1)


@pytest.fixture
def server():
    server = slcan_server.SlcanServer(f"test-slcan-{next(_names)}")
    server.peer = can.Bus(interface="virtual", channel=server.channel)
    yield server
    server.peer.shutdown()
    server.close()


class Raw:
    """A client on a plain socket: write Lawicel commands, read the server's lines."""

    def __init__(self, server):
        self.sock = socket.create_connection((server.host, server.port), timeout=5)
        self.buffer = b""

    def ask(self, text: str) -> bytes:
        self.sock.sendall(text.encode() + b"\r")
        return self.line()

    def line(self) -> bytes:
        while b"\r" not in self.buffer and b"\a" not in self.buffer:
            self.buffer += self.sock.recv(4096)
        end = min(i for i in (self.buffer.find(b"\r"), self.buffer.find(b"\a")) if i >= 0) + 1
        line, self.buffer = self.buffer[:end], self.buffer[end:]
        return line


def test_lawicel_commands(server):
    """The adapter's commands (Lawicel/CANUSB): version, serial number, status flags, bit rate, open, close; an
    unknown command or a frame on a closed channel is answered with BEL."""
    client = Raw(server)
    assert client.ask("V") == b"V1013\r"
    assert client.ask("N").startswith(b"N") and client.ask("F") == b"F00\r"
    assert client.ask("S6") == b"\r" and client.ask("s031C") == b"\r"
    assert client.ask("t1230") == b"\a"                       # not open yet
    assert client.ask("O") == b"\r"
    assert client.ask("t12320102") == b"z\r"
    msg = server.peer.recv(2)
    assert (msg.arbitration_id, bytes(msg.data), msg.is_extended_id) == (0x123, b"\x01\x02", False)
    assert client.ask("T1ABCDEF01FF") == b"Z\r"
    msg = server.peer.recv(2)
    assert (msg.arbitration_id, bytes(msg.data), msg.is_extended_id) == (0x1ABCDEF0, b"\xff", True)
    assert client.ask("r1004") == b"z\r"
    msg = server.peer.recv(2)
    assert msg.is_remote_frame and msg.dlc == 4 and msg.arbitration_id == 0x100
    for bad in ("Q", "t12", "t8001122", "t1239", "t1232AB"):
        assert client.ask(bad) == b"\a", bad
    assert client.ask("C") == b"\r"


def test_frames_from_the_bus_reach_every_open_client_and_a_silent_client_does_not_stall_the_others(server):
    first, second, silent = Raw(server), Raw(server), Raw(server)
    for client in (first, second, silent):
        assert client.ask("O") == b"\r"
    assert first.ask("Z1") == b"\r"                         # time stamps for the first client
    server.peer.send(can.Message(arbitration_id=0x7E5, data=b"\xaa" * 8, is_extended_id=False))
    assert second.line() == b"t7E58AAAAAAAAAAAAAAAA\r"
    stamped = first.line()
    assert stamped.startswith(b"t7E58AAAAAAAAAAAAAAAA") and len(stamped) == len(b"t7E58") + 16 + 4 + 1
    assert first.ask("t0010") == b"z\r" and second.line() == b"t0010\r"   # client to client
    for k in range(60_000):                                 # the silent client's queue overruns …
        server.peer.send(can.Message(arbitration_id=0x181, data=k.to_bytes(4, "little"), is_extended_id=False))
    received = 0
    deadline = time.monotonic() + 60
    while received < 60_000 and time.monotonic() < deadline:  # … the others get everything, in order
        assert second.line() == f"t1814{(received).to_bytes(4, 'little').hex().upper()}\r".encode()
        received += 1
    assert received == 60_000


def test_a_client_that_does_not_read_loses_frames_counted_instead_of_blocking(server, monkeypatch):
    """An adapter's receive buffer overruns; the server must not wait for one slow master."""
    monkeypatch.setattr(slcan_server, "MAX_QUEUED", 10_000)
    near, far = socket.socketpair()
    near.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 4096)
    client = slcan_server._Client(server, near)
    try:
        began = time.monotonic()
        for _ in range(20_000):
            client.write(b"t1814000000000\r")                 # nobody reads `far`
        assert time.monotonic() - began < 5 and client.overruns > 0
    finally:
        client.stop()
        near.close()
        far.close()


def test_the_links_reader_and_python_cans_slcan_both_read_the_server(server):
    """Decision N13: the link's SlcanSocketBus reads the same protocol as python-can's slcan interface, faster."""
    fast = slcan.SlcanSocketBus(server.url)
    stock = can.Bus(interface="slcan", channel=server.url, sleep_after_open=0)
    try:
        time.sleep(0.2)
        fast.send(can.Message(arbitration_id=0x601, data=bytes(range(8)), is_extended_id=False))
        assert bytes(stock.recv(2).data) == bytes(range(8)) and server.peer.recv(2).arbitration_id == 0x601
        for k in range(2000):
            server.peer.send(can.Message(arbitration_id=0x182, data=k.to_bytes(2, "little"), is_extended_id=False))
        values = [int.from_bytes(fast.recv(5).data, "little") for _ in range(2000)]
        assert values == list(range(2000))
        assert fast.recv(0.05) is None
    finally:
        fast.shutdown()
        stock.shutdown()


def test_close_ends_every_thread_of_the_server_even_with_a_client_connected():
    """A drive ends on SIGTERM by closing its listeners: the thread waiting in accept() must end too. On Linux
    closing a listening socket does not wake accept(), so it stayed blocked and every close waited out its 2 s join
    (a drive process 'slow to end on SIGTERM', issue 28 item 3)."""
    server = slcan_server.SlcanServer(f"test-slcan-{next(_names)}")
    client = socket.create_connection((server.host, server.port))
    accepting = server._threads[0]
    deadline = time.monotonic() + 30
    while not (server.clients and in_accept(accepting)) and time.monotonic() < deadline:  # back in accept()
        time.sleep(0.01)
    server.close()
    assert not [thread.name for thread in server._threads if thread.is_alive()]
    client.close()


def in_accept(thread) -> bool:
    frame = sys._current_frames().get(thread.ident)
    return frame is not None and frame.f_code.co_name == "accept"
