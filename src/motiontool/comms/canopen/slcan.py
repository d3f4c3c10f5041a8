"""The master's side of slcan (Lawicel ASCII) over TCP: the frames as lines and a python-can bus that reads them in
bulk (`SlcanSocketBus`), for ``canopen:slcan:socket://HOST:PORT`` links to the virtual drive's slcan server
(controller/canopen/slcan_server.py) or a serial-to-Ethernet CAN adapter.

A frame is ``tiiil<data>`` / ``Tiiiiiiiil<data>`` (``r``/``R`` remote frames), CR-terminated; ``Z1`` appends a 16-bit
ms time stamp. OK is CR, an error BEL.
"""

from __future__ import annotations

import contextlib
import re
import select
import socket
import threading
import time
from collections import deque
from collections.abc import Callable

import can

from motiontool.cliargs import shown

OK, ERROR = b"\r", b"\a"
READ_SIZE = 65536
MAX_LINE = 64               # the longest slcan line is 30 characters (T, 8 id, dlc, 16 data, 4 stamp)


def frame_text(msg: can.Message, stamp: bool = False) -> bytes:
    """A message as one Lawicel line."""
    if msg.is_remote_frame:
        head = f"R{msg.arbitration_id:08X}{msg.dlc}" if msg.is_extended_id else f"r{msg.arbitration_id:03X}{msg.dlc}"
    else:
        head = (f"T{msg.arbitration_id:08X}" if msg.is_extended_id else f"t{msg.arbitration_id:03X}") + \
            f"{len(msg.data)}{bytes(msg.data).hex().upper()}"
    if stamp:
        head += f"{int(time.monotonic() * 1000) % 60000:04X}"
    return head.encode("ascii") + OK


_HEX = frozenset("0123456789abcdefABCDEF")


def parse_frame(line: str) -> can.Message | None:
    """A ``t``/``T``/``r``/``R`` command → message; None when it is malformed: anything but hex digits (a sign, a
    space), an id beyond 11/29 bits, a DLC beyond 8, missing data, or characters after the frame other than a
    4-digit time stamp."""
    kind = line[:1]
    extended = kind in ("T", "R")
    width = 8 if extended else 3
    digits = line[1:]
    if kind not in ("t", "T", "r", "R") or not digits or not set(digits) <= _HEX or len(digits) < width + 1:
        return None
    can_id, dlc = int(digits[:width], 16), int(digits[width], 16)
    if dlc > 8 or can_id > (0x1FFFFFFF if extended else 0x7FF):
        return None
    data_digits = 0 if kind in ("r", "R") else 2 * dlc
    if len(digits) - width - 1 - data_digits not in (0, 4):   # nothing after the data but a time stamp
        return None
    if kind in ("r", "R"):
        return can.Message(arbitration_id=can_id, is_extended_id=extended, is_remote_frame=True, dlc=dlc)
    data = bytes.fromhex(digits[width + 1:width + 1 + data_digits])
    return can.Message(arbitration_id=can_id, is_extended_id=extended, data=data)



class SlcanSocketBus(can.BusABC):
    """A python-can bus that speaks slcan over TCP with buffered reads (decision N13).

    python-can's own slcan interface reads its port one byte at a time, three system calls per byte on a
    ``socket://`` channel: about 500 frames/s on a busy 2-core machine, an eighth of what four 1 kHz TPDOs need.
    This class speaks the same protocol to the same servers and reads whatever has arrived in one call.
    """

    def __init__(self, channel: str, timeout: float = 5.0, **kwargs):
        address = channel.removeprefix("socket://")
        host, _, port = address.rpartition(":")
        if not host or not re.fullmatch(r"[0-9]{1,5}", port) or int(port) > 65535:  # ASCII: isdigit() takes "٥"
            raise can.CanInitializationError(f"slcan channel {shown(channel)!r}: give socket://HOST:PORT "
                                             "(PORT 0-65535)")
        try:
            self.sock = socket.create_connection((host, int(port)), timeout=timeout)
        except OSError as exc:
            raise can.CanInitializationError(f"cannot connect to {channel}: {exc}") from exc
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.sock.settimeout(timeout)      # for send and close; reads wait in select (_read)
        self._buffer = b""
        self._lines: deque[str] = deque()
        self._send_lock = threading.Lock()
        # (id, extended) -> bool: frames nobody listens to are skipped before they are parsed (a busy bus, a babbling
        # node: the link's SDO thread keeps its core)
        self.wanted: Callable[[int, bool], bool] | None = None
        self.channel_info = f"slcan {channel}"
        self._write(b"C\rO\r")
        super().__init__(channel=channel, **kwargs)

    def _write(self, data: bytes) -> None:
        try:
            with self._send_lock:
                self.sock.sendall(data)
        except OSError as exc:
            raise can.CanOperationError(f"slcan write failed: {exc}") from exc

    def send(self, msg: can.Message, timeout: float | None = None) -> None:
        self._write(frame_text(msg))

    def _recv_internal(self, timeout: float | None) -> tuple[can.Message | None, bool]:
        """The next frame the server sent (its answers ``z``/``Z``/CR are skipped), waiting at most `timeout`."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            while self._lines:
                line = self._lines.popleft()
                head = line[:1]
                if head not in ("t", "T", "r", "R") or not self._is_wanted(line, head in ("T", "R")):
                    continue
                msg = parse_frame(line)
                if msg is not None:
                    msg.timestamp = time.time()
                    msg.channel = self.channel_info
                    return msg, False
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            self._read(left)
            if not self._lines and deadline is not None and time.monotonic() >= deadline:
                return None, False

    def _is_wanted(self, line: str, extended: bool) -> bool:
        if self.wanted is None:
            return True
        try:
            can_id = int(line[1:9] if extended else line[1:4], 16)
        except ValueError:
            return True        # parse_frame refuses it
        return self.wanted(can_id, extended)

    def _read(self, timeout: float | None) -> bool:
        """Read what has arrived (waiting at most `timeout`); True when lines came. The wait is a select, not a
        socket timeout, which `send` in other threads would share."""
        try:
            if not select.select([self.sock], [], [], timeout)[0]:
                return False
            chunk = self.sock.recv(READ_SIZE)
        except (OSError, ValueError) as exc:      # ValueError: select on a socket closed by shutdown()
            raise can.CanOperationError(f"slcan read failed: {exc}") from exc
        if not chunk:
            raise can.CanOperationError("the slcan server closed the connection")
        *lines, self._buffer = (self._buffer + chunk).split(b"\r")
        if len(self._buffer) > MAX_LINE:     # an adapter that sends no CR is not speaking slcan: not kept
            self._buffer = b""
        self._lines.extend(line.decode("ascii", "replace").strip("\a\n ") for line in lines)
        return bool(lines)

    def shutdown(self) -> None:
        super().shutdown()
        with contextlib.suppress(OSError):
            self.sock.sendall(b"C\r")
        with contextlib.suppress(OSError):
            self.sock.close()
