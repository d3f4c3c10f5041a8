"""The objects that carry the link's services over SDO, on top of the controller's dictionary, and the EDS the drive
ships (both sides know these numbers; the drive's dictionary entries for them are controller/canopen/eds.py).

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

from motiontool.resources import resources_path

STORE_EDS, LINK_MESSAGE, PROGRAM_IMAGE, PROGRAM_CONTROL = 0x1021, 0x5F00, 0x5F10, 0x5F11
PROGRAM_STATES = {"idle": 0, "running": 1, "break": 2, "ended": 3, "error": 4}
START, BREAK, CONTINUE = 1, 2, 3

EDS_PATH = ("eds", "mco305.eds")   # resources/eds/mco305.eds: the drive's dictionary, kept equal by a test


def eds_path():
    return resources_path(*EDS_PATH)
