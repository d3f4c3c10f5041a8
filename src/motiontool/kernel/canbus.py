"""The CAN bus the simulated controllers share (the MCO's X62 "MCO bus", DG 7274-7428).

A `CanBus` carries `CanFrame`s between the `CanPort`s of the controllers on it (kernel/canport.py). Time is the
controllers' tick: a frame sent during tick t reaches every other port at the start of tick t+1, so one hop costs
1 ms and a run is reproducible to the tick, as fast as Python goes. A port never receives its own frames (a CAN
controller does not read back what it sends).

Outside the kernel a bus can be bridged to a real python-can bus (the virtual drive, comms/canopen/): `outlets`
are called with every frame a controller sends, and `inject()` (thread-safe) hands in frames from outside, which
the ports receive at the next tick like any other frame. A bridge that serves the controllers' SDO servers itself
(python-canopen LocalNodes) switches the kernel's own servers off with `kernel_sdo_servers = False`.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import dataclass

MAX_STANDARD_ID = 0x7FF
SLAVE_BUS_OFFSET = 100000   # "id + 100000" addresses the slave bus of controllers with two (CR 764-809)


@dataclass(frozen=True, slots=True)
class CanFrame:
    can_id: int          # 11-bit identifier (29-bit when extended)
    data: bytes = b""    # 0..8 bytes; a remote frame carries none
    rtr: bool = False    # remote transmission request: dlc bytes asked for
    dlc: int = -1        # data length code; -1 = len(data)
    extended: bool = False

    @property
    def length(self) -> int:
        return len(self.data) if self.dlc < 0 else self.dlc

    def __repr__(self) -> str:
        body = f"r{self.length}" if self.rtr else self.data.hex(" ")
        return f"CanFrame(0x{self.can_id:03X} {body})"


class CanBus:
    """Frames between ports, delivered once per tick; bridged to the outside by outlets and inject()."""

    def __init__(self) -> None:
        self.ports: list = []                                  # kernel.canport.CanPort
        self.outlets: list[Callable[[CanFrame], None]] = []    # a bridge's sender (called in the tick)
        self.kernel_sdo_servers = True                         # False when a bridge serves SDO (LocalNodes)
        self.pending: list[tuple[CanFrame, object]] = []
        self.injected: deque[CanFrame] = deque()              # from other threads (deque appends are atomic)
        self.sent = 0                                          # frames carried (statistics)

    def attach(self, port) -> None:
        if port not in self.ports:
            self.ports.append(port)

    def detach(self, port) -> None:
        if port in self.ports:
            self.ports.remove(port)

    def send(self, frame: CanFrame, sender=None) -> None:
        """A frame from `sender` (a port, or None for a test or tool on the bus); delivered at the next tick."""
        self.pending.append((frame, sender))
        self.sent += 1
        for outlet in self.outlets:
            outlet(frame)

    def inject(self, frame: CanFrame) -> None:
        """A frame from outside the simulation (any thread); every port receives it at the next tick."""
        self.injected.append(frame)

    def deliver(self) -> None:
        """Hand the frames sent since the last delivery to every port except their sender."""
        if not self.pending and not self.injected:
            return
        pending, self.pending = self.pending, []
        injected = self.injected
        while injected:
            pending.append((injected.popleft(), None))
        ports = self.ports
        for frame, sender in pending:
            for port in ports:
                if port is not sender:
                    port.inbox.append(frame)
