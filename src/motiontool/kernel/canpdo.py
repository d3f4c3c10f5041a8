"""PDOs of the simulated MCO: the PDO[] pseudo array, LINKPDO/LINKSDO mapping, CANopen mapping objects and
transmission (CR 1910-2092, 3298-3404; DG 7399-7428).

One 8-byte PDO array per PDO number (decision K104): a received RxPDO is copied into it ("The RxPDO is also copied
into the PDO array", CR 1959), the mapped values of a TxPDO are copied into it before it is sent ("The TxPDO is also
copied into the PDO array", CR 2051), and `PDO[n] = v` writes straight into it ("The command PDO writes directly in
the outgoing PDO", CR 3366). That is why `PDO[1].3 = 1` can read and write the same element, and why the manual
warns not to write bytes a mapping uses (CR 3379-3383). PDO 5, the "serial PDO" of up to ~250 bytes, is only an
array here: it travels over USB/RS232, not over CAN.

Only PDO 1 is valid at power-up; LINKPDO/LINKSDO and writes to sub 1 of 0x1400-0x1403/0x1800-0x1803 make the
others valid (CR 1962-1967, 3313-3321). A valid TxPDO is sent once something uses it (a mapping or a PDO[] write):
with transmission type 255 on every change and at least every event time (default 10 ms, CR 3359-3362); 254 only
on a remote request (CR 2060-2065: "the PDO has to be collected per remote frame"); 0-240 on SYNC. PDOs travel
only while the controller is OPERATIONAL; it enters that state by itself at power-up (decision K105).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from motiontool.kernel import objdict
from motiontool.kernel.canbus import CanFrame
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.sysvars import read_sysvar

CAN_PDOS = 4                 # PDO 1-4 on the CAN bus (0x1400-0x1403 … 0x1A00-0x1A03)
SERIAL_PDO = 5
PDO_BYTES, SERIAL_PDO_BYTES = 8, 252
DEFAULT_EVENT_MS = 10        # "Cyclical update of the parameter every 10 ms" (CR 3359)
NOT_VALID = 0x80000000
RTR_ONLY, ON_CHANGE = 254, 255


@dataclass
class MapEntry:
    target: int      # SYSVAR index: 0x01iiiiss maps an object (CANopen mapping), others APOSS mapping
    bits: int
    dummy: bool = False

    @property
    def canopen(self) -> bool:
        return self.target >> 24 == 1

    def mapping_value(self) -> int:
        """The entry as 0x1600/0x1A00 show it: index << 16 | sub << 8 | bits (APOSS mappings are invisible)."""
        if not self.canopen:
            return 0
        return ((self.target >> 8) & 0xFFFF) << 16 | (self.target & 0xFF) << 8 | (self.bits & 0xFF)


@dataclass
class Pdo:
    tx: bool
    number: int
    cob: int | None = None               # None: the default of the node id
    valid: bool = False
    type: int = ON_CHANGE
    inhibit: int = 0                     # 100 µs units
    event: int = DEFAULT_EVENT_MS        # ms, TxPDO only
    entries: dict[int, MapEntry] = field(default_factory=dict)   # rank (1..) → entry
    count: int = 0                       # sub 0 of the mapping object: ranks 1..count are in use
    used: bool = False                   # a PDO[] write made this TxPDO carry data
    layout: tuple | None = None          # ([(bit offset, bits, reader)], length): see PdoEngine.compose
    last_sent: int | None = None
    last_data: bytes | None = None
    pending: bool = False                # a change waits for the inhibit time
    syncs: int = 0

    def default_cob(self, node: int) -> int:
        return (0x180 if self.tx else 0x200) + 0x100 * (self.number - 1) + node

    def cob_id(self, node: int) -> int:
        return self.cob if self.cob is not None else self.default_cob(node)

    def in_use(self) -> bool:
        return self.count > 0 or self.used

    def mapped(self) -> list[tuple[int, MapEntry]]:
        """(bit offset, entry) for the ranks in use, in rank order."""
        result, offset = [], 0
        for rank in range(1, self.count + 1):
            entry = self.entries.get(rank)
            if entry is None:
                continue
            result.append((offset, entry))
            offset += entry.bits
        return result

    def mapped_bits(self) -> int:
        return sum(e.bits for e in (self.entries.get(r) for r in range(1, self.count + 1)) if e is not None)


class PdoEngine:
    """The PDOs of one controller (kernel/canport.py owns it as `port.pdo`)."""

    def __init__(self, port):
        self.port = port
        self.rx = {n: Pdo(False, n, valid=n == 1) for n in range(1, CAN_PDOS + 1)}
        self.tx = {n: Pdo(True, n, valid=n == 1) for n in range(1, CAN_PDOS + 1)}
        self.rx[SERIAL_PDO] = Pdo(False, SERIAL_PDO, valid=True)
        self.tx[SERIAL_PDO] = Pdo(True, SERIAL_PDO, valid=True)
        self.arrays = {n: bytearray(PDO_BYTES) for n in range(1, CAN_PDOS + 1)}
        self.arrays[SERIAL_PDO] = bytearray(SERIAL_PDO_BYTES)
        self.sync_id = 0x80
        self.active = False                 # a TxPDO may need sending: checked every tick
        self.received = 0

    # --- PDO[] --------------------------------------------------------------------------------------------
    @staticmethod
    def _element(index: int) -> tuple[int, int]:
        """PDO[n] → (PDO number, byte offset): 1/2 are PDO 1 (CR 3304), 1001… PDO 1, 2001… PDO 2 …"""
        if index in (1, 2):
            number, word = 1, index
        else:
            number, word = divmod(index, 1000)
        size = SERIAL_PDO_BYTES if number == SERIAL_PDO else PDO_BYTES
        if not 1 <= number <= SERIAL_PDO or not 1 <= word <= size // 4:
            raise ControllerError(171, f"PDO[{index}] does not exist (1001/1002 … 4001/4002, 5001 …)")
        return number, 4 * (word - 1)

    def read_element(self, index: int) -> int:
        number, offset = self._element(index)
        return int.from_bytes(self.arrays[number][offset:offset + 4], "little", signed=True)

    def write_element(self, index: int, value: int) -> None:
        number, offset = self._element(index)
        self.arrays[number][offset:offset + 4] = (int(value) & 0xFFFFFFFF).to_bytes(4, "little")
        if number <= CAN_PDOS and not self.tx[number].used:
            self.tx[number].used, self.tx[number].layout = True, None
            self.active = True

    # --- LINKPDO / LINKSDO -------------------------------------------------------------------------------------
    def link(self, tx: bool, number: int, rank: int, bits: int, target: int, dummy: bool = False) -> None:
        """LINKSDO/LINKPDO: map `bits` of SYSVAR[target] at `rank` of PDO `number` and make the PDO valid."""
        if not 1 <= number <= SERIAL_PDO:
            number = 1                      # "each PDO number out of range is handled like 1" (CR 1925-1930)
        if bits <= 0 or bits % 8:
            raise ControllerError(183, f"length {bits} bits: a multiple of 8 (CR 1918)")
        if rank < 1:
            raise ControllerError(183, f"rank {rank}: ranks begin with 1 (CR 1921)")
        pdo = (self.tx if tx else self.rx)[number]
        size = SERIAL_PDO_BYTES if number == SERIAL_PDO else PDO_BYTES
        entries = dict(pdo.entries)
        entries[rank] = MapEntry(target, bits, dummy)
        if sum(e.bits for e in entries.values()) > 8 * size:
            raise ControllerError(183, f"PDO {number} holds {size} bytes; the mapping needs more")
        where = objdict.split_sysvar(target)
        if where is not None and where[0] not in objdict.OBJECTS:
            raise ControllerError(183, f"SYSVAR[0x{target:08X}] is no object of the dictionary")
        pdo.entries = entries
        pdo.count = max(pdo.count, rank)
        pdo.valid = True
        pdo.layout = None
        self.active = True

    # --- ticks ---------------------------------------------------------------------------------------------
    def transmit(self, now: int, operational: bool) -> None:
        """Send the TxPDOs that are due this tick (type 255: change or event time)."""
        if not operational:
            return
        busy = False
        for number in range(1, CAN_PDOS + 1):
            pdo = self.tx[number]
            if not (pdo.valid and pdo.in_use()):
                continue
            busy = True
            if pdo.type != ON_CHANGE:
                continue
            data = self.compose(pdo)
            due = pdo.last_sent is None or pdo.pending or data != pdo.last_data or (
                pdo.event > 0 and now - pdo.last_sent >= pdo.event)
            if not due:
                continue
            if pdo.inhibit and pdo.last_sent is not None and (now - pdo.last_sent) * 10 < pdo.inhibit:
                pdo.pending = True
                continue
            self._send(pdo, data, now)
        self.active = busy

    def compose(self, pdo: Pdo) -> bytes:
        """The TxPDO's bytes: its PDO array with the mapped values written in (little-endian, CR 3389-3397).
        The layout (offsets and readers of the mapped objects) is worked out once per mapping: a Free Run sends
        four TxPDOs every millisecond."""
        if pdo.layout is None:
            items = [(offset, entry.bits, _reader(entry.target)) for offset, entry in pdo.mapped() if not entry.dummy]
            pdo.layout = (items, PDO_BYTES if pdo.used else min(PDO_BYTES, (pdo.mapped_bits() + 7) // 8))
        items, length = pdo.layout
        array = self.arrays[pdo.number]
        ctl = self.port.controller
        for offset, bits, read in items:
            _put_bits(array, offset, bits, read(ctl))
        return bytes(array[:length])

    def _send(self, pdo: Pdo, data: bytes, now: int) -> None:
        pdo.last_sent, pdo.last_data, pdo.pending = now, data, False
        self.port.send(CanFrame(pdo.cob_id(self.port.node_id), data))

    # --- reception -----------------------------------------------------------------------------------------
    def receive(self, frame: CanFrame, now: int, operational: bool) -> bool:
        """An RxPDO, a remote request for a TxPDO or a SYNC; True when the frame was one of those."""
        node = self.port.node_id
        if frame.can_id == self.sync_id and not frame.rtr:
            if operational:
                self._sync(now)
            return True
        for number in range(1, CAN_PDOS + 1):
            tpdo = self.tx[number]
            if frame.rtr and tpdo.valid and tpdo.cob_id(node) == frame.can_id:
                if operational:
                    self._send(tpdo, self.compose(tpdo), now)
                return True
            rpdo = self.rx[number]
            if not frame.rtr and rpdo.valid and rpdo.cob_id(node) == frame.can_id:
                if operational:
                    self._apply(rpdo, frame.data)
                return True
        return False

    def _sync(self, now: int) -> None:
        for number in range(1, CAN_PDOS + 1):
            pdo = self.tx[number]
            if not (pdo.valid and pdo.in_use()) or pdo.type > 240:
                continue
            data = self.compose(pdo)
            pdo.syncs += 1
            if (pdo.type == 0 and data != pdo.last_data) or (pdo.type and pdo.syncs >= pdo.type):
                pdo.syncs = 0
                self._send(pdo, data, now)

    def _apply(self, pdo: Pdo, data: bytes) -> None:
        """Copy a received RxPDO into its PDO array and its mapped SYSVAR elements (CR 1910-1916)."""
        self.received += 1
        array = self.arrays[pdo.number]
        array[:len(data)] = data
        ctl = self.port.controller
        for offset, entry in pdo.mapped():
            if entry.dummy or offset + entry.bits > 8 * len(data):
                continue
            for target, bits, at in _pieces(entry, offset):
                value = _get_bits(array, at, bits, _signed(target, bits))
                _write_target(ctl, target, value)


# --- mapping helpers ------------------------------------------------------------------------------------------
def _pieces(entry: MapEntry, offset: int):
    """An entry split into objects: more bits than the object holds fill the next sub-indices ("LINKPDO 1 320
    0x01210005 0 // the first ten longs of the PDO are linked into the first ten elements", CR 2788-2792)."""
    where = objdict.split_sysvar(entry.target)
    size = 32
    if where is not None:
        try:
            size = 8 * objdict.DATATYPES[objdict.find(*where).datatype][1] or 32
        except objdict.ObjectError:
            size = 32
    if entry.bits <= size:
        return [(entry.target, entry.bits, offset)]
    return [(entry.target + k, size, offset + k * size) for k in range(entry.bits // size)]


def _signed(target: int, bits: int) -> bool:
    if bits >= 32:
        return True
    where = objdict.split_sysvar(target)
    if where is None:
        return False
    try:
        entry = objdict.find(*where)
    except objdict.ObjectError:
        return False
    _, size, signed = objdict.DATATYPES[entry.datatype]
    return signed and 8 * size == bits


def _reader(target: int):
    """A function controller → value of SYSVAR[target], resolved once (an object's getter, else read_sysvar)."""
    where = objdict.split_sysvar(target)
    try:
        get = objdict.find(*where).get if where is not None else None
    except objdict.ObjectError:
        get = None
    if get is None:
        return lambda ctl: _read_target(ctl, target)

    def read(ctl) -> int:
        try:
            return int(get(ctl))
        except (ControllerError, objdict.ObjectError, TypeError, ValueError):
            return 0
    return read


def _read_target(ctl, target: int) -> int:

    try:
        value = read_sysvar(ctl, target)
    except ControllerError:
        value = 0
    return 0 if value is None else int(value)


def _write_target(ctl, target: int, value: int) -> None:
    where = objdict.split_sysvar(target)
    if where is None:                        # APOSS mapping: any SYSVAR element (CR 1969-1977)
        ctl.write_pseudo(0, target, value)
        return
    try:
        if objdict.read(ctl, *where) != value:   # ON PARAM "each time it changes" (CR 2779-2810, C15 example)
            objdict.write(ctl, where[0], where[1], value, source="pdo")
    except objdict.ObjectError:
        pass                                 # a PDO cannot be refused; the value is dropped


def _put_bits(array: bytearray, offset: int, bits: int, value: int) -> None:
    if offset % 8 == 0 and bits % 8 == 0:
        array[offset // 8:(offset + bits) // 8] = (value & ((1 << bits) - 1)).to_bytes(bits // 8, "little")
        return
    whole = int.from_bytes(array, "little")
    mask = ((1 << bits) - 1) << offset
    whole = (whole & ~mask) | ((value << offset) & mask)
    array[:] = whole.to_bytes(len(array), "little")


def _get_bits(array: bytes, offset: int, bits: int, signed: bool) -> int:
    value = (int.from_bytes(array, "little") >> offset) & ((1 << bits) - 1)
    if signed and value >> (bits - 1):
        value -= 1 << bits
    return value


# --- the communication and mapping objects (kernel/objdict.py) --------------------------------------------------
def accessor(tx: bool, number: int, what: str, rank: int = 0) -> tuple[objdict.Getter, objdict.Setter]:
    """(get, put) of one sub-object of 0x1400/0x1600/0x1800/0x1A00 for PDO `number`."""
    def pdo(c) -> Pdo:
        return (c.can.pdo.tx if tx else c.can.pdo.rx)[number]

    if what == "cob":
        def get(c):
            p = pdo(c)
            return p.cob_id(c.can.node_id) | (0 if p.valid else NOT_VALID)

        def put(c, value, source):
            p, value = pdo(c), int(value) & 0xFFFFFFFF
            p.valid = not value & NOT_VALID
            cob = value & 0x7FF
            p.cob = None if cob == p.default_cob(c.can.node_id) else cob
            c.can.pdo.active = True
        return get, put
    if what == "map":
        def get(c):
            entry = pdo(c).entries.get(rank)
            return 0 if entry is None else entry.mapping_value()

        def put(c, value, source):
            value = int(value) & 0xFFFFFFFF
            index, sub, bits = value >> 16, (value >> 8) & 0xFF, value & 0xFF
            pdo(c).layout = None
            if value == 0:
                pdo(c).entries.pop(rank, None)
                return
            try:
                entry = objdict.find(index, sub)
            except objdict.ObjectError:
                raise objdict.ObjectError(objdict.ABORT_NOT_MAPPABLE, f"0x{index:04X}/{sub} does not exist") \
                    from None
            if not entry.mappable or objdict.DATATYPES[entry.datatype][1] * 8 != bits:
                raise objdict.ObjectError(objdict.ABORT_NOT_MAPPABLE,
                                          f"0x{index:04X}/{sub} cannot be mapped with {bits} bits")
            pdo(c).entries[rank] = MapEntry(objdict.sysvar_index(index, sub), bits)
        return get, put
    if what == "count":
        def put_count(c, value, source):
            p, value = pdo(c), int(value)
            if not 0 <= value <= 8:
                raise objdict.ObjectError(objdict.ABORT_VALUE, f"{value} mapped objects: 0..8")
            if sum(p.entries[r].bits for r in range(1, value + 1) if r in p.entries) > 8 * PDO_BYTES:
                raise objdict.ObjectError(objdict.ABORT_PDO_LENGTH, "the mapped objects exceed 8 bytes")
            p.count, p.layout = value, None
            c.can.pdo.active = True
        return (lambda c: pdo(c).count), put_count
    attribute = {"type": "type", "inhibit": "inhibit", "event": "event"}[what]

    def put_attribute(c, value, source):
        setattr(pdo(c), attribute, int(value))
        pdo(c).syncs = 0
        c.can.pdo.active = True
    return (lambda c: getattr(pdo(c), attribute)), put_attribute


def _register_objects() -> None:
    """0x1400/0x1600 (RxPDO 1-4) and 0x1800/0x1A00 (TxPDO 1-4) in the object dictionary."""
    entry, record = objdict.Entry, objdict.record
    for n in range(1, CAN_PDOS + 1):
        for tx in (False, True):
            comm, mapping = (0x1800 + n - 1, 0x1A00 + n - 1) if tx else (0x1400 + n - 1, 0x1600 + n - 1)
            base = (0x180 if tx else 0x200) + 0x100 * (n - 1) + (0 if n == 1 else NOT_VALID)
            label = "TPDO" if tx else "RPDO"
            subs = [entry(comm, 1, "COB-ID used by PDO", "UNSIGNED32", "rw", *accessor(tx, n, "cob"),
                          default=f"$NODEID+0x{base:X}", mappable=False),
                    entry(comm, 2, "Transmission type", "UNSIGNED8", "rw", *accessor(tx, n, "type"),
                          default=ON_CHANGE, mappable=False)]
            if tx:
                subs += [entry(comm, 3, "Inhibit time", "UNSIGNED16", "rw", *accessor(tx, n, "inhibit"), default=0,
                               mappable=False),
                         entry(comm, 5, "Event timer", "UNSIGNED16", "rw", *accessor(tx, n, "event"),
                               default=DEFAULT_EVENT_MS, mappable=False)]
            record(comm, f"{label} {n} communication parameter", subs)
            count = entry(mapping, 0, "Number of mapped objects", "UNSIGNED8", "rw", *accessor(tx, n, "count"),
                          default=0, mappable=False)
            maps = [entry(mapping, k, f"Mapped object {k}", "UNSIGNED32", "rw", *accessor(tx, n, "map", k),
                          default=0, mappable=False) for k in range(1, 9)]
            objdict.OBJECTS[mapping] = objdict.Obj(mapping, f"{label} {n} mapping parameter", "RECORD",
                                                   {0: count, **{e.sub: e for e in maps}})


_register_objects()
