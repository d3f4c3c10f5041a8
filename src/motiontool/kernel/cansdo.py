"""SDO on the simulated CAN bus (CiA 301 expedited and segmented transfers): the client behind SDOREAD,
SDOWRITE, SDOREADSEG(P) and SDOSTATE (CR 3689-3887, DG 7355-7382), and the server every simulated MCO runs on
0x600 + CANNR / 0x580 + CANNR ("a complete SDO dictionary is implemented", DG 7403).

Client transfers live in channels, one per node id. A negative id starts a transfer without waiting: at most 5
run in parallel, to different ids (error 121, DG 11606-11612); SDOSTATE reads the result and frees the channel
(CR 3816-3862). A waiting transfer blocks the program; a failure is error 189 with the node id as extra
information (DG 11800-11806). No answer within `SDO_TIMEOUT_MS` is a timeout (decision K106).
"""

from __future__ import annotations

import struct
from dataclasses import dataclass, field

from motiontool.kernel import objdict
from motiontool.kernel.canbus import CanFrame
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.vm import ArrayRef, Wait

SDO_TIMEOUT_MS = 500
MAX_CHANNELS = 5               # "Up to 5 transfers to different ids in parallel" (CR 3849-3852)
# SDOSTATE results (CR 3823-3837, DG 11411-11426)
BUSY, VALUE, SEGMENTS = 0, 1, 2
TIMEOUT, CAN_ERROR, NOT_IN_USE, ABORTED = -2, -12, -33, -50
ARRAY_TOO_SMALL, TOGGLE_ERROR, TOO_MUCH, NOT_ENOUGH = -51, -52, -53, -54
_HEADER = struct.Struct("<BHB")


def _request(command: int, index: int, sub: int, payload: bytes = b"") -> bytes:
    return _HEADER.pack(command, index, sub) + payload.ljust(4, b"\0")


def abort_frame(node: int, index: int, sub: int, code: int) -> CanFrame:
    return CanFrame(0x580 + node, _request(0x80, index, sub, struct.pack("<I", code)))


@dataclass
class Transfer:
    """One client transfer to `node`: "read" (SDOREAD), "write" (SDOWRITE), "seg"/"segp" (SDOREADSEG(P))."""

    node: int
    kind: str
    index: int
    sub: int
    value: int = 0
    array: ArrayRef | None = None      # the DIM array of a segmented read
    waiting: bool = True
    deadline: int = 0
    state: int = BUSY                  # SDOSTATE code once finished
    result: int = 0                    # the value SDOSTATE writes into its variable
    toggle: int = 0
    data: bytearray = field(default_factory=bytearray)
    size: int | None = None

    @property
    def finished(self) -> bool:
        return self.state != BUSY


