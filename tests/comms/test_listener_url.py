"""The drive's `listening on URL` is what a master gives to `--link`, options included (issue 24 item 10: the
printed URL dropped `,baud=`, so a master on `fc:socket://…` timed a 2400-baud drive as a socket)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from motiontool.comms.links import open_link
from tests.comms.drive_process import drive_process

pytestmark = pytest.mark.wire


@pytest.mark.parametrize("listen", ["fc:pty,baud=19200", "fc:socket://127.0.0.1:0,baud=19200"])
def test_the_printed_url_keeps_the_baud_rate_and_a_node_can_be_added_to_it(listen):
    with drive_process("--node", "1", listen=listen) as drive:
        assert drive.url.endswith(",baud=19200"), drive.url
        assert "pty" in listen or drive.url.startswith("fc:socket://127.0.0.1:")
        link = open_link(drive.url + "#1")          # as the tests and the manual's users add the node
        try:
            assert link.bus.settings.baud == 19200
            assert link.read_parameter("KPROP") == 30
        finally:
            link.close()


def test_a_canopen_listener_refuses_an_option_it_would_drop():
    """The slcan server takes no baud rate (the master sets the bit rate with S0-S8): `,baud=` is refused in one
    line naming the option instead of vanishing from the printed URL."""
    result = subprocess.run([sys.executable, "-m", "motiontool", "drive", "--listen",
                             "canopen:slcan:socket://127.0.0.1:0,baud=115200"],
                            capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)
    assert result.returncode == 1 and result.stdout == ""
    assert len(result.stderr.splitlines()) == 1 and "unknown option 'baud'" in result.stderr, result.stderr
