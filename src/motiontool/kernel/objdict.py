"""The controller's CANopen object dictionary ("SDO dictionary", DG 7399-7428, CR 1910-2092, 3298-3404).

One table serves every way in: SYSVAR[0x01000000 + (index << 8) + sub] in programs (CR 2039), the SDO servers
(the kernel's own, kernel/cansdo.py, and the virtual drive's python-canopen LocalNodes), PDO mapping (LINKPDO,
LINKSDO, 0x1600/0x1A00) and the EDS the drive ships (controller/canopen/eds.py writes it from `OBJECTS`).
docs/protocols/canopen.md lists the objects; the manual's fixed points are 0x1201 (SDO2, DG 7317-7349), 0x1400 /
0x1600 / 0x1800 / 0x1A00 (PDOs, CR 3313-3388), 0x2100 (arrays, first element at sub 5, CR 2042-2044, 2793-2797),
0x2201 (user parameters, CR 1986), 0x2202 (system process data, CR 1988-1990, 2085-2088), 0x2300 sub 2 (VELMAX,
CR 3887), 0x23FF (whole arrays, CR 2806), 0x2500 (axis process data, CR 2040, 2083) and the DS402 objects the
manual's examples use (0x6040/0x6041/0x6060/0x6061, CR 1993, 2089-2092, 2825). The rest is ours (decisions N1-N9):
every MCO parameter at 0x2000 + its number (the FC 300 convention the SDOREADSEGP example uses, CR 3800), the
link's signals at 0x2510, DS401 I/O at 0x6000/0x6200/0x6401/0x6411 so that one simulated MCO is the other's CAN
I/O module (IN/OUT n > 256, DG 7363-7365).

Values are Python ints (integer types), str (VISIBLE_STRING) or bytes (DOMAIN); `encode`/`decode` give the
little-endian CANopen bytes. The PDO objects (0x1400-0x1A03) are the PDO engine's: kernel/canpdo.py adds them to
`OBJECTS` when it is loaded (kernel/canport.py loads it), so this module imports nothing of the CAN engines.
"""

from __future__ import annotations

import struct
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from motiontool.kernel import sysvars
from motiontool.kernel.errors import ControllerError
from motiontool.paramdb import database

# CiA 301 data types: name → (EDS code, bytes or 0 for variable length, signed)
DATATYPES: dict[str, tuple[int, int, bool]] = {
    "BOOLEAN": (0x0001, 1, False), "INTEGER8": (0x0002, 1, True), "INTEGER16": (0x0003, 2, True),
    "INTEGER32": (0x0004, 4, True), "UNSIGNED8": (0x0005, 1, False), "UNSIGNED16": (0x0006, 2, False),
    "UNSIGNED32": (0x0007, 4, False), "VISIBLE_STRING": (0x0009, 0, False), "DOMAIN": (0x000F, 0, False),
}
PARAMETER_TYPES = {"Int8": "INTEGER8", "Int16": "INTEGER16", "Int32": "INTEGER32", "Uint8": "UNSIGNED8",
                   "Uint16": "UNSIGNED16", "Uint32": "UNSIGNED32"}

# SDO abort codes (CiA 301 7.2.4.3.17)
ABORT_TOGGLE = 0x05030000
ABORT_TIMEOUT = 0x05040000
ABORT_COMMAND = 0x05040001
ABORT_WRITE_ONLY = 0x06010001
ABORT_READ_ONLY = 0x06010002
ABORT_NO_OBJECT = 0x06020000
ABORT_NOT_MAPPABLE = 0x06040041
ABORT_PDO_LENGTH = 0x06040042
ABORT_LENGTH = 0x06070010
ABORT_NO_SUB = 0x06090011
ABORT_VALUE = 0x06090030
ABORT_STORE = 0x08000020
ABORT_STATE = 0x08000022
ABORT_NO_DATA = 0x08000024

