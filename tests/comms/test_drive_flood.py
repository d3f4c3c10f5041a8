"""A client flooding the drive with garbage (issue 24 "Done when": a well-behaved master keeps >= 80 % of its round
trips; benchmarks/link_fc.py measures that). A paced FC listener reads a connection no faster than its line would
carry it, so the flood is held back by TCP instead of taking the drive's cores."""

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
