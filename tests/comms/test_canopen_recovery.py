"""A CANopen link that loses its drive (issue 24 item 9, decision N54), against `motiontool drive` as its own
process: a transfer under way ends as soon as the loss is known, in words, and a lost connection is a pause from
which the link comes back by itself, whoever subscribes to it."""

from __future__ import annotations

import os
import signal
import socket
import threading
import time

import pytest

from motiontool.comms.links import open_link
from motiontool.comms.protocol import ConnectionLost, LinkError
from tests.comms.drive_process import DriveProcess

pytestmark = pytest.mark.wire

LISTEN = "canopen:slcan:socket://127.0.0.1:{}"


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def read_again(link, seconds: float) -> int:
    """KPROP once the link reads again (a lost connection is a pause), else the test fails."""
    deadline = time.monotonic() + seconds
    while True:
        try:
            return link.read_parameter("KPROP")
        except LinkError as exc:
            assert time.monotonic() < deadline, f"the link did not come back within {seconds} s: {exc}"
            time.sleep(0.2)


@pytest.mark.parametrize("subscribed", [True, False], ids=["ide", "command-line"])
@pytest.mark.parametrize("how", ["kill", "stop"])
def test_a_drive_lost_during_a_download_ends_the_download_within_the_heartbeat_time(capfd, how, subscribed):
    """Before, kill -9 of the drive in the middle of a download waited out the 10 s answer timeout and then said
    "Bad file descriptor" with a thread traceback on stderr, though the heartbeat consumer had said "Lost
    connection" after 1 s; a stopped drive (SIGSTOP) held a link without subscribers for 20 s. A 400 kB image
    takes the drive's slcan server 8 s at least (7 500 frames/s, N53): the loss comes in its middle."""
    drive = DriveProcess("--node", "1", listen=LISTEN.format(0))
    link = open_link(drive.url + "#1")
    if subscribed:
        link.subscribe(lambda event: None)
    assert link.identify()
    outcome: list = []

    def download():
        try:
            link.download(os.urandom(400_000), name="big")
            outcome.append("finished")
        except LinkError as exc:
            outcome.append(exc)
        outcome.append(time.monotonic())

    try:
        worker = threading.Thread(target=download)
        worker.start()
        worker.join(1.0)
        assert worker.is_alive()            # the download is under way
        lost_at = time.monotonic()
        if how == "kill":
            drive.proc.kill()
        else:
            drive.proc.send_signal(signal.SIGSTOP)
        worker.join(20)
        assert outcome, "the download still waited 20 s after the drive was lost"
        error, ended = outcome
        # the transport's end is known at once, a silence after the consumer time (1000 ms) and a little
        assert ended - lost_at < (1.0 if how == "kill" else 3.0), ended - lost_at
        assert isinstance(error, ConnectionLost)
        assert str(error).startswith("lost connection to CANopen node 1: "), error
        if how == "stop":        # and the link comes back when the drive goes on
            drive.proc.send_signal(signal.SIGCONT)
            assert read_again(link, 10) == 30
    finally:
        link.close()
        if how == "stop":
            drive.proc.send_signal(signal.SIGCONT)
        drive.stop()
    assert "Traceback" not in capfd.readouterr().err


@pytest.mark.parametrize("options", ["", ",heartbeat=100"], ids=["guarded", "heartbeat"])
def test_a_link_without_subscribers_comes_back_when_its_drive_restarts(options):
    """`params`/`run`-style use: no subscriber, so nothing guarded the node. Before, such a link that had once
    lost its drive refused every request for ever ("no heartbeat from CANopen node 1"), and one that set the
    heartbeat waited for heartbeats the restarted node (0x1017 = 0 at power on) never sent. Now it asks by node
    guarding while lost, opens its transport again and sets up again what it had set (the heartbeat)."""
    listen = LISTEN.format(free_port())
    first = DriveProcess("--node", "1", listen=listen)
    link = open_link(first.url + "#1" + options)
    second = None
    try:
        assert link.read_parameter("KPROP") == 30
        first.proc.kill()
        first.proc.wait(10)
        with pytest.raises(ConnectionLost):
            link.read_parameter("KPROP")
        second = DriveProcess("--node", "1", listen=listen)
        assert second.url
        assert read_again(link, 15) == 30
        assert link.alive
        if options:      # the heartbeat it had set is set again: the link is watched by it, not guarded
            assert link.read_object(0x1017) == 100
    finally:
        link.close()
        if second is not None:
            second.stop()


def test_a_download_of_a_link_that_waits_goes_on_after_a_stall():
    """With a patience (`run --timeout`, F30) a stall is a pause: the heartbeat consumer says the connection is lost
    after 1 s and ends the transfer under way (N54); the link sends the same message again once the node is back,
    and the download does not fail for the lost connection."""
    drive = DriveProcess("--node", "1", listen=LISTEN.format(0))
    link = open_link(drive.url + "#1,heartbeat=100")
    link.patience_s = 60
    said: list[str] = []
    link.subscribe(lambda event: said.append(event.text) if event.kind == "connection" else None)
    outcome: list = []

    def download():
        try:
            link.download(os.urandom(400_000), name="big")
            outcome.append("finished")
        except LinkError as exc:
            outcome.append(exc)

    try:
        worker = threading.Thread(target=download)
        worker.start()
        worker.join(1.0)
        assert worker.is_alive()            # the download is under way
        drive.proc.send_signal(signal.SIGSTOP)
        deadline = time.monotonic() + 10
        while not said and time.monotonic() < deadline:
            time.sleep(0.05)
        drive.proc.send_signal(signal.SIGCONT)
        worker.join(60)
        # the drive may refuse the image (random bytes) once all of it has arrived; not for the lost connection
        assert outcome and (outcome[0] == "finished" or not isinstance(outcome[0], ConnectionLost)), outcome
        assert said and said[0].startswith("lost connection to CANopen node 1 ")
    finally:
        link.close()
        drive.proc.send_signal(signal.SIGCONT)
        drive.stop()


def test_an_open_that_fails_leaves_no_connection_behind():
    """A CANopen link whose set-up fails (here: a node the drive does not have, so its heartbeat time cannot be
    read) closes what it opened: each failed open kept an slcan client on the drive, which serves 16."""
    drive = DriveProcess("--node", "1", listen=LISTEN.format(0))
    try:
        before = len(os.listdir("/proc/self/fd"))
        for _ in range(2):
            with pytest.raises(LinkError):
                open_link(drive.url + "#9")
        assert len(os.listdir("/proc/self/fd")) <= before     # (a thread of an earlier test may close one)
        link = open_link(drive.url + "#1")
        link.close()
    finally:
        drive.stop()