SYSVAR_OBJECT = 0x01000000   # SYSVAR index of an object: 0x01000000 + (index << 8) + sub (CR 2039)
ARRAY_BASE, ARRAY_OBJECTS = 0x2100, 256   # 0x2100 + k: array k + 1, its first 250 elements
ARRAY_FIRST_SUB, ARRAY_ELEMENTS = 5, 250  # "SDO 0x2100 / 5 (= … the first element of the first array)"
PARAMETER_BASE = 0x2000                    # parameter xx-yy at 0x2000 + xxyy, sub 0
TIME_STAMP_SUB = 0xF0                      # 0x2500 sub 0xF0: the controller clock's low 16 bits (PDO time stamps)


class ObjectError(Exception):
    """An access the dictionary refuses; `code` is the SDO abort code."""

    def __init__(self, code: int, text: str = ""):
        super().__init__(text or f"SDO abort 0x{code:08X}")
        self.code = code


def sysvar_index(index: int, sub: int) -> int:
    return SYSVAR_OBJECT + (index << 8) + sub


def split_sysvar(value: int) -> tuple[int, int] | None:
    """SYSVAR index → (object index, sub), or None if it is not an object index (0x01iiiiss)."""
    if value >> 24 != 1:
        return None
    return (value >> 8) & 0xFFFF, value & 0xFF


# --- values ↔ bytes --------------------------------------------------------------------------------------------
def encode(value: Any, datatype: str) -> bytes:
    """A value as the object's little-endian bytes; integers wrap to the type's width (SET does not check
    ranges, DG 7782-7795, so a parameter can hold more than its type)."""
    _, size, _ = DATATYPES[datatype]
    if datatype == "VISIBLE_STRING":
        return str(value).encode("latin-1", "replace")
    if datatype == "DOMAIN":
        return bytes(value)
    return (int(value) & ((1 << (8 * size)) - 1)).to_bytes(size, "little")


def decode(data: bytes, datatype: str) -> Any:
    """Bytes → value; an integer object accepts 1..its size bytes (an MCO's SDOWRITE always sends four, DG
    7382: the value must fit the type)."""
    _, size, signed = DATATYPES[datatype]
    if datatype == "VISIBLE_STRING":
        return bytes(data).decode("latin-1")
    if datatype == "DOMAIN":
        return bytes(data)
    if not data:
        raise ObjectError(ABORT_LENGTH, "no data for an integer object")
    value = int.from_bytes(bytes(data), "little", signed=signed and len(data) == size)
    if len(data) > size:
        value = int.from_bytes(bytes(data), "little", signed=True)
        if not fits(value, datatype):
            raise ObjectError(ABORT_LENGTH, f"{len(data)} bytes for a {datatype}")
    return value


def fits(value: int, datatype: str) -> bool:
    _, size, signed = DATATYPES[datatype]
    bits = 8 * size
    return (-(1 << (bits - 1)) <= value < (1 << (bits - 1))) if signed else (0 <= value < (1 << bits)) or (
        size == 4 and -(1 << 31) <= value < 0)   # a LONG written into an UNSIGNED32 (APOSS has no unsigned)


# --- the dictionary ---------------------------------------------------------------------------------------------
Getter = Callable[[Any], Any]                  # controller → value
Setter = Callable[[Any, Any, str], None]       # (controller, value, source) → None


@dataclass(frozen=True)
class Entry:
    """One object or sub-object."""

    index: int
    sub: int
    name: str
    datatype: str
    access: str                     # ro | rw | wo | const
    get: Getter | None = None
    put: Setter | None = None
    default: Any = None             # the EDS DefaultValue ("$NODEID+0x180" allowed)
    mappable: bool = True

    @property
    def readable(self) -> bool:
        return self.access != "wo"

    @property
    def writable(self) -> bool:
        return self.access in ("rw", "wo")


