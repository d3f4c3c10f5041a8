"""The APOSS CAN commands on the simulated controller (DG 7274-7428; CR DEFCANIN … SDOWRITE, LINKPDO, LINKSDO):
raw telegrams (DEFCANIN/DEFCANOUT/CANIN/CANOUT/CANDEL), buffered and global messages (OUTMSG/INMSG/INGLB/MSGVAL,
ON CANMSG/ON CANINPUT through kernel/interrupts.py), the CANopen master (CANINI, SDOREAD/SDOWRITE/SDOREADSEG(P)/
SDOSTATE, IN/OUT/INB/OUTB/INAD/OUTDA on CAN I/O above 256) and the CANopen slave (LINKPDO, LINKSDO, LINKSYSVAR).

Byte order (decision K100): CANIN/CANOUT and the buffered messages put the first byte of the telegram in the high
byte of varhi ("High to low … for low-level commands such as CANIN and CANOUT", DG 5526); PDO[], LINKPDO/LINKSDO
and CANIN (id*100) are CANopen's low-to-high (CR 404-406, 3389-3397).
"""

from __future__ import annotations

from motiontool.kernel.canbus import CanFrame
from motiontool.kernel.cansdo import SdoWait, Transfer
from motiontool.kernel.command_base import COMMANDS, command
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.vm import Wait

CAN_IO_BASE = 256          # IN/OUT numbers above 256 are CAN I/O: node * 256 + number (DG 7363-7365)
CAPTURE = 999              # CANINI 999 (CR 380-420)


class Poll(Wait):
    """Wait until `take()` gives a value, at most `timeout` ms: < 0 not at all, 0 for ever (CR 366-431, 1677)."""

    def __init__(self, ctl, take, timeout: int, failed: int = -1):
        self.take, self.failed = take, failed
        self.deadline = None if timeout == 0 else ctl.time_ms + max(timeout, 0)
        self.ctl = ctl

    def done(self) -> bool:
        value = self.take()
        if value is not None:
            self.value = value
            return True
        if self.deadline is not None and self.ctl.time_ms >= self.deadline:
            self.value = self.failed
            return True
        return False


# --- raw telegrams ------------------------------------------------------------------------------------------------
@command("DEFCANIN")
def defcanin(ctl, vm, args):
    return ctl.can.define_mailbox(args[0], args[1], receive=True)


@command("DEFCANOUT")
def defcanout(ctl, vm, args):
    return ctl.can.define_mailbox(args[0], args[1], receive=False)


@command("CANDEL")
def candel(ctl, vm, args):
    ctl.can.delete_mailbox(args[0])


@command("CANOUT")
def canout(ctl, vm, args):
    box = ctl.can.mailbox(args[0], receive=False)
    box.data, box.sent = _high_first(args[1], args[2])[:box.length], True
    ctl.can.send(CanFrame(box.can_id, box.data))


