"""The virtual drive on CAN: `motiontool drive --listen canopen:slcan:socket://127.0.0.1:PORT` (issue 15 item 4).

The drive's controllers sit on a python-can ``virtual`` channel of this process:
- each is a python-canopen LocalNode (node.py) answering SDO for its object dictionary;
- a bridge carries the frames of the simulated CAN bus (kernel/canbus.py: the programs' telegrams, PDOs, NMT,
  heartbeats, SDO transfers between controllers) to the channel and the channel's frames back into it;
- an slcan TCP server (slcan.py) makes the channel a CAN adapter for any python-can client.

`CanopenDrive` does the first two for any python-can channel (tests use it directly on a ``virtual`` bus);
`SlcanListener` adds the TCP server and registers the listener scheme ``canopen``.
"""

from __future__ import annotations

import contextlib
import itertools
import threading

import can
import canopen

from motiontool.comms.canopen.objects import eds_path
from motiontool.comms.protocol import LinkError
from motiontool.controller.canopen import eds
from motiontool.controller.canopen.hub import HubBus
from motiontool.controller.canopen.node import ControllerNode
from motiontool.controller.canopen.slcan_server import SlcanServer, open_local_bus
from motiontool.controller.drive.listeners import exposed, listen_port, warn_exposed
from motiontool.kernel.canbus import CanFrame

_channels = itertools.count(1)


def to_message(frame: CanFrame) -> can.Message:
    return can.Message(arbitration_id=frame.can_id, data=frame.data, is_remote_frame=frame.rtr,
                       dlc=frame.length, is_extended_id=frame.extended)


def to_frame(msg: can.Message) -> CanFrame:
    return CanFrame(msg.arbitration_id, bytes(msg.data) if not msg.is_remote_frame else b"", msg.is_remote_frame,
                    msg.dlc, msg.is_extended_id)


class CanopenDrive:
    """The drive's controllers as CANopen nodes on python-can `channel` (interface ``virtual``)."""

    def __init__(self, drive, channel: str, interface: str = "virtual"):
        self.drive = drive
        self.channel = channel
        simulation = drive.simulation
        text = eds.eds_text()
        od = canopen.import_od(str(eds_path()))
        wanted = {0, *(0x600 + n for n in drive.nodes), *(0x100 + n for n in drive.nodes)}  # NMT, SDO 1 and 2
        self._bus = open_local_bus(interface, channel, wanted)
        self.network = canopen.Network(self._bus)
        self.network.notifier = self._notifier = can.Notifier(self._bus, self.network.listeners, 0.5)
        self.nodes: dict[int, ControllerNode] = {}
        for n, drive_node in drive.nodes.items():
            node = ControllerNode(n, od, drive, drive_node, text)
            self.network.add_node(node)
            self.nodes[n] = node
        # the bridge: the simulated bus's frames out, the channel's frames in (the LocalNodes serve SDO now)
        self._bridge = open_local_bus(interface, channel)
        self._can_bus = simulation.can_bus
        self._can_bus.kernel_sdo_servers = False
        self._can_bus.outlets.append(self._out)
        self._closed = threading.Event()
        self._thread: threading.Thread | None = None
        if isinstance(self._bridge, HubBus):
            self._bridge.on_frame = self._take
        else:
            self._thread = threading.Thread(target=self._in, name="canopen-bridge", daemon=True)
            self._thread.start()

    def forget_transfers(self, cob_ids) -> None:
        """The master that sent SDO requests on these COB-IDs went away in the middle of a block transfer, maybe."""
        for cob_id in cob_ids:
            if (node := self.nodes.get(cob_id & 0x7F)) is not None:
                node.forget_transfer(cob_id)

    def _out(self, frame: CanFrame) -> None:
        """Called in the tick (under the drive's lock): the bus only queues the message."""
        self._nmt_reset(frame)         # a controller's program may reset its neighbours
        with contextlib.suppress(can.CanError):
            self._bridge.send(to_message(frame))

    def _in(self) -> None:
        while not self._closed.is_set():
            msg = self._bridge.recv(timeout=0.2)
            if msg is not None:
                self._take(msg)

    def _take(self, msg: can.Message) -> None:
        """A frame of the channel into the simulation (the sender's thread on the hub, else the bridge's)."""
        if not msg.is_error_frame:
            frame = to_frame(msg)
            self._nmt_reset(frame)       # before the controllers boot up: a master waits for the boot-up
            self._can_bus.inject(frame)

    def _nmt_reset(self, frame: CanFrame) -> None:
        """NMT Reset Node / Communication (82 or 81, node or 0 for all) reaches the nodes' SDO servers too."""
        if frame.can_id or frame.extended or frame.rtr or len(frame.data) < 2 or frame.data[0] not in (0x81, 0x82):
            return
        for n, node in self.nodes.items():
            if frame.data[1] in (0, n):
                node.reset_communication()

    def close(self) -> None:
        self._closed.set()
        if self._out in self._can_bus.outlets:
            self._can_bus.outlets.remove(self._out)
        self._can_bus.kernel_sdo_servers = True
        if isinstance(self._bridge, HubBus):
            self._bridge.on_frame = None
        if self._thread is not None:
            self._thread.join(timeout=2.0)
        self._notifier.stop(2.0)
        self._bus.shutdown()
        self._bridge.shutdown()


class SlcanListener:
    """`canopen:slcan:socket://HOST:PORT` for `motiontool drive --listen` (port 0: any free port)."""

    def __init__(self, spec, drive):
        spec.check_options({"any_host"})     # the master sets the slcan bit rate (S0-S8): nothing else to take
        interface, _, channel = spec.target.partition(":")
        if interface != "slcan" or not channel.startswith("socket://"):
            raise LinkError(f"--listen '{spec.text}': the CANopen drive listens as canopen:slcan:socket://HOST:PORT")
        host, _, port = channel.removeprefix("socket://").rpartition(":")
        host = host.strip("[]")
        number = listen_port(spec, port or "0")  # before the hub bus exists: a refusal leaves nothing open
        public = exposed(spec, host)
        name = f"motiontool-drive-{next(_channels)}"
        try:
            self.server = SlcanServer(name, host, number, interface="hub")
        except (OSError, ValueError) as exc:
            raise LinkError(f"--listen '{spec.text}': {exc}") from None
        self.canopen = CanopenDrive(drive, name, interface="hub")
        self.server.on_disconnect.append(self.canopen.forget_transfers)
        self.url = f"canopen:slcan:{self.server.url}"
        if public:
            warn_exposed(self.url)

    def close(self) -> None:
        self.canopen.close()
        self.server.close()


def _register() -> None:
    from motiontool.controller.drive.listeners import register_listener_scheme

    register_listener_scheme("canopen", SlcanListener, "canopen:slcan:socket://127.0.0.1:PORT",
                             "CANopen nodes behind an slcan (Lawicel) TCP server")


_register()