@dataclass
class Obj:
    """An object: VAR (entry at sub 0), RECORD (named subs) or ARRAY; a compact ARRAY has `count` subs of one
    kind built by `element(sub)` (EDS CompactSubObj)."""

    index: int
    name: str
    kind: str                                       # VAR | RECORD | ARRAY
    entries: dict[int, Entry] = field(default_factory=dict)
    count: int = 0                                  # compact ARRAY: subs 1..count
    element: Callable[[int], Entry] | None = None

    def entry(self, sub: int) -> Entry:
        found = self.entries.get(sub)
        if found is not None:
            return found
        if self.element is not None and 1 <= sub <= self.count:
            return self.element(sub)
        raise ObjectError(ABORT_NO_SUB, f"0x{self.index:04X} has no sub-index {sub}")


OBJECTS: dict[int, Obj] = {}


def _var(index: int, name: str, datatype: str, access: str, get: Getter | None = None, put: Setter | None = None,
         default: Any = None, mappable: bool = True) -> None:
    OBJECTS[index] = Obj(index, name, "VAR", {0: Entry(index, 0, name, datatype, access, get, put, default,
                                                       mappable)})


def record(index: int, name: str, subs: list[Entry], kind: str = "RECORD") -> None:
    top = max(e.sub for e in subs)
    count = Entry(index, 0, "Highest sub-index supported", "UNSIGNED8", "const", lambda c: top, default=top,
                  mappable=False)
    OBJECTS[index] = Obj(index, name, kind, {0: count, **{e.sub: e for e in subs}})


def find(index: int, sub: int) -> Entry:
    obj = OBJECTS.get(index)
    if obj is None:
        raise ObjectError(ABORT_NO_OBJECT, f"no object 0x{index:04X}")
    return obj.entry(sub)


def read(controller, index: int, sub: int) -> Any:
    """The value of index/sub as the SDO server and SYSVAR see it; ObjectError with an abort code."""
    entry = find(index, sub)
    if not entry.readable or entry.get is None:
        raise ObjectError(ABORT_WRITE_ONLY, f"0x{index:04X}/{sub} is write-only")
    try:
        return entry.get(controller)
    except ControllerError as exc:
        raise ObjectError(ABORT_NO_DATA, str(exc)) from None


def write(controller, index: int, sub: int, value: Any, source: str = "sdo") -> None:
    """Write index/sub. `source` "program" (SYSVAR[…] = v) does not fire ON PARAM; "sdo" and "pdo" do, for the
    object's SYSVAR index (CR 2779-2810: "active if the array element is written by an incoming PDO or by an
    SDO write")."""
    entry = find(index, sub)
    if not entry.writable or entry.put is None:
        raise ObjectError(ABORT_READ_ONLY, f"0x{index:04X}/{sub} is read-only")
    if isinstance(value, int) and entry.datatype in DATATYPES and DATATYPES[entry.datatype][1] \
            and not fits(value, entry.datatype):
        raise ObjectError(ABORT_VALUE, f"{value} does not fit {entry.datatype}")
    try:
        entry.put(controller, value, source)
    except ControllerError as exc:
        raise ObjectError(ABORT_READ_ONLY if exc.number == 112 else ABORT_VALUE, str(exc)) from None
    if source != "program" and index != 0x23FF:  # CR 2806: a whole-array write does not fire ON PARAM
        controller.interrupts.fire_param(sysvar_index(index, sub))


def read_sysvar(controller, value: int) -> int | None:
    """SYSVAR[0x01iiiiss] of an integer object, or None when the dictionary has no such object."""
    where = split_sysvar(value)
    if where is None or where[0] not in OBJECTS:
        return None
    try:
        result = read(controller, *where)
    except ObjectError:
        return None
    return result if isinstance(result, int) else 0


def write_sysvar(controller, value: int, new: int) -> bool:
    """SYSVAR[0x01iiiiss] = new from a program; False when the index is no object. A read-only object refuses
    with error 183."""
    where = split_sysvar(value)
    if where is None or where[0] not in OBJECTS:
        return False
    try:
        entry = find(*where)
        if entry.put is None or entry.access == "const":
            raise ControllerError(183, f"SYSVAR[0x{value:08X}] is read-only")
        entry.put(controller, int(new), "program")
    except ObjectError as exc:
        raise ControllerError(183, str(exc)) from None
    return True


