"""How a CanopenLink (link.py) learns that it lost its node at once: a listener on the transport's errors, an SDO
answer wait that a loss ends, and the time a heartbeat was sent (decision N54)."""

from __future__ import annotations

import queue
import time
from collections.abc import Callable

import can
from canopen.sdo import SdoAbortedError, SdoCommunicationError


def sent_at(stamp: float | None) -> float:
    """A heartbeat's time on this process's monotonic clock: when its frame was stamped (wall time), else now. A
    notifier that falls behind (a busy machine) hands over beats of a node that has since stopped; counted at their
    handling they made a stalled node look alive (a heartbeat test failed so at load 15)."""
    now = time.monotonic()
    if not stamp:
        return now
    age = time.time() - stamp
    return now - age if 0 <= age < 60 else now


class TransportWatch(can.Listener):
    """Tells the link when its transport fails and ends the notifier's thread quietly (python-can printed the
    error with a thread traceback, and the link learned it only when a transfer had timed out)."""

    def __init__(self, on_error: Callable[[Exception], None]):
        self.tell = on_error
        self.notifier: can.Notifier | None = None

    def on_message_received(self, msg: can.Message) -> None:
        pass

    def on_error(self, exc: Exception) -> None:
        self.tell(exc)
        if self.notifier is not None:
            self.notifier._stopped = True    # a handled error would have it read the dead bus again at once


def answer_reader(client, cut: Callable[[], str | None]):
    """python-canopen's SdoClient.read_response, which also ends when `cut()` says why the link lost the node (its
    `_lose` puts None in the answers to wake it): a download waited out its 10 s answer timeout though the
    heartbeat had said so after 1 s."""
    def read_response() -> bytes:
        deadline = time.monotonic() + client.RESPONSE_TIMEOUT
        while True:
            if reason := cut():
                raise SdoCommunicationError(reason)
            try:
                response = client.responses.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                raise SdoCommunicationError("No SDO response received") from None
            if response is not None:     # None: a loss already over (a stale wake-up)
                break
        if response[0] == 0x80:
            raise SdoAbortedError(int.from_bytes(response[4:8], "little"))
        return response
    return read_response
