"""A block upload whose end the drive does not answer (it was stopped just then) is a missing answer, not a
crash (comms/canopen/block_upload.py): python-canopen 2.4 raised AttributeError there, and a `run --link` over
CANopen whose drive was stopped for seconds died instead of pausing (found by a clean-clone run of
tests/comms/test_live_links.py::test_a_drive_stopped_for_seconds_is_a_pause_of_the_run). CiA 301 §7.2.4.3.12:
a client that times out aborts the transfer with "SDO protocol timed out" (0x05040000)."""

from __future__ import annotations

import itertools
import struct
import threading
import time

import can
import canopen
import pytest
from canopen.sdo import SdoCommunicationError

from motiontool.comms.canopen.block_upload import ABORT_TIMED_OUT, block_upload
from motiontool.comms.canopen.objects import LINK_MESSAGE, eds_path

_channels = itertools.count(1)


class SilentAtTheEnd(threading.Thread):
    """An SDO server of node 1 that answers a block upload of three bytes but never its end."""

    def __init__(self, channel: str) -> None:
        super().__init__(daemon=True)
        self.bus = can.Bus(interface="virtual", channel=channel)
        self.stop = threading.Event()
        self.aborts: list[tuple[int, int]] = []     # (index, abort code) of the aborts received

    def send(self, data: bytes) -> None:
        self.bus.send(can.Message(arbitration_id=0x581, data=data.ljust(8, b"\0"), is_extended_id=False))

    def run(self) -> None:
        while not self.stop.is_set():
            msg = self.bus.recv(0.02)
            if msg is None or msg.arbitration_id != 0x601:
                continue
            data = bytes(msg.data)
            if data[0] & 0xE3 == 0xA0:                              # initiate block upload
                self.send(bytes([0xC2]) + data[1:4] + struct.pack("<L", 3))   # size given, no CRC
            elif data[0] == 0xA3:                                   # start: one segment, the last
                self.send(bytes([0x80 | 1]) + b"abc")
            elif data[0] == 0x80:                                   # the client's abort
                index, = struct.unpack_from("<H", data, 1)
                self.aborts.append((index, struct.unpack_from("<L", data, 4)[0]))
            # the block acknowledge (0xA2) gets no "end block upload": the drive stopped here

    def close(self) -> None:
        self.stop.set()
        self.join(2)
        self.bus.shutdown()


@pytest.fixture
def node_and_server():
    channel = f"test-block-upload-{next(_channels)}"
    server = SilentAtTheEnd(channel)
    server.start()
    network = canopen.Network()
    network.connect(interface="virtual", channel=channel)
    node = network.add_node(1, str(eds_path()))
    node.sdo.RESPONSE_TIMEOUT = 0.3
    yield node, server
    network.disconnect()
    server.close()


def test_an_unanswered_end_of_a_block_upload_is_a_timeout_and_is_aborted(node_and_server):
    node, server = node_and_server
    with pytest.raises(SdoCommunicationError):
        block_upload(node.sdo, LINK_MESSAGE)
    deadline = time.monotonic() + 5
    while not server.aborts and time.monotonic() < deadline:   # the server's thread reads it
        time.sleep(0.01)
    assert [code for _index, code in server.aborts] == [ABORT_TIMED_OUT]   # python-canopen's abort names no index


def test_other_attribute_errors_are_not_taken_for_a_timeout():
    class NoOpen:
        def open(self, *args, **kwargs):
            raise AttributeError("something else", name="abort", obj=self)
    with pytest.raises(AttributeError, match="something else"):
        block_upload(NoOpen(), LINK_MESSAGE)
