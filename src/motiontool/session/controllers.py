"""The interfaces and controllers this IDE session can reach (ide-spec 2.5, 2.8-2.13, 2.36; DG 2504-2552, 3087-3111).

An interface is a way to reach controllers: the embedded simulator (controllers 1..4, each its own simulated MCO
305) or an FC bus on a serial port or serial-to-Ethernet converter (the controllers by their addresses), or any other
registered link scheme. Settings → Interface keeps one configuration per interface type and which one is the default
(Esc and commands without a controller connect through it). The registry is shared by all APOSS windows: a
controller keeps running its program when a window leaves it, and one controller belongs to at most one window.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from motiontool.comms.link import Link
from motiontool.comms.links import open_link, scan_controllers

SIMULATED_IDS = (1, 2, 3, 4)
APC_SIM = "apcsim"   # the interface of the simulated APC (Unidrive SP) that runs DPL programs: one controller
BAUDS = (2400, 4800, 9600, 19200, 38400, 57600, 76800, 115200)   # FC 300 8-32


@dataclass(frozen=True)
class InterfaceConfig:
    """One interface: its type, port (a pyserial URL for FC), baud rate and controller ID scan range."""

    kind: str = "sim"             # "sim" | "fc" | another registered link scheme
    port: str = ""
    baud: int = 9600
    first: int = 1
    last: int = 4
    sdo: int = 1                  # CANopen: the SDO channel (2: the node's second server, beside another master, N52)

    @property
    def key(self) -> str:
        return "sim" if self.kind == "sim" else f"{self.kind}:{self.port}"

    @property
    def description(self) -> str:
        """As the manual's Download dialog names an interface ("VLT: COM2 9600 baud", DG 3289)."""
        if self.kind == "sim":
            return "Simulator"
        if self.kind == "fc":
            return f"FC: {self.port}" + ("" if "://" in self.port else f" {self.baud} baud")
        if self.kind == APC_SIM:
            return "APC simulator"
        return f"{self.kind}: {self.port}"

    def spec(self, controller_id: int) -> str:
        if self.kind == "sim":
            return "sim"
        option = f",baud={self.baud}" if self.kind == "fc" else f",sdo={self.sdo}" if self.sdo != 1 else ""
        return f"{self.kind}:{self.port}#{controller_id}{option}"

    @property
    def scan_range(self) -> range:
        return range(self.first, self.last + 1)


class OpenInterface:
    def __init__(self, config: InterfaceConfig, found: list[int]):
        self.config = config
        self.found = found                    # the controllers that answered the scan
        self.links: dict[int, Link] = {}


class ControllerRegistry:
    def __init__(self, *, realtime_factor: float = 1.0, default: InterfaceConfig | None = None):
        self.realtime_factor = realtime_factor
        self.default = default or InterfaceConfig()
        self.interfaces: dict[str, OpenInterface] = {}
        self.known: dict[str, InterfaceConfig] = {}                           # every interface opened so far
        self.sessions: list = []                                              # the windows' sessions sharing these
        self.closed_listeners: list[Callable[[str, list[int]], None]] = []   # (interface key, controller ids)
        self.owners: dict[tuple[str, int], object] = {}                       # (key, id) → the session holding it

    # --- interfaces -------------------------------------------------------------------------------------
    def open_interface(self, *, config: InterfaceConfig | None = None) -> OpenInterface:
        """Open Interface (DG 2540): the interface's controllers in its scan range (the simulator's all exist, a
        bus is scanned); an open interface is returned as it is."""
        config = config or self.default
        interface = self.interfaces.get(config.key)
        if interface is None:
            self.known[config.key] = config
            if config.kind == "sim":
                found = [n for n in config.scan_range if n in SIMULATED_IDS]
            else:
                found = scan_controllers(config.spec(config.first), config.scan_range)
            interface = self.interfaces[config.key] = OpenInterface(config, found)
        return interface

    def interface(self, *, key: str | None = None) -> OpenInterface:
        if key is None or key == self.default.key:
            return self.open_interface(config=self.default)
        if key not in self.interfaces:
            if key not in self.known:
                raise ValueError(f"interface {key} is not open")
            return self.open_interface(config=self.known[key])   # reconnecting after Close Interface
        return self.interfaces[key]

    def link(self, controller_id: int, *, interface: str | None = None) -> Link:
        """The link to a controller of an interface (the default one when None), opened on first use; a dead
        link (lost connection) is replaced."""
        iface = self.interface(key=interface)
        config = iface.config
        if config.kind == "sim" and controller_id not in SIMULATED_IDS:
            raise ValueError(f"no controller {controller_id} on the simulated interface")
        link = iface.links.get(controller_id)
        if link is None or not getattr(link, "alive", True):
            fresh = self._open(config, controller_id)
            if link is not None:
                link.close()
                if hasattr(fresh, "resume"):  # the same master again: its session goes on (comms/remote.py)
                    fresh.resume(link)
            iface.links[controller_id] = fresh
            if controller_id not in iface.found:
                iface.found = sorted({*iface.found, controller_id})
        return iface.links[controller_id]

    def _open(self, config: InterfaceConfig, controller_id: int) -> Link:
        if config.kind in ("sim", APC_SIM):  # the simulators, paced at real time × the window's factor
            return open_link(f"{config.kind},realtime={self.realtime_factor:g}")
        return open_link(config.spec(controller_id))

    def open_links(self, *, interface: str | None = None) -> list[tuple[int, Link]]:
        """The open links of one interface (the default one when None), by controller ID."""
        key = interface or self.default.key
        iface = self.interfaces.get(key)
        return sorted(iface.links.items()) if iface else []

    def close(self, *, controller_id: int | None = None, interface: str | None = None) -> list[tuple[str, int]]:
        """Close one controller's link, every link of an interface (Close Interface), or all of them (Close All
        Interfaces: both None). Returns the (interface, ID) pairs closed; windows holding them are told."""
        if controller_id is None and interface is None:
            keys = list(self.interfaces)
        else:
            keys = [interface or self.default.key]
        closed: list[tuple[str, int]] = []
        for key in keys:
            iface = self.interfaces.get(key)
            if iface is None:
                continue
            ids = [controller_id] if controller_id is not None else list(iface.links)
            for cid in ids:
                link = iface.links.pop(cid, None)
                if link is not None:
                    link.close()
                    closed.append((key, cid))
            if controller_id is None:
                del self.interfaces[key]
        for key in {k for k, _ in closed}:
            for listener in list(self.closed_listeners):
                listener(key, [cid for k, cid in closed if k == key])
        return closed

    def set_default(self, config: InterfaceConfig) -> None:
        """Settings → Interface: affects only new connections (DG 3109-3111)."""
        self.default = config
