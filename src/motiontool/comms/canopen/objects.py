"""The objects that carry the link's services over SDO, on top of the controller's dictionary (kernel/objdict.py).

- 0x1021 Store EDS (CiA 306): the EDS text, so a tool can fetch the dictionary from the node itself;
- 0x5F00 Link message: write a request message of the link protocol (comms/wire.py: every request the IDE sends —
  download, start/break, debugger, events with PRINT lines and errors …), then read its answer;
- 0x5F10 Program image: write a compiled program (ProgramImage bytes): it becomes the temporary program;
- 0x5F11 Program control: write 1 start the temporary program, 2 break ([Esc]), 3 continue; read the program state
  (0 idle, 1 running, 2 break, 3 ended, 4 error).

Tools other than motiontool use 0x5F10/0x5F11 and the parameter objects directly; motiontool's link sends
everything else through 0x5F00 (decision N11).
"""

from __future__ import annotations

from motiontool.kernel.objdict import Entry, Obj

STORE_EDS, LINK_MESSAGE, PROGRAM_IMAGE, PROGRAM_CONTROL = 0x1021, 0x5F00, 0x5F10, 0x5F11
PROGRAM_STATES = {"idle": 0, "running": 1, "break": 2, "ended": 3, "error": 4}
START, BREAK, CONTINUE = 1, 2, 3


def _var(index: int, name: str, datatype: str, access: str) -> Obj:
    return Obj(index, name, "VAR", {0: Entry(index, 0, name, datatype, access, mappable=False)})


SERVICE_OBJECTS: dict[int, Obj] = {
    STORE_EDS: _var(STORE_EDS, "Store EDS", "DOMAIN", "ro"),
    LINK_MESSAGE: _var(LINK_MESSAGE, "Link message", "DOMAIN", "rw"),
    PROGRAM_IMAGE: _var(PROGRAM_IMAGE, "Program image", "DOMAIN", "wo"),
    PROGRAM_CONTROL: _var(PROGRAM_CONTROL, "Program control", "INTEGER32", "rw"),
}
