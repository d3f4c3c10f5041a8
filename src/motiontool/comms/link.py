"""The Link: the one way anything (IDE, scope, CLI) talks to a controller."""

from __future__ import annotations

import threading
from abc import abstractmethod
from collections.abc import Callable
from typing import Any

from motiontool.comms.client import ControllerClient
from motiontool.comms.protocol import LinkEvent, Request


class Link(ControllerClient):
    """A connection to one controller. Requests block until answered; events arrive at subscribers. Requests may
    come from several threads at once (the IDE's window, its status worker, a wire link's event poller): every
    Link answers each one as if they came one after the other. The typed requests are the client's
    (comms/client.py); a Link carries them with `call`."""

    kind = "abstract"
    _ids = threading.Lock()     # request ids are unique per link even when several threads call at once
    status_interval_s = 0.0     # how often a display may ask for the status without loading the link

    def __init__(self) -> None:
        self._subscribers: list[Callable[[LinkEvent], None]] = []
        self._next_id = 0

    # --- transport ------------------------------------------------------------------------------------
    @abstractmethod
    def request(self, request: Request) -> Any:
        """Send a request and return its value; raise LinkError when the controller refuses it."""

    def close(self) -> None:  # noqa: B027 - links without resources need not override
        pass

    @property
    def virtual_time(self) -> bool:
        """True when the controller's clock moves only on `advance` (the synchronous simulator); False when it
        runs by itself (a real drive, a paced simulator)."""
        return False

    def flush_events(self) -> None:  # noqa: B027 - links that publish events as they happen need not override
        """Publish the events the controller has produced so far (wire links poll for them)."""

    def subscribe(self, callback: Callable[[LinkEvent], None]) -> None:
        self._subscribers.append(callback)

    def unsubscribe(self, callback: Callable[[LinkEvent], None]) -> None:
        if callback in self._subscribers:
            self._subscribers.remove(callback)

    def _publish(self, event: LinkEvent) -> bool:
        """Hand `event` to every subscriber; False when there was none (the event reached nobody)."""
        callbacks = list(self._subscribers)
        for callback in callbacks:
            callback(event)
        return bool(callbacks)

    def call(self, op: str, **args: Any) -> Any:
        with Link._ids:   # a wire drive answers a repeated id from its cache: two requests must never share one
            self._next_id += 1
            request_id = self._next_id
        return self.request(Request(op, args, request_id))
