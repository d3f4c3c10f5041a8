"""One simulated controller as a CANopen slave: a python-canopen LocalNode whose SDO server reads and writes the
controller's object dictionary (kernel/objdict.py) and the service objects (comms/canopen/objects.py) under the
drive's lock.

NMT, heartbeat and PDOs are the controller's own (kernel/canport.py, kernel/canpdo.py), reaching the bus through
the drive's bridge (server.py): the LocalNode here is the SDO server only, so the dictionary has one owner.
"""

from __future__ import annotations

import base64

import canopen
from canopen.sdo import SdoAbortedError

from motiontool.comms.canopen import objects
from motiontool.comms.protocol import Request
from motiontool.controller.canopen.eds import SERVICE_OBJECTS
from motiontool.controller.canopen.sdoblock import BlockSdoServer
from motiontool.kernel import objdict
from motiontool.kernel.canport import STOPPED

ABORT_GENERAL = 0x08000000
SDO2_RX, SDO2_TX = 0x100, 0x680   # SDO server 2's COB-IDs + node id (DG 7323-7325), valid once 0x1201 says so
NOT_VALID = 0x80000000
ABORT_LENGTH_HIGH, ABORT_LENGTH_LOW = 0x06070012, 0x06070013


def _check_length(data: bytes, datatype: str) -> None:
    """A master writes a fixed-size object with exactly its size (CiA 301 7.2.4.3.3): two bytes into KPROP made it
    16, four into the UNSIGNED16 0x1017 were taken. (The controllers' own SDOWRITE keeps the kernel's 1..4-byte
    reading, DG 7382.)"""
    size = objdict.DATATYPES[datatype][1]
    if not size:          # strings and domains have the length they are given
        return
    if len(data) > size:
        raise SdoAbortedError(ABORT_LENGTH_HIGH)
    if len(data) < size:
        raise SdoAbortedError(ABORT_LENGTH_LOW)