# --- the objects ------------------------------------------------------------------------------------------------
def _memory(key: int, default: int = 0) -> tuple[Getter, Setter]:
    """An object that is plain storage (DS402 words the application interprets, CR 1993, 2089-2092)."""
    return (lambda c: c.sysvar_memory.get(key, default),
            lambda c, v, s: c.sysvar_memory.__setitem__(key, int(v)))


def _communication_objects() -> None:
    _var(0x1000, "Device type", "UNSIGNED32", "ro", lambda c: 0, default=0, mappable=False)
    _var(0x1001, "Error register", "UNSIGNED8", "ro", lambda c: 1 if c.error else 0)
    _var(0x1005, "COB-ID SYNC", "UNSIGNED32", "rw", lambda c: c.can.pdo.sync_id,
         lambda c, v, s: setattr(c.can.pdo, "sync_id", int(v) & 0x7FF), default=0x80, mappable=False)
    _var(0x1008, "Manufacturer device name", "VISIBLE_STRING", "const", lambda c: "MCO 305 (simulated)",
         default="MCO 305 (simulated)")
    _var(0x1009, "Manufacturer hardware version", "VISIBLE_STRING", "const", lambda c: "motiontool",
         default="motiontool")
    _var(0x100A, "Manufacturer software version", "VISIBLE_STRING", "const", lambda c: "MCO 5.00",
         default="MCO 5.00")
    _var(0x100C, "Guard time", "UNSIGNED16", "rw", *_memory(sysvar_index(0x100C, 0)), default=0, mappable=False)
    _var(0x100D, "Life time factor", "UNSIGNED8", "rw", *_memory(sysvar_index(0x100D, 0)), default=0, mappable=False)
    record(0x1010, "Store parameters", [Entry(0x1010, 1, "Save all parameters", "UNSIGNED32", "rw",
                                               lambda c: 1, _store, default=1, mappable=False)])
    record(0x1011, "Restore default parameters", [Entry(0x1011, 1, "Restore all default parameters",
                                                         "UNSIGNED32", "rw", lambda c: 1, _restore, default=1,
                                                         mappable=False)])
    _var(0x1017, "Producer heartbeat time", "UNSIGNED16", "rw", lambda c: c.can.heartbeat_ms,
         lambda c, v, s: setattr(c.can, "heartbeat_ms", int(v)), default=0, mappable=False)
    record(0x1018, "Identity object", [
        Entry(0x1018, 1, "Vendor-ID", "UNSIGNED32", "ro", lambda c: 0, default=0, mappable=False),
        Entry(0x1018, 2, "Product code", "UNSIGNED32", "ro", lambda c: 305, default=305, mappable=False),
        Entry(0x1018, 3, "Revision number", "UNSIGNED32", "ro", lambda c: 0x00050000, default=0x00050000,
              mappable=False),
        Entry(0x1018, 4, "Serial number", "UNSIGNED32", "ro", lambda c: c.can.node_id, default="$NODEID+0",
              mappable=False)])
    record(0x1200, "SDO server parameter", [
        Entry(0x1200, 1, "COB-ID client to server", "UNSIGNED32", "ro", lambda c: 0x600 + c.can.node_id,
              default="$NODEID+0x600", mappable=False),
        Entry(0x1200, 2, "COB-ID server to client", "UNSIGNED32", "ro", lambda c: 0x580 + c.can.node_id,
              default="$NODEID+0x580", mappable=False)])
    # SDO2 (DG 7317-7349): read with NOT_VALID set until a program or tool writes the COB-IDs; only the valid
    # bit can change ("It is not possible to change these CobIds")
    record(0x1201, "SDO server 2 parameter", [
        Entry(0x1201, 1, "COB-ID client to server", "UNSIGNED32", "rw", *_sdo2(1), default="$NODEID+0x80000100",
              mappable=False),
        Entry(0x1201, 2, "COB-ID server to client", "UNSIGNED32", "rw", *_sdo2(2), default="$NODEID+0x80000680",
              mappable=False)])


