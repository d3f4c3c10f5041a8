"""Parameters ▸ Name over a wire link (DG 2870-2882: "Names cannot be longer than 8 characters and must be
uppercase"): a name set, here or by a second master, is what the next identify answers. RemoteLink kept its first
identify answer for the link's life, so after a rename the IDE's Name dialog, Select Controller and the diagnostic
report showed the old name over FC and CANopen (the simulator has no such copy)."""

from __future__ import annotations

import pytest

from motiontool.comms.links import open_link
from tests.comms.drive_process import drive_process

pytestmark = pytest.mark.wire


def test_a_name_set_by_this_master_or_another_is_the_next_identify_answer():
    with drive_process("--node", "1") as drive:
        first, second = open_link(f"{drive.url}#1"), open_link(f"{drive.url}#1")
        try:
            assert first.identify().name == "" and not first.virtual_time
            first.set_name("PRESS1")
            assert first.identify().name == "PRESS1"
            second.set_name("PRESS2")                     # another master renames it
            assert first.identify().name == "PRESS2"
        finally:
            first.close()
            second.close()
