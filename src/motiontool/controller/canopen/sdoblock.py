"""SDO block transfer (CiA 301 7.2.4.3.9-7.2.4.3.16) for the drive's SDO servers.

python-canopen's SdoServer answers block uploads with a segmented upload and refuses block downloads; its client
speaks both. Program downloads, arrays and the link's messages travel through DOMAIN objects, where a block of
127 segments with one acknowledgement beats one round trip per 7 bytes (decision N14). Both directions check the
CRC (CRC-16/XMODEM, as python-canopen) when the client asks for it.
"""

from __future__ import annotations

import binascii
import struct
import time

from canopen.sdo import SdoAbortedError, SdoServer

BLOCK_SIZE = 127
IDLE_S = 5.0    # a block transfer without a frame this long was abandoned by its client (it vanished)
ABORT_COMMAND, ABORT_SEQUENCE, ABORT_CRC = 0x05040001, 0x05040003, 0x05040004
_HEADER = struct.Struct("<BHB")


class BlockSdoServer(SdoServer):
    """An SdoServer that also serves block downloads and block uploads."""

    def __init__(self, rx_cobid: int, tx_cobid: int, node) -> None:
        super().__init__(rx_cobid, tx_cobid, node)
        self._block: _BlockDownload | _BlockUpload | None = None
        self._last = 0.0

    def forget_transfer(self) -> None:
        """The client went away (its slcan connection closed): a block transfer in progress is over."""
        self._block = None

    def on_request(self, can_id, data, timestamp):
        if getattr(self._node, "stopped", False):   # CiA 301: no SDO in STOPPED; the client's request times out
            return
        if len(data) != 8:   # an SDO frame has 8 bytes: python-canopen's server printed a traceback for a short one
            if self._block is None and data:
                head = bytes(data[1:4]).ljust(3, b"\0")      # the object it names, as far as it names one
                self.send_response(struct.pack("<BHBL", 0x80, head[0] | head[1] << 8, head[2], ABORT_COMMAND))
            return
        now = time.monotonic()
        if self._block is not None and now - self._last > IDLE_S:
            self._block = None
        self._last = now
        block = self._block
        if block is not None:
            if data[0] == 0x80:                        # an abort ends the block transfer (segments have a seqno)
                self._block = None
                return
            try:
                if block.on_frame(bytes(data)):
                    self._block = None
            except SdoAbortedError as exc:
                self._block = None
                self.abort(exc.code)
            return
        super().on_request(can_id, data, timestamp)

    def block_download(self, data):
        command, index, subindex = _HEADER.unpack_from(data)
        self._index, self._subindex = index, subindex
        if command & 0x01:
            raise SdoAbortedError(ABORT_COMMAND)
        crc = bool(command & 0x04)
        self._block = _BlockDownload(self, index, subindex, crc)
        self.send_response(_HEADER.pack(0xA0 | crc << 2, index, subindex) + bytes([BLOCK_SIZE, 0, 0, 0]))

    def block_upload(self, data):
        command, index, subindex = _HEADER.unpack_from(data)
        self._index, self._subindex = index, subindex
        if command & 0x03:
            raise SdoAbortedError(ABORT_COMMAND)
        payload = self._node.get_data(index, subindex, check_readable=True)
        blksize = data[4] or BLOCK_SIZE
        crc = bool(command & 0x04)
        self._block = _BlockUpload(self, payload, blksize, crc)
        self.send_response(_HEADER.pack(0xC2 | crc << 2, index, subindex) + struct.pack("<I", len(payload)))


class _BlockDownload:
    def __init__(self, server: BlockSdoServer, index: int, subindex: int, crc: bool):
        self.server, self.index, self.subindex, self.crc = server, index, subindex, crc
        self.data = bytearray()
        self.expected = 1
        self.ended = False

    def on_frame(self, data: bytes) -> bool:
        """A segment, or the end of the transfer; True when the transfer is over."""
        if self.ended:
            if data[0] & 0xE3 != 0xC1:
                raise SdoAbortedError(ABORT_COMMAND)
            unused = (data[0] >> 2) & 7
            if unused:
                del self.data[-unused:]
            if self.crc and struct.unpack_from("<H", data, 1)[0] != binascii.crc_hqx(bytes(self.data), 0):
                raise SdoAbortedError(ABORT_CRC)
            self.server._node.set_data(self.index, self.subindex, bytes(self.data), check_writable=True)
            self.server.send_response(bytes([0xA1]) + bytes(7))
            return True
        seqno, last = data[0] & 0x7F, bool(data[0] & 0x80)
        if seqno == self.expected:
            self.data += data[1:8]
            self.expected += 1
        elif seqno == 0:
            raise SdoAbortedError(ABORT_SEQUENCE)
        if last or seqno >= BLOCK_SIZE:
            acked = self.expected - 1
            self.server.send_response(bytes([0xA2, acked, BLOCK_SIZE]) + bytes(5))
            self.ended = last and acked == seqno
            self.expected = 1
        return False


class _BlockUpload:
    def __init__(self, server: BlockSdoServer, payload: bytes, blksize: int, crc: bool):
        self.server, self.payload, self.blksize, self.crc = server, payload, blksize, crc
        self.position = 0          # first byte of the block being sent
        self.sent = 0              # segments in that block
        self.state = "start"

    def on_frame(self, data: bytes) -> bool:
        command = data[0]
        if self.state == "start":
            if command != 0xA3:
                raise SdoAbortedError(ABORT_COMMAND)
            self._send_block()
        elif self.state == "ack":
            if command & 0xE3 != 0xA2:
                raise SdoAbortedError(ABORT_COMMAND)
            acked, self.blksize = data[1], data[2] or BLOCK_SIZE
            self.position = min(len(self.payload), self.position + 7 * acked)
            if self.position >= len(self.payload) and acked == self.sent:
                unused = (7 - len(self.payload) % 7) % 7 if self.payload else 7
                crc = binascii.crc_hqx(self.payload, 0) if self.crc else 0
                self.server.send_response(struct.pack("<BH", 0xC1 | unused << 2, crc) + bytes(5))
                self.state = "end"
            else:
                self._send_block()
        elif self.state == "end":
            if command & 0xE3 != 0xA1:
                raise SdoAbortedError(ABORT_COMMAND)
            return True
        return False

    def _send_block(self) -> None:
        chunks = [self.payload[i:i + 7] for i in range(self.position, len(self.payload), 7)][:self.blksize]
        if not chunks:
            chunks = [b""]
        end = self.position + 7 * len(chunks) >= len(self.payload)
        for seqno, chunk in enumerate(chunks, start=1):
            last = end and seqno == len(chunks)
            self.server.send_response(bytes([seqno | (0x80 if last else 0)]) + chunk.ljust(7, b"\0"))
        self.sent = len(chunks)
        self.state = "ack"