def _store(c, value: int, source: str) -> None:
    if int(value) & 0xFFFFFFFF != 0x65766173:  # "save" (CiA 301 7.5.2.13)
        raise ObjectError(ABORT_STORE, "write the signature 'save' (0x65766173) to store")
    c.params.save(lambda index: index // 100 in (19, 32, 33))  # 1010 'save all parameters'


def _restore(c, value: int, source: str) -> None:
    if int(value) & 0xFFFFFFFF != 0x64616F6C:  # "load"
        raise ObjectError(ABORT_STORE, "write the signature 'load' (0x64616F6C) to restore the defaults")
    params = c.params
    for p in params.db:
        if p.index // 100 in (19, 32, 33) and not p.read_only:
            params.values[p.index] = params.saved[p.index] = p.to_raw(p.default)
    c.apply_parameters()


def _sdo2(sub: int) -> tuple[Getter, Setter]:
    key = sysvar_index(0x1201, sub)

    def cob(c) -> int:
        return (0x100 if sub == 1 else 0x680) + c.can.node_id

    def get(c) -> int:
        return c.sysvar_memory.get(key, 0x80000000 | cob(c))

    def put(c, value, source) -> None:
        value = int(value) & 0xFFFFFFFF
        ids = {0x100 + c.can.node_id, 0x680 + c.can.node_id}   # the manual's example writes them either way
        if value & 0x7FFFFFFF not in ids:
            raise ObjectError(ABORT_VALUE, "the SDO2 COB-IDs cannot be changed, only made valid or not valid")
        c.sysvar_memory[key] = value
    return get, put


def _parameter_objects() -> None:
    for p in database():
        number = p.index
        datatype = PARAMETER_TYPES.get(p.data_type, "INTEGER32")
        read_only = p.read_only or number // 100 == 34
        get, put = _parameter_access(number)
        _var(PARAMETER_BASE + number, f"{p.number} {p.name or p.description}"[:60], datatype,
             "ro" if read_only else "rw", get, None if read_only else put, default=p.to_raw(p.default))


def _parameter_access(number: int) -> tuple[Getter, Setter]:
    """(get, put) of parameter `number` (a function of its own: the lambdas keep this number, not the loop's last)."""
    return (lambda c: c.params.get(number)), (lambda c, v, s: c.params.set(number, int(v), source=s))


def _array_element(k: int) -> Callable[[int], Entry]:
    index = ARRAY_BASE + k

    def array(c):
        arrays = c.arrays.arrays
        if k >= len(arrays):
            raise ObjectError(ABORT_NO_DATA, f"the controller has no array {k + 1}")
        return arrays[k]

    def element(sub: int) -> Entry:
        if sub < ARRAY_FIRST_SUB:
            get = (lambda c: len(array(c))) if sub == 1 else (lambda c: 0)
            return Entry(index, sub, "Number of elements" if sub == 1 else "Reserved", "INTEGER32", "ro", get)
        i = sub - ARRAY_FIRST_SUB

        def get_element(c):
            a = array(c)
            if i >= len(a):
                raise ObjectError(ABORT_NO_DATA, f"array {k + 1} ({a.name}) has {len(a)} elements")
            return int(a.data[i])

        def put_element(c, value, source):
            a = array(c)
            if i >= len(a):
                raise ObjectError(ABORT_NO_DATA, f"array {k + 1} ({a.name}) has {len(a)} elements")
            a.data[i] = int(value)
        return Entry(index, sub, f"Element {i + 1}", "INTEGER32", "rw", get_element, put_element)
    return element


def _whole_array(sub: int) -> Entry:
    """0x23FF sub k: all of array k as little-endian INTEGER32 values (CR 2806)."""
    def get(c):
        arrays = c.arrays.arrays
        if sub > len(arrays):
            raise ObjectError(ABORT_NO_DATA, f"the controller has no array {sub}")
        return struct.pack(f"<{len(arrays[sub - 1])}i", *(int(v) for v in arrays[sub - 1].data))

    def put(c, value, source):
        arrays = c.arrays.arrays
        if sub > len(arrays):
            raise ObjectError(ABORT_NO_DATA, f"the controller has no array {sub}")
        data, array = bytes(value), arrays[sub - 1]
        if len(data) % 4 or len(data) // 4 > len(array):
            raise ObjectError(ABORT_LENGTH, f"{len(data)} bytes for array {sub} of {len(array)} elements")
        array.data[:len(data) // 4] = list(struct.unpack(f"<{len(data) // 4}i", data))
    return Entry(0x23FF, sub, f"Array {sub}", "DOMAIN", "rw", get, put, mappable=False)


def _user_parameter(sub: int) -> Entry:
    number = 1900 + sub - 1   # sub 1 = 19-00 (sysvars.py; CR 1986 "user parameter 1 (= SDO 0x2201/01)")
    return Entry(0x2201, sub, f"User parameter {number // 100}-{number % 100:02d}", "INTEGER32", "rw",
                 lambda c: c.params.get(number), lambda c, v, s: c.params.set(number, int(v), source=s))


def _manufacturer_objects() -> None:
    for k in range(ARRAY_OBJECTS):
        OBJECTS[ARRAY_BASE + k] = Obj(ARRAY_BASE + k, f"Application array {k + 1}", "ARRAY",
                                      {0: Entry(ARRAY_BASE + k, 0, "Highest sub-index supported", "UNSIGNED8", "ro",
                                                lambda c: ARRAY_FIRST_SUB - 1 + ARRAY_ELEMENTS, mappable=False)},
                                      ARRAY_FIRST_SUB - 1 + ARRAY_ELEMENTS, _array_element(k))
    OBJECTS[0x2201] = Obj(0x2201, "User parameters", "ARRAY",
                          {0: Entry(0x2201, 0, "Highest sub-index supported", "UNSIGNED8", "ro", lambda c: 100,
                                    mappable=False)}, 100, _user_parameter)
    io = [Entry(0x2202, 2, "Digital inputs 1-8", "UNSIGNED8", "ro", lambda c: c.io.read_byte(0)),
          Entry(0x2202, 3, "Digital inputs 9-16", "UNSIGNED8", "ro", lambda c: c.io.read_byte(1)),
          Entry(0x2202, 0x0A, "Digital outputs 1-8", "UNSIGNED8", "rw", lambda c: _output_byte(c, 0),
                lambda c, v, s: _set_output_byte(c, 0, v)),
          Entry(0x2202, 0x0B, "Digital outputs 9-16", "UNSIGNED8", "rw", lambda c: _output_byte(c, 1),
                lambda c, v, s: _set_output_byte(c, 1, v)),
          Entry(0x2202, 0x2A, "Encoder raw value", "INTEGER32", "ro", lambda c: c.axis.apos),
          Entry(0x2202, 0x44, "GuardErrorId", "INTEGER32", "ro", lambda c: c.can.guard_error_id)]
    record(0x2202, "System process data", io)
    record(0x2300, "Axis 1 temporary parameters", [
        Entry(0x2300, 2, "Maximum velocity (VELMAX, RPM)", "INTEGER32", "rw", lambda c: c.params.get(3280),
              lambda c, v, s: c.params.set(3280, int(v), source=s))])
    OBJECTS[0x23FF] = Obj(0x23FF, "Whole application arrays", "ARRAY",
                          {0: Entry(0x23FF, 0, "Highest sub-index supported", "UNSIGNED8", "ro", lambda c: 254,
                                    mappable=False)}, 254, _whole_array)
    axis = [Entry(0x2500, n, name, "INTEGER32", "rw" if n == 9 else "ro", reader,
                  (lambda c, v, s: c.master.write_position(int(v))) if n == 9 else None)
            for n, (name, _unit, reader) in sorted(sysvars.AXIS_PROCESS_DATA.items())]
    axis.append(Entry(0x2500, TIME_STAMP_SUB, "Time stamp (ms, low 16 bits)", "UNSIGNED16", "ro",
                      lambda c: c.time_ms & 0xFFFF))
    record(0x2500, "Axis 1 process data", axis)
    record(0x2510, "Link signals", [Entry(0x2510, k, name, "INTEGER32", "ro", _rounded(reader))
                                     for k, (name, reader) in enumerate(SIGNALS.items(), start=1)])


def _rounded(reader: Getter) -> Getter:
    """`reader`'s value rounded (a function of its own: the lambda keeps this reader, not the loop's last)."""
    return lambda c: round(reader(c))


def _output_byte(c, n: int) -> int:
    outputs = c.io.outputs
    return sum(outputs.get(8 * n + k + 1, 0) << k for k in range(8))


def _set_output_byte(c, n: int, value: int) -> None:
    c.io.write_byte(n, int(value) & 0xFF)


def _device_profile_objects() -> None:
    """DS401 digital/analog I/O (so an MCO is the other's CAN I/O module) and the DS402 words the manual's
    programs interpret themselves (plain storage)."""
    record(0x6000, "Read input 8-bit", [
        Entry(0x6000, 1, "Inputs 1-8", "UNSIGNED8", "ro", lambda c: c.io.read_byte(0)),
        Entry(0x6000, 2, "Inputs 9-16", "UNSIGNED8", "ro", lambda c: c.io.read_byte(1))], kind="ARRAY")
    record(0x6200, "Write output 8-bit", [
        Entry(0x6200, 1, "Outputs 1-8", "UNSIGNED8", "rw", lambda c: _output_byte(c, 0),
              lambda c, v, s: _set_output_byte(c, 0, v)),
        Entry(0x6200, 2, "Outputs 9-16", "UNSIGNED8", "rw", lambda c: _output_byte(c, 1),
              lambda c, v, s: _set_output_byte(c, 1, v))], kind="ARRAY")
    record(0x6401, "Read analog input 16-bit", [
        Entry(0x6401, 1, "Analog input 53", "INTEGER16", "ro", lambda c: c.io.analog.get(53, 0)),
        Entry(0x6401, 2, "Analog input 54", "INTEGER16", "ro", lambda c: c.io.analog.get(54, 0))], kind="ARRAY")
    record(0x6411, "Write analog output 16-bit", [
        Entry(0x6411, 1, "Analog output 42", "INTEGER16", "rw", lambda c: c.io.analog.get(42, 0),
              lambda c, v, s: c.io.analog.__setitem__(42, int(v)))], kind="ARRAY")
    for index, name, datatype in ((0x6040, "Controlword", "UNSIGNED16"), (0x6041, "Statusword", "UNSIGNED16"),
                                  (0x6060, "Modes of operation", "INTEGER8"),
                                  (0x6061, "Modes of operation display", "INTEGER8")):
        _var(index, name, datatype, "rw", *_memory(sysvar_index(index, 0)), default=0)


# Signals of the link (controller/service.py streams them by name): 0x2510 sub 1.. in this order.
SIGNALS: dict[str, Callable[[Any], float]] = {
    "APOS": lambda c: c.uu(c.axis.apos),
    "CPOS": lambda c: c.uu(c.axis.cpos),
    "TRACKERR": lambda c: c.axis.scaling.qc_to_uu(c.axis.tracking_error),
    "AVEL": lambda c: c.avel(),
    "CVEL": lambda c: c.axis.scaling.velocity_uu_per_s(c.axis.profile.velocity),
    "AXEND": lambda c: c.axis.axend(),
    "STAT": lambda c: c.stat(),
    "ERRNO": lambda c: c.error,
    "SPEEDREF": lambda c: round(c.axis.reference * 1000),
    "INPUTS": lambda c: c.io.input_word(),
    "OUTPUTS": lambda c: c.io.output_word(),
    "MAPOS": lambda c: c.master.mapos,   # master position and velocity in master qc, qc/s (CR: MAPOS, MAVEL)
    "MAVEL": lambda c: c.master.mavel,
}
SIGNAL_SUB = {name: k for k, name in enumerate(SIGNALS, start=1)}

_communication_objects()
_parameter_objects()
_manufacturer_objects()
_device_profile_objects()
sysvars.object_reader = read_sysvar