class ControllerNode(canopen.LocalNode):
    """`drive_node` is the drive's DriveNode (controller/drive/node.py): its `service` (a ControllerService) and its
    `handle_message(bytes) -> bytes` for the link messages of 0x5F00."""

    def __init__(self, node_id: int, od: canopen.ObjectDictionary, drive, drive_node, eds_text: str):
        super().__init__(node_id, od)
        # before the network subscribes it
        self.sdo: BlockSdoServer = BlockSdoServer(0x600 + node_id, 0x580 + node_id, self)
        self.sdo2 = BlockSdoServer(SDO2_RX + node_id, SDO2_TX + node_id, _SecondChannel(self))
        self.drive = drive
        self.drive_node = drive_node
        self.eds = eds_text.encode("utf-8")
        self._answers = {1: b"", 2: b""}   # per SDO channel: the answer to the last link message written to 0x5F00

    def associate_network(self, network) -> None:
        super().associate_network(network)
        self.sdo2.network = network
        network.subscribe(self.sdo2.rx_cobid, self.sdo2.on_request)

    def remove_network(self) -> None:
        if self.has_network():
            self.network.unsubscribe(self.sdo2.rx_cobid, self.sdo2.on_request)
        super().remove_network()

    def forget_transfer(self, cob_id: int) -> None:
        """The master that sent requests on `cob_id` went away, maybe in the middle of a block transfer."""
        for server in (self.sdo, self.sdo2):
            if server.rx_cobid == cob_id:
                server.forget_transfer()

    def reset_communication(self) -> None:
        """NMT Reset Communication / Reset Node: a transfer under way on SDO 2 ends. The controller itself makes
        0x1201 NOT_VALID again when it takes the command, before it boots up (kernel/canport.py, N51/N52); written
        here as a master's SDO write, it fired the program's ON PARAM."""
        self.sdo2.forget_transfer()

    @property
    def sdo2_valid(self) -> bool:
        """SDO server 2 answers once a master or the program cleared NOT_VALID in both COB-IDs (DG 7327-7337)."""
        with self.drive.lock:
            return not any(objdict.read(self.controller, 0x1201, sub) & NOT_VALID for sub in (1, 2))

    @property
    def controller(self):
        return self.drive_node.service.controller

    @property
    def stopped(self) -> bool:
        """In NMT STOPPED the node serves no SDO (CiA 301 7.3.2.2); the NMT state is the controller's own."""
        return self.controller.can.nmt_state == STOPPED

    # --- SDO server callbacks ----------------------------------------------------------------------------
    def get_data(self, index: int, subindex: int, check_readable: bool = False, channel: int = 1) -> bytes:
        if index in SERVICE_OBJECTS:
            return self._service_read(index, channel)
        with self.drive.lock:
            try:
                entry = objdict.find(index, subindex)
                return objdict.encode(objdict.read(self.controller, index, subindex), entry.datatype)
            except objdict.ObjectError as exc:
                raise SdoAbortedError(exc.code) from None

    def set_data(self, index: int, subindex: int, data: bytes, check_writable: bool = False,
                 channel: int = 1) -> None:
        if index in SERVICE_OBJECTS:
            self._service_write(index, bytes(data), channel)
            return
        with self.drive.lock:
            try:
                entry = objdict.find(index, subindex)
                _check_length(bytes(data), entry.datatype)
                objdict.write(self.controller, index, subindex, objdict.decode(bytes(data), entry.datatype), "sdo")
            except objdict.ObjectError as exc:
                raise SdoAbortedError(exc.code) from None

    # --- the service objects ----------------------------------------------------------------------------
    def _service_read(self, index: int, channel: int) -> bytes:
        if index == objects.STORE_EDS:
            return self.eds
        if index == objects.LINK_MESSAGE:
            if not self._answers[channel]:
                raise SdoAbortedError(objdict.ABORT_NO_DATA)
            return self._answers[channel]
        if index == objects.PROGRAM_CONTROL:
            with self.drive.lock:
                state = objects.PROGRAM_STATES.get(self.controller.program_state, 0)
            return objdict.encode(state, "INTEGER32")
        raise SdoAbortedError(objdict.ABORT_WRITE_ONLY)

    def _service_write(self, index: int, data: bytes, channel: int) -> None:
        if index == objects.LINK_MESSAGE:
            self._answers[channel] = self.drive_node.handle_message(data)
            return
        if index == objects.STORE_EDS:
            raise SdoAbortedError(objdict.ABORT_READ_ONLY)
        service = self.drive_node.service
        if index == objects.PROGRAM_CONTROL:
            command = objdict.decode(data, "INTEGER32")
            op = {objects.START: "start", objects.BREAK: "break", objects.CONTINUE: "continue"}.get(command)
            if op is None:
                raise SdoAbortedError(objdict.ABORT_VALUE)
            request = Request(op, {})
        else:   # PROGRAM_IMAGE, the last of SERVICE_OBJECTS
            request = Request("download", {"image": base64.b64encode(data).decode("ascii"), "number": None,
                                           "name": ""})
        with self.drive.lock:
            response = service.handle(request)
        if not response.ok:
            raise SdoAbortedError(objdict.ABORT_STATE if index == objects.PROGRAM_CONTROL else objdict.ABORT_STORE)


class _SecondChannel:
    """What SDO server 2 serves: the node's objects, but its own answer in 0x5F00, so a master on each channel
    reads the answer to its own message (decision N52)."""

    def __init__(self, node: ControllerNode):
        self.node = node
        self.object_dictionary = node.object_dictionary

    @property
    def stopped(self) -> bool:
        """No answer in STOPPED, nor while 0x1201 is NOT_VALID: the client times out as at a node without it."""
        return self.node.stopped or not self.node.sdo2_valid

    def get_data(self, index: int, subindex: int, check_readable: bool = False) -> bytes:
        return self.node.get_data(index, subindex, check_readable, channel=2)

    def set_data(self, index: int, subindex: int, data: bytes, check_writable: bool = False) -> None:
        self.node.set_data(index, subindex, data, check_writable, channel=2)
