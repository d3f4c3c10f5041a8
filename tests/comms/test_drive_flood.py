"""A client flooding the drive with garbage (issue 24 "Done when": a well-behaved master keeps >= 80 % of its round
trips; benchmarks/link_fc.py and link_canopen.py measure that). A paced FC listener reads a connection no faster than
its line would carry it, the slcan server a client's lines no faster than a 1 Mbit/s CAN bus carries frames, so the
flood is held back by TCP instead of taking the drive's cores."""

from __future__ import annotations

import os
import socket
import threading
import time

import pytest

from motiontool.comms.links import open_link
from tests.comms.drive_process import drive_process

pytestmark = pytest.mark.wire


def _cpu_seconds(pid: int) -> float:
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


class _Flood:
    """A second connection sending `payload` as fast as it can (after `first`); `sent` bytes."""

    def __init__(self, host: str, port: int, payload: bytes, first: bytes = b""):
        self.sock = socket.create_connection((host, port))
        self.sock.sendall(first)
        self.payload, self.sent = payload, 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._send, daemon=True)

    def _send(self) -> None:
        while not self._stop.is_set():
            try:
                self.sent += self.sock.send(self.payload)
            except OSError:
                return

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self.sock.close()
        self._thread.join(5)


def test_a_garbage_flood_on_a_paced_fc_listener_is_held_to_the_line_rate():
    """Before, the drive read 75 MB/s of garbage from one connection and spent a core parsing it (a master beside
    it kept 62-78 % of its round trips). A 115 200-baud line carries 10.5 kB/s: in 2 s the drive may take that
    plus what the sockets buffer, and its CPU stays far below a core while the master is served."""
    with drive_process("--node", "1", listen="fc:socket://127.0.0.1:0,baud=115200") as drive:
        host, port = drive.url.removeprefix("fc:socket://").split(",")[0].rsplit(":", 1)
        link = open_link(drive.url + "#1")
        flood = socket.create_connection((host, int(port)))
        stop, sent = threading.Event(), [0]

        def send():
            garbage = bytes(range(256)) * 256
            while not stop.is_set():
                try:
                    sent[0] += flood.send(garbage)
                except OSError:
                    return
        sender = threading.Thread(target=send, daemon=True)
        try:
            link.read_parameter("KPROP")
            cpu = _cpu_seconds(drive.proc.pid)
            sender.start()
            started = time.monotonic()
            reads = 0
            while time.monotonic() - started < 2.0:
                assert link.read_parameter("KPROP") == 30
                reads += 1
            cpu = _cpu_seconds(drive.proc.pid) - cpu
            assert reads >= 20
            assert sent[0] < 32 << 20, f"the drive took {sent[0] >> 20} MB in 2 s"
            assert cpu < 1.0, f"the drive spent {cpu:.2f} s of CPU in 2 s"
        finally:
            stop.set()
            flood.close()
            sender.join(5)
            link.close()


def test_a_flood_of_slcan_lines_is_held_to_the_bus_rate():
    """Before, the slcan server took 325 MB/s of garbage lines (a CR every 256 bytes) or 150 000 frames/s from one
    client and forwarded the frames to every other: a master beside it kept 26 % (garbage) and 6 % (frames) of its
    SDO round trips. Now a client's lines are read at most as a 1 Mbit/s bus carries 8-byte frames (7 500/s): a
    listening client sees no more of a flood's frames than that, and a garbage flood gets little further than the
    sockets' buffers."""
    from motiontool.comms.canopen.slcan import SlcanSocketBus

    with drive_process("--node", "1", listen="canopen:slcan:socket://127.0.0.1:0") as drive:
        channel = drive.url.removeprefix("canopen:slcan:")
        host, port = channel.removeprefix("socket://").rsplit(":", 1)
        link = open_link(drive.url + "#1")
        listener = SlcanSocketBus(channel)
        try:
            for payload, limit in ((bytes(range(256)) * 256, 32 << 20), (b"t7E580011223344556677\r" * 3000, None)):
                with _Flood(host, int(port), payload, first=b"O\r") as flood:
                    started, reads, seen = time.monotonic(), 0, 0
                    while time.monotonic() - started < 2.0:
                        assert link.read_parameter("KPROP") == 30
                        reads += 1
                        while (msg := listener.recv(0)) is not None:
                            seen += msg.arbitration_id == 0x7E5
                    taken = flood.sent
                assert reads >= 20
                if limit:
                    assert taken < limit, f"the drive took {taken >> 20} MB of garbage in 2 s"
                else:       # 2 s of the bus, its 0.2 s of slack and one read of 64 kB
                    assert seen < 7_500 * 2.2 + 65536 // 22, f"{seen} frames of the flood in 2 s"
        finally:
            listener.shutdown()
            link.close()
