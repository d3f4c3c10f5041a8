"""A virtual drive serves the network only when asked to, and says so (issue 24 item 7): it has no authentication,
and whoever reaches its port can download programs, write parameters and reset the controller."""

from __future__ import annotations

import socket
import subprocess
import sys

import pytest

from motiontool.comms.links import open_link
from tests.comms.drive_process import DriveProcess

pytestmark = pytest.mark.wire


def ipv6_loopback() -> bool:
    try:
        with socket.create_server(("::1", 0), family=socket.AF_INET6):
            return True
    except OSError:
        return False


@pytest.mark.parametrize("listen", ["fc:socket://0.0.0.0:0", "fc:socket://[::]:0",
                                    "canopen:slcan:socket://0.0.0.0:0"])
def test_listening_beyond_this_machine_needs_the_opt_in(listen):
    """Before, `--listen fc:socket://0.0.0.0:PORT` served downloads, parameter writes and factory reset to the
    network without a word."""
    done = subprocess.run([sys.executable, "-m", "motiontool", "drive", "--listen", listen, "--node", "1"],
                          capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)
    assert done.returncode == 1 and done.stdout == ""
    assert done.stderr.count("\n") == 1
    assert "listen on 127.0.0.1 (add ,any_host=1 to listen on" in done.stderr


@pytest.mark.parametrize("listen, url_host", [("fc:socket://0.0.0.0:0,any_host=1", "0.0.0.0"),
                                              ("canopen:slcan:socket://0.0.0.0:0,any_host=1", "0.0.0.0"),
                                              ("fc:socket://[::]:0,any_host=1", "[::]")])
def test_an_opted_in_listener_warns_naming_what_it_exposes(listen, url_host):
    if "[::]" in listen and not ipv6_loopback():
        pytest.skip("no IPv6 on this machine")
    drive = DriveProcess("--node", "1", listen=listen)
    try:
        assert f"socket://{url_host}:" in drive.url
        loopback = "[::1]" if url_host == "[::]" else "127.0.0.1"
        link = open_link(drive.url.replace(url_host, loopback) + "#1")
        try:
            assert link.status().program_state == "idle"
        finally:
            link.close()
    finally:
        code, _, err = drive.stop()
    assert code == 0
    assert f"WARNING: {drive.url} serves the network without authentication" in err


def test_ipv6_loopback_needs_no_opt_in():
    if not ipv6_loopback():
        pytest.skip("no IPv6 on this machine")
    drive = DriveProcess("--node", "1", listen="fc:socket://[::1]:0")
    try:
        link = open_link(drive.url + "#1")
        try:
            assert link.status().program_state == "idle"
        finally:
            link.close()
    finally:
        code, _, err = drive.stop()
    assert code == 0 and "WARNING" not in err