class SdoClient:
    """The channels of one controller (port.sdo)."""

    def __init__(self, port) -> None:
        self.port = port
        self.channels: dict[int, Transfer] = {}

    @property
    def busy(self) -> bool:
        return any(not t.finished for t in self.channels.values())

    def start(self, transfer: Transfer) -> Transfer:
        if not 1 <= transfer.node <= 127:
            raise ControllerError(183, f"CAN id {transfer.node}: 1..127 (CR 3693)")
        old = self.channels.get(transfer.node)
        if old is not None and not old.finished:
            raise ControllerError(121, f"an SDO transfer to node {transfer.node} is still running")
        unread = [n for n, t in self.channels.items() if n != transfer.node and not t.waiting]
        if not transfer.waiting and len(unread) >= MAX_CHANNELS:
            raise ControllerError(121, f"{MAX_CHANNELS} non-waiting SDO transfers are not read yet")
        self.channels[transfer.node] = transfer
        transfer.deadline = self.port.controller.time_ms + SDO_TIMEOUT_MS
        if transfer.kind == "write":
            payload = struct.pack("<i", _long(transfer.value))
            self._send(transfer, _request(0x23, transfer.index, transfer.sub, payload))
        else:
            self._send(transfer, _request(0x40, transfer.index, transfer.sub))
        return transfer

    def state(self, node: int) -> tuple[int, int]:
        """SDOSTATE: (result code, value); a finished transfer's channel is freed by reading it."""
        transfer = self.channels.get(abs(node))
        if transfer is None:
            return NOT_IN_USE, 0
        if transfer.finished:
            del self.channels[abs(node)]
        return transfer.state, transfer.result

    def _send(self, transfer: Transfer, data: bytes) -> None:
        self.port.send(CanFrame(0x600 + transfer.node, data))

    # --- ticks ---------------------------------------------------------------------------------------------
    def expire(self, now: int) -> None:
        for transfer in self.channels.values():
            if not transfer.finished and now >= transfer.deadline:
                self._finish(transfer, TIMEOUT, (transfer.index << 8) + transfer.sub)
                self._send(transfer, _request(0x80, transfer.index, transfer.sub,
                                              struct.pack("<I", objdict.ABORT_TIMEOUT)))

    def response(self, frame: CanFrame) -> bool:
        """An SDO answer (0x581-0x5FF) for one of our transfers; True when it was one."""
        transfer = self.channels.get(frame.can_id - 0x580)
        if transfer is None or transfer.finished or len(frame.data) < 8:
            return False
        data = frame.data
        scs = data[0] >> 5
        if scs == 4:                                        # abort by the server
            self._finish(transfer, ABORTED, struct.unpack_from("<i", data, 4)[0])
        elif transfer.kind == "write":
            if scs == 3:
                self._finish(transfer, VALUE, transfer.value)
        elif scs == 2:                                      # initiate upload answer
            self._upload_started(transfer, data)
        elif scs == 0:                                      # an upload segment
            self._segment(transfer, data)
        transfer.deadline = self.port.controller.time_ms + SDO_TIMEOUT_MS
        return True

    def _upload_started(self, transfer: Transfer, data: bytes) -> None:
        if data[0] & 0x02:                                  # expedited
            size = 4 - ((data[0] >> 2) & 3) if data[0] & 0x01 else 4
            transfer.data = bytearray(data[4:4 + size])
            self._complete(transfer)
            return
        transfer.size = struct.unpack_from("<I", data, 4)[0] if data[0] & 0x01 else None
        transfer.toggle = 0
        self._send(transfer, _request(0x60, 0, 0)[:1] + bytes(7))

    def _segment(self, transfer: Transfer, data: bytes) -> None:
        if (data[0] >> 4) & 1 != transfer.toggle:
            self._finish(transfer, TOGGLE_ERROR, 0)
            return
        transfer.data += data[1:8 - ((data[0] >> 1) & 7)]
        if transfer.size is not None and len(transfer.data) > transfer.size:
            self._finish(transfer, TOO_MUCH, len(transfer.data))
        elif data[0] & 0x01:
            if transfer.size is not None and len(transfer.data) < transfer.size:
                self._finish(transfer, NOT_ENOUGH, len(transfer.data))
            else:
                self._complete(transfer)
        else:
            transfer.toggle ^= 1
            self._send(transfer, bytes([0x60 | transfer.toggle << 4]) + bytes(7))

    def _complete(self, transfer: Transfer) -> None:
        data = bytes(transfer.data)
        if transfer.kind == "read":
            self._finish(transfer, VALUE, _long(int.from_bytes(data[:4], "little", signed=len(data) >= 4)))
            return
        array = transfer.array
        assert array is not None  # SDOREADSEG(P) ("seg"/"segp") give one; "write" does not come here
        per_element = 4 if transfer.kind == "segp" else 1
        needed = -(-len(data) // per_element)
        if needed > len(array.data):
            self._finish(transfer, ARRAY_TOO_SMALL, needed)
            return
        if per_element == 1:
            array.data[:len(data)] = list(data)
        else:   # packed: byte k in element k // 4 + 1, .b1 first (the manual's printpackedstring, CR 3777-3797)
            padded = data.ljust(4 * needed, b"\0")
            array.data[:needed] = list(struct.unpack(f"<{needed}i", padded))
        self._finish(transfer, SEGMENTS, len(data))

    def _finish(self, transfer: Transfer, state: int, result: int) -> None:
        transfer.state, transfer.result = state, result


def _long(value: int) -> int:
    value &= 0xFFFFFFFF
    return value - (1 << 32) if value >> 31 else value


class SdoWait(Wait):
    """A program waiting for its transfer: the value when it succeeds, error 189 when it fails (DG 11800)."""

    def __init__(self, vm, client: SdoClient, transfer: Transfer, returns_value: bool):
        self.vm, self.client, self.transfer, self.returns_value = vm, client, transfer, returns_value

    def done(self) -> bool:
        transfer = self.transfer
        if not transfer.finished:
            return False
        self.client.channels.pop(transfer.node, None)
        if transfer.state in (VALUE, SEGMENTS):
            self.value = transfer.result if self.returns_value else None
            return True
        # the command failed: it ends (0 as its value) and error 189 goes to ON ERROR or ends the program
        self.vm.wait = None
        if self.returns_value:
            self.vm.stack.append(0)
        raise ControllerError(189, f"SDO to node {transfer.node}, object 0x{transfer.index:04X}/{transfer.sub}: "
                                   f"{describe(transfer)}")


def describe(transfer: Transfer) -> str:
    state = transfer.state
    if state == TIMEOUT:
        return f"no answer within {SDO_TIMEOUT_MS} ms"
    if state == ABORTED:
        return f"aborted with code 0x{transfer.result & 0xFFFFFFFF:08X}"
    if state == ARRAY_TOO_SMALL:
        return f"the array is too small ({transfer.result} elements needed)"
    return {TOGGLE_ERROR: "toggle bit error", TOO_MUCH: "more data than announced",
            NOT_ENOUGH: "less data than announced"}.get(state, f"failed ({state})")


# --- the server ---------------------------------------------------------------------------------------------------
class SdoServer:
    """The kernel's SDO server of one controller (when no bridge serves it, CanBus.kernel_sdo_servers)."""

    def __init__(self, port) -> None:
        self.port = port
        self._upload: bytes | None = None
        self._download: bytearray | None = None
        self._where = (0, 0)
        self._toggle = 0

    def request(self, frame: CanFrame) -> None:
        data = frame.data
        if len(data) < 8:
            return
        ccs = data[0] >> 5
        node = self.port.node_id
        index, sub = struct.unpack_from("<HB", data, 1)
        try:
            if ccs == 2:
                self._initiate_upload(index, sub)
            elif ccs == 3:
                self._upload_segment(data[0])
            elif ccs == 1:
                self._initiate_download(data, index, sub)
            elif ccs == 0:
                self._download_segment(data)
            elif ccs == 4:
                self._upload = self._download = None
            else:
                raise objdict.ObjectError(objdict.ABORT_COMMAND, "block transfers are not served by the kernel")
        except objdict.ObjectError as exc:
            self._upload = self._download = None
            where: tuple[int, int] = (index, sub) if ccs in (1, 2) else self._where
            self.port.send(abort_frame(node, *where, exc.code))

    def _reply(self, data: bytes) -> None:
        self.port.send(CanFrame(0x580 + self.port.node_id, data))

    def _initiate_upload(self, index: int, sub: int) -> None:
        entry = objdict.find(index, sub)
        raw = objdict.encode(objdict.read(self.port.controller, index, sub), entry.datatype)
        self._where = (index, sub)
        if 0 < len(raw) <= 4:
            self._reply(_request(0x43 | (4 - len(raw)) << 2, index, sub, raw))
            return
        self._upload, self._toggle = raw, 0
        self._reply(_request(0x41, index, sub, struct.pack("<I", len(raw))))

    def _upload_segment(self, command: int) -> None:
        if self._upload is None:
            raise objdict.ObjectError(objdict.ABORT_COMMAND, "no upload running")
        if (command >> 4) & 1 != self._toggle:
            raise objdict.ObjectError(objdict.ABORT_TOGGLE)
        chunk, self._upload = self._upload[:7], self._upload[7:]
        last = not self._upload
        self._reply(bytes([self._toggle << 4 | (7 - len(chunk)) << 1 | int(last)]) + chunk.ljust(7, b"\0"))
        self._toggle ^= 1
        if last:
            self._upload = None

    def _initiate_download(self, data: bytes, index: int, sub: int) -> None:
        entry = objdict.find(index, sub)
        self._where = (index, sub)
        if data[0] & 0x02:   # expedited
            size = 4 - ((data[0] >> 2) & 3) if data[0] & 0x01 else 4
            self._store(entry, bytes(data[4:4 + size]))
            self._reply(_request(0x60, index, sub))
            return
        self._download, self._toggle = bytearray(), 0
        self._reply(_request(0x60, index, sub))

    def _download_segment(self, data: bytes) -> None:
        if self._download is None:
            raise objdict.ObjectError(objdict.ABORT_COMMAND, "no download running")
        if (data[0] >> 4) & 1 != self._toggle:
            raise objdict.ObjectError(objdict.ABORT_TOGGLE)
        self._download += data[1:8 - ((data[0] >> 1) & 7)]
        self._reply(bytes([0x20 | self._toggle << 4]) + bytes(7))
        self._toggle ^= 1
        if data[0] & 0x01:
            raw, self._download = bytes(self._download), None
            self._store(objdict.find(*self._where), raw)

    def _store(self, entry: objdict.Entry, raw: bytes) -> None:
        objdict.write(self.port.controller, entry.index, entry.sub, objdict.decode(raw, entry.datatype), "sdo")
