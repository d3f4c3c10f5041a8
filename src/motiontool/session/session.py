"""Which controller an APOSS window is connected to, without Qt (issue 27 item 5, decision I35; DG 2011, 2064-2066,
2536-2546).

A Session is one window's side of the shared ControllerRegistry: the interface and controller ID it is bound to, the
open Link and the Identity the controller gave on connecting. Connecting is two parts: the requests (open the link,
identify) run wherever the caller's `run` puts them - the IDE passes `link_jobs.waiting`, so they run off the GUI
thread while the window paints - and the state change runs in the caller's thread. What happened is told to the
listeners as a SessionEvent whose `message` is what the IDE says about it; the Qt adapter (ui/connection.py) updates
its widgets from them.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

from motiontool.comms.client import Identity
from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError
from motiontool.session.controllers import ControllerRegistry

T = TypeVar("T")
Runner = Callable[[str, Callable[[], Any]], Any]   # (what it waits for, the requests) -> their answer


def run_here(_doing: str, work: Callable[[], T]) -> T:
    """The requests in the caller's thread (tests, headless use)."""
    return work()


@dataclass(frozen=True)
class SessionEvent:
    kind: str                 # "connected" | "disconnected" | "lost" | "failed"
    controller_id: int
    interface: str | None
    message: str = ""         # what the IDE says in its Communication pane ("": nothing)


class Session:
    def __init__(self, registry: ControllerRegistry) -> None:
        self.registry = registry
        self.interface_key: str | None = None   # the interface of the controller (kept when lost)
        self.controller_id = 1
        self.link: Link | None = None
        self.identity: Identity | None = None
        self.lost_reason = ""
        self.closed = False
        self.listeners: list[Callable[[SessionEvent], None]] = []
        registry.sessions.append(self)
        registry.closed_listeners.append(self._closed)

    @property
    def connected(self) -> bool:
        return self.link is not None

    @property
    def interface_description(self) -> str:
        iface = self.registry.interfaces.get(self.interface_key or "")
        return iface.config.description if iface else self.registry.default.description

    def _tell(self, kind: str, message: str = "", *, controller_id: int | None = None) -> None:
        cid = self.controller_id if controller_id is None else controller_id
        event = SessionEvent(kind, cid, self.interface_key, message)
        for listener in list(self.listeners):
            listener(event)

    # --- connecting ----------------------------------------------------------------------------------------
    def open(self, controller_id: int, interface: str) -> tuple[Link, Identity]:
        """The requests of connecting; safe off the GUI thread (they change nothing of the session)."""
        try:
            link = self.registry.link(controller_id, interface=interface)
            return link, link.identify()
        except OSError as exc:   # a port that cannot be opened: said as it is, not as a failed request
            raise LinkError(str(exc)) from exc

    def select(self, controller_id: int, *, interface: str | None = None, run: Runner = run_here) -> bool:
        """Connect to a controller (the default interface when none is named); the controller left keeps running
        its program; a controller another session holds moves here (DG 2546). A failure is told, not raised."""
        key = interface or self.registry.default.key
        try:
            link, ident = run(f"Connecting to controller {controller_id} …",
                              lambda: self.open(controller_id, key))
        except (LinkError, ValueError) as exc:
            self._tell("failed", f"Connection to controller {controller_id} failed: {exc}", controller_id=controller_id)
            return False
        if self.closed:   # the window closed while `run` waited: the controller stays no one's (decision I35)
            if not self.registry.sessions:
                self.registry.close()   # the last window's close came before the link was opened: close it too
            return False
        self.attach(controller_id, key, link, ident)
        return True

    def attach(self, controller_id: int, key: str, link: Link, ident: Identity) -> None:
        """The state change of connecting, after `open` answered."""
        holder = self.registry.owners.get((key, controller_id))
        if isinstance(holder, Session) and holder is not self:
            holder.release(f"controller {controller_id} moved to another APOSS window")
        if self.connected:
            self.registry.owners.pop((self.interface_key or "", self.controller_id), None)
        self.registry.owners[(key, controller_id)] = self
        self.interface_key = key
        self.controller_id = controller_id
        self.link = link
        self.identity = ident
        self.lost_reason = ""
        # ide-spec 2.37: the identity and firmware version on connect
        self._tell("connected", f"Connected to controller {controller_id} [{self.interface_description}] "
                                f"{ident.product or '?'}, {ident.firmware or '?'}")

    def connect_default(self, *, run: Runner = run_here) -> bool:
        """Commands that need a controller connect first: to this session's controller after a loss, else to the
        default interface's controller."""
        if self.connected:
            return True
        return self.select(self.controller_id, interface=self.interface_key, run=run)

    def reconnect(self, *, run: Runner = run_here) -> bool:
        return self.select(self.controller_id, interface=self.interface_key, run=run)

    # --- letting go ------------------------------------------------------------------------------------------
    def release(self, why: str) -> None:
        """Let go of the controller (its link stays open for whoever takes it)."""
        if self.connected:
            self.registry.owners.pop((self.interface_key or "", self.controller_id), None)
            self.link = None
            self._tell("disconnected", why[:1].upper() + why[1:])

    def lost(self, reason: str = "no answer") -> None:
        """The link was found dead: the session stays bound to its controller, the next connect goes there."""
        self.registry.owners.pop((self.interface_key or "", self.controller_id), None)
        self.link = None
        self.lost_reason = reason
        self._tell("lost", f"Lost connection to controller {self.controller_id} ({self.interface_description})! "
                           "Press Esc or Reconnect to connect again.")

    def close(self) -> None:
        """The window closes: its controller stays open for the other sessions; the last one closes all."""
        self.closed = True
        self.release("")
        if self._closed in self.registry.closed_listeners:
            self.registry.closed_listeners.remove(self._closed)
        if self in self.registry.sessions:
            self.registry.sessions.remove(self)
        if not self.registry.sessions:
            self.registry.close()

    def _closed(self, key: str, ids: list[int]) -> None:
        if key == self.interface_key and self.connected and self.controller_id in ids:
            self.link = None
            self._tell("disconnected")
