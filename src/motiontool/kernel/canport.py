"""The CAN controller of one simulated MCO: its node id, the frames it receives and what it does with them
(DG 7274-7428). The APOSS commands (kernel/can_commands.py) and the object dictionary (kernel/objdict.py) use it.

Every tick (`Controller.tick`) the port takes the frames the bus delivered (kernel/canbus.py) and hands each to its
first taker: NMT commands and global messages (identifier 0), raw mailboxes (DEFCANIN), the CANINI 999 capture of
TxPDO1s, PDOs and SYNC (kernel/canpdo.py), SDO requests and answers (kernel/cansdo.py), node guarding, the buffered
RxMessage (CANNR * 2 + 1). Then it sends what is due: TxPDOs, heartbeats, CANINI guarding.

The node id is parameter 33-90 CANNR (default 127); in a simulation of several controllers every controller's
CANNR starts as its node id (decision K101).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

from motiontool.kernel.canbus import CanBus, CanFrame
from motiontool.kernel.canpdo import PdoEngine
from motiontool.kernel.cansdo import SdoClient, SdoServer
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.objdict import sysvar_index
from motiontool.kernel.sysvars import read_sysvar

CANNR = 3390
# NMT states (CiA 301): the byte of heartbeat and node guarding answers
BOOTUP, STOPPED, OPERATIONAL, PRE_OPERATIONAL = 0x00, 0x04, 0x05, 0x7F
RESET_NODE, RESET_COMMUNICATION = 0x81, 0x82
NMT_COMMANDS = {0x01: OPERATIONAL, 0x02: STOPPED, 0x80: PRE_OPERATIONAL, RESET_NODE: BOOTUP,
                RESET_COMMUNICATION: BOOTUP}
MAX_MAILBOXES = 14          # object 15 belongs to CANINI 999 (CR 388-390)
MAX_MODULES = 16            # CANINI: "A maximum of 16 modules can be stored internally" (CR 458)
GUARD_PERIOD_MS, GUARD_TIMEOUT_MS = 20, 100   # CR 449-453
NO_CANMEMORY = -10          # DEFCANIN/DEFCANOUT when no mailbox is left (DG 11417)
RX_QUEUE = 32               # buffered RxMessages kept for INMSG
LCP_PERIOD_MS = 40          # LINKSYSVAR refresh (CR 2099-2102)


@dataclass
class Mailbox:
    """A DEFCANIN (receive) or DEFCANOUT (transmit) object."""

    number: int
    can_id: int
    length: int
    receive: bool
    data: bytes = b""
    new: bool = False
    sent: bool = False      # a transmit object has data to answer remote frames with


class CanPort:
    def __init__(self, controller) -> None:
        self.controller = controller
        self.bus = CanBus()
        self.bus.attach(self)
        self.own_bus = True                   # a controller alone: its tick delivers its private bus
        self.inbox: list[CanFrame] = []
        self.pdo = PdoEngine(self)
        self.sdo = SdoClient(self)
        self.server = SdoServer(self)
        self._node_id: int | None = None
        self.nmt_state = BOOTUP
        self.heartbeat_ms = 0                 # 0x1017
        self.reset_node_pending = False       # NMT Reset Node received: the host powers the controller off and on
        self._last_heartbeat = 0
        self._guard_toggle = 0
        self.guard_error_id = 0               # SYSVAR 67 / 0x2202 sub 0x44 (CR 471)
        self.user_status = 0                  # USRSTAT
        self.busy = True                      # guarding, LINKSYSVAR or a boot-up to do (else the tick is skipped)
        self.program_started()

    def program_started(self) -> None:
        """A program start forgets the program's CAN objects (mailboxes, CANINI, CANINI 999, its transfers)."""
        self.mailboxes: dict[int, Mailbox] = {}
        self.global_message: bytes | None = None
        self.global_new = False
        self.messages: deque[bytes] = deque(maxlen=RX_QUEUE)
        self.msgval = 0
        self.capture: dict[int, tuple[bytes, bool]] | None = None     # CANINI 999: node → (TxPDO1, new)
        self.modules: list[int] = []                                  # CANINI: guarded nodes
        self._guard_next = 0
        self._guard_pending: dict[int, int] = {}                      # node → time the guard request left
        self._guard_toggles: dict[int, int] = {}
        self.sdo.channels.clear()
        self.remote_outputs: dict[tuple[int, int], int] = {}          # (node, byte) → last OUT/OUTB value
        self.lcp_links: dict[int, int] = {}                           # LINKSYSVAR: parameter 19-xx → SYSVAR
        self._lcp_next = 0

    # --- identity and sending ---------------------------------------------------------------------------
    @property
    def node_id(self) -> int:
        """CANNR as it was when the controller was switched on: a changed 33-90 takes effect at the next power-up
        (decision K118; DG 10815-10819, like CANBAUD "restart the device")."""
        if self._node_id is None:
            self._node_id = self.controller.params.values.get(CANNR, 127)
        return self._node_id

    def power_on(self) -> None:
        """Switched off and on: boot-up again with the current CANNR; PDOs, heartbeat and the program's objects
        start from their defaults."""
        self._node_id = None
        self.nmt_state, self.heartbeat_ms, self.busy = BOOTUP, 0, True
        self.pdo = PdoEngine(self)
        self.sdo.channels.clear()
        self.program_started()

    def attach(self, bus: CanBus) -> None:
        """Join a shared bus (a Simulation's): frames then travel between the controllers on it."""
        self.bus.detach(self)
        self.bus, self.own_bus = bus, False
        bus.attach(self)

    def send(self, frame: CanFrame) -> None:
        self.bus.send(frame, self)

    # --- ticks ------------------------------------------------------------------------------------------
    def tick(self, now: int) -> None:
        if not (self.inbox or self.busy or self.heartbeat_ms or self.pdo.active or self.sdo.channels or
                (self.own_bus and (self.bus.pending or self.bus.injected))):
            return                                   # nothing to do: the common case costs one test per tick
        if self.own_bus:
            self.bus.deliver()
        if self.nmt_state == BOOTUP:                 # power-up: boot-up message, then OPERATIONAL (K105)
            self.send(CanFrame(0x700 + self.node_id, b"\x00"))
            self.nmt_state, self._last_heartbeat = OPERATIONAL, now
        if self.inbox:
            frames, self.inbox = self.inbox, []
            for frame in frames:
                self.receive(frame, now)
        if self.messages:                            # ON CANMSG: while a message waits (CR 2496-2497)
            self.controller.interrupts.fire("CANMSG")
        operational = self.nmt_state == OPERATIONAL
        if self.pdo.active:
            self.pdo.transmit(now, operational)
        if self.sdo.channels:
            self.sdo.expire(now)
        if self.heartbeat_ms and now - self._last_heartbeat >= self.heartbeat_ms:
            self._last_heartbeat = now
            self.send(CanFrame(0x700 + self.node_id, bytes([self.nmt_state])))
        if self.modules:
            self._guard(now)
        if self.lcp_links and now % LCP_PERIOD_MS == 0:
            self._refresh_lcp()
        self.busy = bool(self.modules or self.lcp_links or self.messages or self.nmt_state == BOOTUP)

    def _refresh_lcp(self) -> None:
        """LINKSYSVAR: one linked parameter shows its SYSVAR value every 40 ms, in turn (CR 2099-2102)."""

        numbers = sorted(self.lcp_links)
        number = numbers[self._lcp_next % len(numbers)]
        self._lcp_next += 1
        value = read_sysvar(self.controller, self.lcp_links[number])
        self.controller.params.values[number] = 0 if value is None else int(value)

    def receive(self, frame: CanFrame, now: int) -> None:
        can_id, node = frame.can_id, self.node_id
        if can_id == 0 and not frame.rtr and not frame.extended:
            self._identifier_zero(frame.data)
            return
        for box in self.mailboxes.values():          # the first mailbox with the id takes it (CR 401-409)
            if box.can_id != can_id:
                continue
            if box.receive and not frame.rtr:
                box.data, box.new = frame.data, True
                return
            if not box.receive and frame.rtr and box.sent:   # a transmit object answers a remote frame
                self.send(CanFrame(can_id, box.data))
                return
        if frame.extended:   # CANopen's services use base frames (CiA 301): a 29-bit frame is for mailboxes only
            return
        if self.capture is not None and 0x181 <= can_id <= 0x1FF and not frame.rtr:
            self.capture[can_id - 0x180] = (frame.data, True)
        if self.pdo.receive(frame, now, self.nmt_state == OPERATIONAL):
            return
        if can_id == 0x600 + node:
            if self.bus.kernel_sdo_servers and self.nmt_state != STOPPED:
                self.server.request(frame)
        elif 0x581 <= can_id <= 0x5FF:
            self.sdo.response(frame)
        elif can_id == 0x700 + node and frame.rtr:  # node guarding: the state with the toggle bit
            self.send(CanFrame(0x700 + node, bytes([self._guard_toggle << 7 | self.nmt_state])))
            self._guard_toggle ^= 1
        elif 0x701 <= can_id <= 0x77F and not frame.rtr:
            self._guard_pending.pop(can_id - 0x700, None)
        elif can_id == 2 * node + 1 and not frame.rtr:   # buffered RxMessage (DG 7299-7305)
            self.messages.append(bytes(frame.data).ljust(8, b"\0"))

    def _identifier_zero(self, data: bytes) -> None:
        """Identifier 0 carries NMT commands ([command, node]) and the global message, whose bytes 0-1 are 0
        (CR 2470-2476: "byte 0 and 1 may not be used and must set to 0")."""
        if len(data) >= 2 and data[0] != 0:
            if data[1] in (0, self.node_id) and data[0] in NMT_COMMANDS:
                self.nmt_state = NMT_COMMANDS[data[0]]
                self.busy = True                     # a reset boots up again at the next tick
                if data[0] in (RESET_NODE, RESET_COMMUNICATION):
                    # CiA 301: the communication objects (0x1000-0x1FFF: heartbeat 0x1017, the PDOs) take their
                    # power-on values again; RESET NODE also resets the application: the host powers the
                    # controller off and on (decision N51)
                    self.heartbeat_ms = 0
                    self.pdo = PdoEngine(self)
                    self.sdo.channels.clear()
                    for sub in (1, 2):   # SDO server 2 (0x1201): NOT_VALID again, its power-on value (N52)
                        self.controller.sysvar_memory.pop(sysvar_index(0x1201, sub), None)
                    self.reset_node_pending = data[0] == RESET_NODE
            return
        self.global_message, self.global_new = bytes(data).ljust(8, b"\0"), True
        self.controller.interrupts.fire("CANINPUT")

    # --- CANINI guarding ---------------------------------------------------------------------------------
    def register_modules(self, modules: list[int]) -> None:
        """CANINI: NMT start for every module, guarding for those given with a positive id (CR 436-492)."""
        if len(modules) > MAX_MODULES:
            raise ControllerError(102, f"CANINI with {len(modules)} modules (at most {MAX_MODULES})")
        self.modules = [m for m in modules if m > 0]
        self.busy = True
        self._guard_pending.clear()
        for module in modules:
            self.send(CanFrame(0, bytes([0x01, abs(module)])))

    def _guard(self, now: int) -> None:
        for node, sent in list(self._guard_pending.items()):
            if now - sent > GUARD_TIMEOUT_MS:
                self.guard_error_id = node
                self.modules = []                    # guarding stops with the error (one report)
                self._guard_pending.clear()
                self.controller.raise_error(ControllerError(188, f"node {node} did not answer node guarding"))
                return
        if now % GUARD_PERIOD_MS == 0 and self.modules:
            node = self.modules[self._guard_next % len(self.modules)]
            self._guard_next += 1
            self._guard_pending.setdefault(node, now)
            self.send(CanFrame(0x700 + node, rtr=True, dlc=1))

    # --- buffered and global messages ---------------------------------------------------------------------
    def take_message(self) -> int | None:
        """INMSG: bytes 2-3 of the oldest buffered message (MSGVAL gets bytes 4-7), or None."""
        if not self.messages:
            return None
        return self._unpack(self.messages.popleft())

    def take_global(self) -> int | None:
        """INGLB: bytes 2-3 of a global message that arrived since the last INGLB, or None."""
        if not self.global_new:
            return None
        self.global_new = False
        assert self.global_message is not None  # set with global_new
        return self._unpack(self.global_message)

    def _unpack(self, data: bytes) -> int:
        """Bytes 2-3 as an unsigned word, bytes 4-7 into MSGVAL; high byte first as in CANIN/CANOUT (K100)."""
        self.msgval = int.from_bytes(data[4:8], "big", signed=True)
        return int.from_bytes(data[2:4], "big")

    def send_message(self, word: int, value: int) -> None:
        """OUTMSG: a buffered TxMessage on CANNR * 2 (DG 7299-7305)."""
        data = bytes(2) + (int(word) & 0xFFFF).to_bytes(2, "big") + (int(value) & 0xFFFFFFFF).to_bytes(4, "big")
        self.send(CanFrame(2 * self.node_id, data))

    # --- raw mailboxes -----------------------------------------------------------------------------------
    def define_mailbox(self, can_id: int, length: int, receive: bool) -> int:
        if not 0 <= length <= 8:
            raise ControllerError(183, f"data length {length}: 0..8 bytes (CR 768)")
        can_id %= 100000            # "+100000" selects the slave bus; the simulation has one bus
        if not 0 <= can_id <= 0x7FF:
            raise ControllerError(183, f"CAN id {can_id}: 11-bit identifiers 0..2047")
        if len(self.mailboxes) >= MAX_MAILBOXES:
            return NO_CANMEMORY
        number = next(n for n in range(1, MAX_MAILBOXES + 2) if n not in self.mailboxes)
        self.mailboxes[number] = Mailbox(number, can_id, length, receive)
        return number

    def mailbox(self, number: int, receive: bool) -> Mailbox:
        box = self.mailboxes.get(number)
        if box is None or box.receive != receive:
            kind = "DEFCANIN" if receive else "DEFCANOUT"
            raise ControllerError(189, f"object {number} is no {kind} object (DG 11806)")
        return box

    def delete_mailbox(self, number: int) -> None:
        if number == -1:
            self.mailboxes.clear()
        else:
            self.mailboxes.pop(number, None)
