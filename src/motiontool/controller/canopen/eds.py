"""The drive's object dictionary as an EDS (CiA 306, the INI text every CANopen tool reads), written from
kernel/objdict.py and the service objects (comms/canopen/objects.py). `resources/eds/mco305.eds` is this text; a
test keeps them equal. Regenerate it with ``python -m motiontool.controller.canopen.eds > resources/eds/mco305.eds``.
"""

from __future__ import annotations

import sys

from motiontool.comms.canopen.objects import LINK_MESSAGE, PROGRAM_CONTROL, PROGRAM_IMAGE, STORE_EDS
from motiontool.kernel import canpdo, objdict
from motiontool.kernel.objdict import Entry, Obj

OBJECT_TYPES = {"VAR": 0x7, "ARRAY": 0x8, "RECORD": 0x9}
MANDATORY = (0x1000, 0x1001, 0x1018)


def _var(index: int, name: str, datatype: str, access: str) -> Obj:
    return Obj(index, name, "VAR", {0: Entry(index, 0, name, datatype, access, mappable=False)})


SERVICE_OBJECTS: dict[int, Obj] = {
    STORE_EDS: _var(STORE_EDS, "Store EDS", "DOMAIN", "ro"),
    LINK_MESSAGE: _var(LINK_MESSAGE, "Link message", "DOMAIN", "rw"),
    PROGRAM_IMAGE: _var(PROGRAM_IMAGE, "Program image", "DOMAIN", "wo"),
    PROGRAM_CONTROL: _var(PROGRAM_CONTROL, "Program control", "INTEGER32", "rw"),
}


def dictionary() -> dict[int, objdict.Obj]:
    """Every object of the drive, by index."""
    return dict(sorted({**objdict.OBJECTS, **SERVICE_OBJECTS}.items()))


def _value(value) -> str:
    if isinstance(value, int):
        return f"0x{value:X}" if value > 255 else str(value)
    return "" if value is None else str(value)


def _entry_lines(entry: objdict.Entry, name: str | None = None) -> list[str]:
    code = objdict.DATATYPES[entry.datatype][0]
    lines = [f"ParameterName={name or entry.name}", "ObjectType=0x7", f"DataType=0x{code:04X}",
             f"AccessType={entry.access}"]
    if entry.default is not None and entry.datatype != "DOMAIN":
        lines.append(f"DefaultValue={_value(entry.default)}")
    lines.append(f"PDOMapping={int(entry.mappable and entry.datatype not in ('DOMAIN', 'VISIBLE_STRING'))}")
    return lines


def _object_sections(obj: objdict.Obj) -> list[str]:
    head = f"{obj.index:04X}"
    if obj.kind == "VAR":
        return [f"[{head}]", *_entry_lines(obj.entries[0], obj.name), ""]
    if obj.count:   # a compact ARRAY: one section describes the sub-indices 1..count (CiA 306 CompactSubObj)
        assert obj.element is not None  # a compact ARRAY builds its sub-indices (objdict.Obj)
        template = obj.element(obj.count)
        return [f"[{head}]", f"ParameterName={obj.name}", "ObjectType=0x8",
                f"DataType=0x{objdict.DATATYPES[template.datatype][0]:04X}", f"AccessType={template.access}",
                f"CompactSubObj={obj.count}",
                f"PDOMapping={int(template.mappable and template.datatype != 'DOMAIN')}", ""]
    lines = [f"[{head}]", f"ParameterName={obj.name}", f"ObjectType=0x{OBJECT_TYPES[obj.kind]:X}",
             f"SubNumber={len(obj.entries)}", ""]
    for sub, entry in sorted(obj.entries.items()):
        lines += [f"[{head}sub{sub:X}]", *_entry_lines(entry), ""]
    return lines


def eds_text() -> str:
    objects = dictionary()
    optional = [i for i in objects if i < 0x2000 and i not in MANDATORY]
    manufacturer = [i for i in objects if 0x2000 <= i < 0x6000]
    profile = [i for i in objects if i >= 0x6000]
    lines = ["[FileInfo]", "FileName=mco305.eds", "FileVersion=1", "FileRevision=0", "EDSVersion=4.0",
             "Description=MCO 305 motion controller as simulated by motiontool (docs/protocols/canopen.md)",
             "CreatedBy=motiontool", "", "[DeviceInfo]", "VendorName=motiontool", "VendorNumber=0x0",
             "ProductName=MCO 305 (simulated)", "ProductNumber=0x131", "RevisionNumber=0x50000", "OrderCode=",
             *(f"BaudRate_{rate}=1" for rate in (10, 20, 50, 125, 250, 500, 800, 1000)),
             "SimpleBootUpMaster=0", "SimpleBootUpSlave=1", "Granularity=8", "DynamicChannelsSupported=0",
             "GroupMessaging=0", f"NrOfRXPDO={canpdo.CAN_PDOS}", f"NrOfTXPDO={canpdo.CAN_PDOS}", "LSS_Supported=0",
             "", "[DummyUsage]", *(f"Dummy000{n}=0" for n in range(1, 8)), ""]
    for title, indices in (("MandatoryObjects", MANDATORY), ("OptionalObjects", optional + profile),
                           ("ManufacturerObjects", manufacturer)):
        lines += [f"[{title}]", f"SupportedObjects={len(indices)}",
                  *(f"{k}=0x{index:04X}" for k, index in enumerate(indices, start=1)), ""]
    for obj in objects.values():
        lines += _object_sections(obj)
    return "\n".join(lines)


if __name__ == "__main__":
    sys.stdout.write(eds_text())