@command("CANIN")
def canin(ctl, vm, args):
    objno, timeout, control, hi, lo = args
    port = ctl.can
    if objno >= 100 and objno % 100 == 0:        # CANIN (id * 100): TxPDO1 of node id after CANINI 999
        return _captured_pdo(ctl, objno // 100, timeout, hi, lo)
    box = port.mailbox(objno, receive=True)
    if control == 1:                              # remote frame first (CR 371)
        port.send(CanFrame(box.can_id, rtr=True, dlc=box.length))

    def take():
        if not box.new:
            return None
        box.new = False
        hi.set(int.from_bytes(box.data[0:4].ljust(4, b"\0"), "big", signed=True))
        lo.set(int.from_bytes(box.data[4:8].ljust(4, b"\0"), "big", signed=True))
        return 0
    return Poll(ctl, take, timeout)


def _captured_pdo(ctl, node: int, timeout: int, hi, lo):
    port = ctl.can
    if port.capture is None:
        raise ControllerError(189, f"CANIN ({node}*100) needs CANINI 999 first (CR 388-391)")

    def take():
        data, new = port.capture.get(node, (b"", False))
        if not new:
            return None
        port.capture[node] = (data, False)
        padded = bytes(data).ljust(8, b"\0")
        hi.set(int.from_bytes(padded[0:4], "little", signed=True))
        lo.set(int.from_bytes(padded[4:8], "little", signed=True))
        return 0
    return Poll(ctl, take, timeout)


def _high_first(hi: int, lo: int) -> bytes:
    return (int(hi) & 0xFFFFFFFF).to_bytes(4, "big") + (int(lo) & 0xFFFFFFFF).to_bytes(4, "big")


# --- buffered and global messages ----------------------------------------------------------------------------------
@command("OUTMSG")
def outmsg(ctl, vm, args):
    ctl.can.send_message(args[0], args[1])


@command("INMSG")
def inmsg(ctl, vm, args):
    return Poll(ctl, ctl.can.take_message, args[0])


@command("INGLB")
def inglb(ctl, vm, args):
    return Poll(ctl, ctl.can.take_global, args[0])


COMMANDS["MSGVAL"] = lambda ctl, vm, args: ctl.can.msgval


@command("USRSTAT")
def usrstat(ctl, vm, args):
    ctl.can.user_status = args[0]


# --- CANopen master ------------------------------------------------------------------------------------------------
@command("CANINI")
def canini(ctl, vm, args):
    port = ctl.can
    port.capture = {} if CAPTURE in args else None   # every CANINI replaces the previous set-up (CR 444-448)
    modules = []
    for value in args:
        if value in (0, CAPTURE):
            continue
        node = abs(value) % 100000
        if not 1 <= node <= 127:
            raise ControllerError(183, f"CANINI {value}: node ids 1..127, negative without guarding")
        modules.append(node if value > 0 else -node)
    port.register_modules(modules)


def _sdo(ctl, vm, kind: str, node: int, index: int, sub: int, value: int = 0, array=None):
    """Start a transfer; a negative id does not wait (SDOSTATE gives the result, CR 3699-3703)."""
    if not 0 <= index <= 0xFFFF or not 0 <= sub <= 0xFF:
        raise ControllerError(183, f"object 0x{index:X}/{sub}: index 0..0xFFFF, sub-index 0..0xFF")
    waiting = node > 0
    transfer = ctl.can.sdo.start(Transfer(abs(node), kind, index, sub, value, array, waiting))
    if not waiting:
        return 0
    return SdoWait(vm, ctl.can.sdo, transfer, returns_value=kind != "write")


@command("SDOREAD")
def sdoread(ctl, vm, args):
    return _sdo(ctl, vm, "read", args[0], args[1], args[2])


@command("SDOWRITE")
def sdowrite(ctl, vm, args):
    return _sdo(ctl, vm, "write", args[0], args[1], args[2], value=args[3])


def _fc_parameter_object(index: int, sub: int) -> tuple[int, int]:
    """CR 3716-3717, 3762-3763: "index = 0x2000  subindex = parameter number". A parameter number that cannot be a
    sub-index (above 0xFF, the C23 example's 1549) addresses object 0x2000 + number, sub 0: the form of the C24
    example (CR 3800 `(0x2000 + para), 0`) and of the FC 300 on CANopen (K116)."""
    return (0x2000 + sub, 0) if index == 0x2000 and sub > 0xFF else (index, sub)


@command("SDOREADSEG")
def sdoreadseg(ctl, vm, args):
    return _sdo(ctl, vm, "seg", args[0], *_fc_parameter_object(args[1], args[2]), array=args[3])


@command("SDOREADSEGP")
def sdoreadsegp(ctl, vm, args):
    return _sdo(ctl, vm, "segp", args[0], *_fc_parameter_object(args[1], args[2]), array=args[3])


@command("SDOSTATE")
def sdostate(ctl, vm, args):
    state, value = ctl.can.sdo.state(args[0])
    args[1].set(value)
    return state


# --- CAN I/O: IN/OUT … above 256 (DG 7363-7365, 7384-7391) -----------------------------------------------------------
class _IoWait(SdoWait):
    """An SDO of a CAN I/O command whose answer is turned into the command's value."""

    def __init__(self, vm, client, transfer, convert):
        super().__init__(vm, client, transfer, returns_value=convert is not None)
        self.convert = convert

    def done(self) -> bool:
        if not super().done():
            return False
        if self.convert is not None:
            self.value = self.convert(self.value)
        return True


def _can_io(number: int) -> tuple[int, int]:
    """bus + node * 256 + n → (node, n); the slave bus (+100000) is the same bus here."""
    node, n = divmod(number % 100000, CAN_IO_BASE)
    if not 1 <= node <= 127:
        raise ControllerError(183, f"CAN I/O {number}: node {node} outside 1..127")
    return node, n


def _io_transfer(ctl, vm, node, kind, index, sub, value=0, convert=None):
    transfer = ctl.can.sdo.start(Transfer(node, kind, index, sub, value))
    return _IoWait(vm, ctl.can.sdo, transfer, convert)


def _wrap(name: str, can_io):
    """Keep the command for local I/O, send numbers above 256 to the CAN I/O module."""
    local = COMMANDS[name]

    def dispatch(ctl, vm, args):
        number = args[0]
        if isinstance(number, int) and number > CAN_IO_BASE:
            return can_io(ctl, vm, *_can_io(number), args[1:])
        return local(ctl, vm, args)
    COMMANDS[name] = dispatch


def _can_in(ctl, vm, node, n, rest):         # DS401 0x6000: inputs by bytes
    byte, bit = divmod(n - 1, 8)
    return _io_transfer(ctl, vm, node, "read", 0x6000, byte + 1, convert=lambda v: (v >> bit) & 1)


def _can_inb(ctl, vm, node, n, rest):
    return _io_transfer(ctl, vm, node, "read", 0x6000, n + 1, convert=lambda v: v & 0xFF)


def _can_out(ctl, vm, node, n, rest):        # DS401 0x6200; the other outputs of the byte as last written
    byte, bit = divmod(n - 1, 8)
    outputs = ctl.can.remote_outputs
    level = 1 if rest[0] in (1, "ON") else 0
    value = (outputs.get((node, byte), 0) & ~(1 << bit)) | (level << bit)
    outputs[(node, byte)] = value
    return _io_transfer(ctl, vm, node, "write", 0x6200, byte + 1, value)


def _can_outb(ctl, vm, node, n, rest):
    ctl.can.remote_outputs[(node, n)] = rest[0] & 0xFF
    return _io_transfer(ctl, vm, node, "write", 0x6200, n + 1, rest[0] & 0xFF)


def _can_inad(ctl, vm, node, n, rest):       # DS401 0x6401 analog inputs, 0x6411 analog outputs
    return _io_transfer(ctl, vm, node, "read", 0x6401, n, convert=lambda v: (v & 0xFFFF) - ((v & 0x8000) << 1))


def _can_outda(ctl, vm, node, n, rest):
    return _io_transfer(ctl, vm, node, "write", 0x6411, n, rest[0])


for _name, _handler in (("IN", _can_in), ("INB", _can_inb), ("OUT", _can_out), ("OUTB", _can_outb),
                        ("INAD", _can_inad), ("OUTDA", _can_outda)):
    _wrap(_name, _handler)


# --- CANopen slave: PDO mapping ------------------------------------------------------------------------------------
@command("LINKPDO")
def linkpdo(ctl, vm, args):
    rank, bits, target, pdo = args
    ctl.can.pdo.link(False, pdo, rank, bits, target)


@command("LINKSDO")
def linksdo(ctl, vm, args):
    target, bits, rank, _text, pdo = args
    ctl.can.pdo.link(True, abs(pdo), rank, bits, target, dummy=pdo < 0)   # -pdo: dummy entry (DG 7423)


@command("LINKSYSVAR")
def linksysvar(ctl, vm, args):
    index, number, _text = args
    if not 1900 <= number <= 1999:
        raise ControllerError(155, f"LINKSYSVAR {number}: only 19-00 … 19-99 can be linked (CR 2098)")
    ctl.can.lcp_links[number] = index
    ctl.can.busy = True

