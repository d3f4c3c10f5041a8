"""The Link: the one way anything (IDE, scope, CLI) talks to a controller."""

from __future__ import annotations

import base64
import threading
from abc import ABC, abstractmethod
from collections.abc import Callable
from typing import Any

from motiontool.comms.protocol import LinkEvent, Request, Status


class Link(ABC):
    """A connection to one controller. Requests block until answered; events arrive at subscribers. Requests may
    come from several threads at once (the IDE's window, its status worker, a wire link's event poller): every
    Link answers each one as if they came one after the other."""

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

    # --- convenience wrappers (the same requests, typed) ---------------------------------------------------
    def status(self) -> Status:
        return Status(**self.call("status"))

    def read_parameter(self, key: str | int) -> int:
        return self.call("read_parameter", key=key)

    def write_parameter(self, key: str | int, value: int) -> None:
        self.call("write_parameter", key=key, value=value)

    def download(self, image_bytes: bytes, number: int | None = None, name: str = "", *,
                 source: dict[str, str] | None = None, stack_size: int | None = None) -> None:
        """Download a program image; `source` (file → text, the program first) stores its source with it
        (Include Sourcecode), `stack_size` is the Settings → Compiler stack size. Both only when given, so a link
        whose controller does not know them still downloads."""
        extra = {key: value for key, value in (("source", source), ("stack_size", stack_size)) if value}
        self.call("download", image=base64.b64encode(image_bytes).decode("ascii"), number=number, name=name,
                  **extra)

    def start(self, number: int | None = None, step: bool = False,
              inputs: list[tuple[int, int, int]] | None = None) -> None:
        """Start a program; with `step` (Prepare Singlestep) it stops before its first statement; `inputs`
        (N, V, T) are set T ms after the start (sent only when given, so every controller still starts)."""
        extra = {"inputs": [list(i) for i in inputs]} if inputs else {}
        self.call("start", number=number, step=step, **extra)

    def break_program(self) -> None:
        self.call("break")

    def continue_program(self) -> None:
        self.call("continue")

    def read_array(self, index: int) -> list[int]:
        return self.call("read_array", index=index)

    def write_array(self, index: int, values: list[int]) -> None:
        self.call("write_array", index=index, values=list(values))

    def set_input(self, number: int, value: int) -> None:
        self.call("set_input", number=number, value=value)

    def advance(self, ms: int) -> None:
        self.call("advance", ms=ms)
