"""CanopenLink: a controller over CANopen, on python-canopen's RemoteNode over any python-can interface
(issue 15 item 2). ``--link canopen:INTERFACE:CHANNEL[#NODE][,OPTION=VALUE…]``, e.g.
``canopen:slcan:socket://127.0.0.1:4002#1``, ``canopen:socketcan:can0#3``, ``canopen:pcan:PCAN_USBBUS1#1``.

- parameters by expedited SDO on their objects (0x2000 + number, docs/protocols/canopen.md);
- every other request of the link protocol as a message through the DOMAIN 0x5F00 (write, then read the answer;
  segmented SDO), events by polling as every wire link does (comms/remote.py);
- Free Run (`stream`) as TxPDOs (freerun.py);
- opening and reading change nothing on the node (decision N50): the link watches the heartbeat the node already
  produces (0x1017, read) and reports "lost connection" when none came for the consumer time, and that the
  connection is back when heartbeats return; a node without one is guarded (a remote frame every 100 ms) while
  anything subscribes to the link, else watched by the link's own SDO requests. Only
  ``heartbeat=MS`` sets 0x1017 (restored on close), and only Free Run sends NMT Start to a node that is not
  OPERATIONAL (PDOs travel only then; said as a message, the node's state restored on close); after a boot-up the
  link sets up again what it had asked for; a transport that broke is opened again by itself.
- a lost connection is a pause (decision N54): a transfer under way stops waiting as soon as the loss is known (the
  heartbeat or guarding silence, the transport's end) with "lost connection to CANopen node N: …", and while lost
  the link asks by node guarding (read-only) whether the node is back, whoever subscribes.

Options: ``heartbeat=MS`` (producer time to set; default: leave the node's), ``consumer=MS`` (default 1000 or five
producer times),
``timeout=S`` (SDO answer timeout, default 1), ``bitrate=BIT/S``, ``eds=PATH`` (default the shipped EDS),
``sdo=1|2`` (the SDO channel: 2 is the node's second SDO server 0x1201, for a second master such as the IDE beside
the command line, decision N52).
"""

from __future__ import annotations

import contextlib
import logging
import struct
import threading
import time
from typing import Any

import can
import canopen
from canopen.objectdictionary import ODVariable
from canopen.sdo import SdoAbortedError, SdoCommunicationError

from motiontool.comms.canopen import objects
from motiontool.comms.canopen.block_upload import block_upload
from motiontool.comms.canopen.freerun import PdoStream
from motiontool.comms.canopen.slcan import SlcanSocketBus
from motiontool.comms.canopen.watch import TransportWatch, answer_reader, sent_at
from motiontool.comms.links import LinkSpec, register_link_scheme
from motiontool.comms.protocol import ConnectionLost, LinkError, LinkEvent, Request
from motiontool.comms.remote import RemoteLink
from motiontool.paramdb import ParameterError, database

# python-canopen logs a client-side abort (e.g. "Transfer aborted by client with code 0x05040001") with no handler
# configured, so Python printed it raw on stderr; the link says what went wrong in its own error
logging.getLogger("canopen").addHandler(logging.NullHandler())

PARAMETER_BASE = 0x2000
MESSAGE_TIMEOUT_S = 10.0   # the answer to a link message (it is carried out before the answer)
CONSUMER_MS = 1000   # default heartbeat consumer time: a loaded machine can hold a drive up for a few hundred ms
GUARD_S = 0.1        # node guarding of a node without a heartbeat, while something watches the link
NMT_NAMES = {4: "STOPPED", 5: "OPERATIONAL", 127: "PRE-OPERATIONAL"}
NMT_BACK = {4: 0x02, 127: 0x80}   # the NMT command that returns a node to a state it was in
ABORT_ERRORS = {0x06010002: 112, 0x06020000: 112, 0x06090030: 183, 0x06090031: 183, 0x06090032: 183}
OPTIONS = {"heartbeat", "consumer", "timeout", "bitrate", "eds", "client", "sdo"}
SDO_COB_IDS = {1: (0x600, 0x580), 2: (0x100, 0x680)}   # client → server, server → client (DG 7323-7325)
# how long a request on SDO 2 waits before the link takes it to be off and enables it: a node answers in ms, but a
# busy machine's scheduler does not - at 0.3 s a clean-clone run took an enabled server for a silent one and then
# failed to write it between another master's transfers
SDO2_PROBE_S = 1.0
COLLISION_S = 2.0       # another master's request this recent explains a transfer that went wrong
ENABLE_TRIES, QUIET_S = 10, 0.015  # enabling SDO 2 through channel 1 waits for a pause of the other master there


def open_bus(interface: str, channel: str, bitrate: int | None = None, client: str = "fast") -> can.BusABC:
    """A python-can bus; slcan over TCP goes through SlcanSocketBus (the same protocol, buffered reads, decision
    N13) unless `client` is "python-can"."""
    if interface == "slcan" and channel.startswith("socket://") and client != "python-can":
        return SlcanSocketBus(channel)
    kwargs: dict[str, Any] = {"interface": interface, "channel": channel}
    if bitrate:
        kwargs["bitrate"] = bitrate
    if interface == "slcan":
        kwargs["sleep_after_open"] = 0 if channel.startswith("socket://") else 2
    return can.Bus(**kwargs)


class CanopenLink(RemoteLink):
    kind = "canopen"

    def __init__(self, interface: str, channel: str, node: int = 1, *, heartbeat_ms: int | None = None,
                 consumer_ms: int | None = None, sdo_timeout_s: float = 1.0, bitrate: int | None = None,
                 eds_path: str | None = None, client: str = "fast", sdo_channel: int = 1):
        if not 1 <= node <= 127:
            raise LinkError(f"CANopen node id {node}: 1..127")
        if sdo_channel not in SDO_COB_IDS:
            raise LinkError(f"CANopen SDO channel {sdo_channel}: 1 or 2")
        self.sdo_channel = sdo_channel
        self._foreign_request: dict[int, float] = {}   # COB-ID → when another master's frame was last seen there
        self.interface, self.channel, self.node_id = interface, channel, node
        self.bitrate, self.client = bitrate, client
        self.heartbeat_ms = heartbeat_ms
        self._consumer_ms = consumer_ms
        self.consumer_ms = consumer_ms or CONSUMER_MS
        self._producer_ms = 0
        self._last_guard = 0.0
        self._beat_seen = threading.Event()          # a heartbeat or guarding answer came (_nmt_state waits)
        self._saved_heartbeat: bytes | None = None    # 0x1017 before the link set it (restored on close)
        self._started_from: int | None = None         # the NMT state Free Run's NMT Start left (restored on close)
        self.sdo_timeout_s = sdo_timeout_s
        self.od = canopen.import_od(str(eds_path or objects.eds_path()), node)
        self._sdo_lock = threading.RLock()
        self._last_beat: float | None = None
        self._state: int | None = None
        self._rebooted = False
        self._blocks = True              # until the node shows it does not serve block transfers
        self._stream_request: tuple[list[str], int] | None = None
        self._cut: str | None = None                  # why waiting transfers stop: the link lost the node
        self._transport_error: Exception | None = None
        self._long_transfer = False                   # a link message under way (its answer may take 10 s)
        super().__init__(self._exchange, f"CANopen node {node} on {interface}:{channel}")
        self._connect()
        try:
            if sdo_channel == 2:
                self._enable_sdo2()
            self.pdo_stream = PdoStream(self.remote.sdo, self.network, node, self.od, self._publish)
            self._configure()
        except BaseException:     # an open that fails leaves no slcan client on the drive (it takes 16)
            self._disconnect()
            raise
        self._watch = threading.Thread(target=self._watchdog, name="canopen-heartbeat", daemon=True)
        self._watch.start()

    # --- the transport ----------------------------------------------------------------------------------
    def _connect(self) -> None:
        try:
            bus = open_bus(self.interface, self.channel, self.bitrate, self.client)
        except (can.CanError, OSError, ValueError) as exc:
            raise ConnectionLost(f"cannot open {self.interface}:{self.channel}: {exc}") from None
        self.network = network = canopen.Network(bus)
        if isinstance(bus, SlcanSocketBus):     # only what the link subscribes to (its node, its PDOs)
            bus.wanted = lambda can_id, extended: not extended and can_id in network.subscribers
        self._transport_error = None
        watch = TransportWatch(self._on_transport_error)
        self.network.notifier = watch.notifier = can.Notifier(bus, [*self.network.listeners, watch], 0.5)
        self.remote = canopen.RemoteNode(self.node_id, self.od)
        if self.sdo_channel != 1:
            rx, tx = SDO_COB_IDS[self.sdo_channel]
            self.remote.sdo = self.remote.add_sdo(rx + self.node_id, tx + self.node_id)
        self.remote.sdo.RESPONSE_TIMEOUT = self.sdo_timeout_s
        self.network.add_node(self.remote)
        for client in self.remote.sdo_channels:      # python-canopen gives its network to `sdo` only
            client.network = self.network
            client.read_response = answer_reader(client, lambda: self._cut)
        if self.sdo_channel != 1:     # channel 1's answers (another master's) would pile up in its queue unread
            first = self.remote.sdo_channels[0]
            self.network.unsubscribe(first.tx_cobid, first.on_response)
        self.remote.nmt.add_heartbeat_callback(self._on_heartbeat)
        # our adapter does not hand us our own frames: a request on our channel is another master's
        self.network.subscribe(self.remote.sdo.rx_cobid, self._on_foreign_request)
        if hasattr(self, "pdo_stream"):      # a new transport: the link sets the node up again when it answers
            self.pdo_stream.sdo, self.pdo_stream.network = self.remote.sdo, self.network
            self._rebooted = True

    def _on_transport_error(self, exc: Exception) -> None:
        self._transport_error = exc

    def _on_foreign_request(self, can_id, data, timestamp) -> None:
        self._foreign_request[can_id] = time.monotonic()

    def _collision(self, channel: int | None = None) -> LinkError | None:
        """Two masters on one SDO channel take each other's answers (CiA 301 allows one client per server): said in
        words when another master's request came while ours went wrong."""
        channel = channel or self.sdo_channel
        if time.monotonic() - self._foreign_request.get(SDO_COB_IDS[channel][0] + self.node_id, 0) > COLLISION_S:
            return None
        return LinkError(f"another master uses SDO channel {channel} of CANopen node {self.node_id}; "
                         f"use ,sdo={2 if channel == 1 else 1} on one of them")

    def _enable_sdo2(self) -> None:
        """The second SDO server answers once 0x1201 is valid (DG 7327-7335): ask it; if it is silent, clear
        NOT_VALID through the first channel, between the other master's transfers there, and say so. It stays
        valid on close: another master may be using it (decision N52)."""
        probe = self.remote.sdo
        probe.RESPONSE_TIMEOUT = min(self.sdo_timeout_s, SDO2_PROBE_S)
        try:
            probe.upload(0x1201, 1)
            return
        except (SdoCommunicationError, SdoAbortedError, can.CanError, OSError):
            pass
        finally:
            probe.RESPONSE_TIMEOUT = self.sdo_timeout_s
        first = self.remote.sdo_channels[0]
        first.RESPONSE_TIMEOUT = self.sdo_timeout_s
        self.network.subscribe(first.rx_cobid, self._on_foreign_request)
        self.network.subscribe(first.tx_cobid, self._on_foreign_request)   # answers to the other master too
        self.network.subscribe(first.tx_cobid, first.on_response)
        try:
            for attempt in range(ENABLE_TRIES):
                self._quiet(first.rx_cobid, first.tx_cobid)
                try:
                    for sub, base in ((1, 0x100), (2, 0x680)):
                        first.download(0x1201, sub, (base + self.node_id).to_bytes(4, "little"))
                    break
                except (SdoCommunicationError, SdoAbortedError) as exc:
                    busy = self._collision(1)
                    if busy is None and "Unexpected response" in str(exc):
                        # an answer to no request of ours is another master's, whether or not its request was seen
                        # (at load 8 it came before the notifier had stamped the request)
                        busy = LinkError(f"another master uses SDO channel 1 of CANopen node {self.node_id}; "
                                         "use ,sdo=2 on one of them")
                    if busy is None:
                        if isinstance(exc, SdoAbortedError):
                            raise LinkError(f"CANopen node {self.node_id} refused to enable its second SDO server "
                                            f"(0x1201): {exc}") from None
                        raise ConnectionLost(f"CANopen node {self.node_id} does not answer: {exc}") from None
                    if attempt == ENABLE_TRIES - 1:
                        raise LinkError(f"{busy}: its second SDO server (0x1201) could not be enabled between the "
                                        "other master's transfers; enable it there or in the program (DG 7339)"
                                        ) from None
        finally:
            self.network.unsubscribe(first.tx_cobid, first.on_response)
            self.network.unsubscribe(first.tx_cobid, self._on_foreign_request)
            self.network.unsubscribe(first.rx_cobid, self._on_foreign_request)
        self._publish(LinkEvent("message", 0, f"CANopen node {self.node_id}: second SDO server enabled (0x1201 "
                                              f"= 0x{0x100 + self.node_id:X} / 0x{0x680 + self.node_id:X})"))

    def _quiet(self, *cob_ids: int) -> None:
        """Wait (up to a few seconds) until no frame came on these COB-IDs for QUIET_S: the other master's transfer
        is over."""
        deadline = time.monotonic() + 3.0
        while time.monotonic() < deadline:
            last = max(self._foreign_request.get(c, 0) for c in cob_ids)
            if time.monotonic() - last >= QUIET_S:
                return
            time.sleep(QUIET_S / 5)

    def _disconnect(self) -> None:
        notifier, bus = self.network.notifier, self.network.bus
        if notifier is not None:
            with contextlib.suppress(Exception):
                notifier.stop(1.0)
        if bus is not None:
            with contextlib.suppress(Exception):
                bus.shutdown()

    def _configure(self) -> None:
        """What the link was asked to change (a heartbeat time; NMT Start once Free Run needed it), else only
        reads: the producer time the node has decides how long a silence may be."""
        with self._sdo_lock:
            current = bytes(self._sdo(lambda sdo: sdo.upload(0x1017, 0)))
            if self.heartbeat_ms is not None:
                if self._saved_heartbeat is None:
                    self._saved_heartbeat = current
                self._sdo(lambda sdo: sdo.download(0x1017, 0, self.heartbeat_ms.to_bytes(2, "little")))
            producer = self.heartbeat_ms if self.heartbeat_ms is not None else int.from_bytes(current, "little")
            self._producer_ms = producer
            self.consumer_ms = self._consumer_ms or max(CONSUMER_MS, 5 * producer)
            if self._started_from is not None:
                self.network.send_message(0, bytes([0x01, self.node_id]))

    def _nmt_state(self) -> int | None:
        """The node's NMT state by node guarding (a remote frame on 0x700 + id: it reads, it changes nothing)."""
        self._beat_seen.clear()
        self.network.send_message(0x700 + self.node_id, b"", remote=True)
        return self._state if self._beat_seen.wait(max(self.sdo_timeout_s, 0.5)) else None

    def _make_operational(self) -> None:
        """Free Run's PDOs travel only in OPERATIONAL: start a node that is not, say so, remember to restore it."""
        state = self._nmt_state()
        if state in (None, 5):
            return
        self._started_from = state
        self.network.send_message(0, bytes([0x01, self.node_id]))
        self._publish(LinkEvent("message", 0, f"CANopen node {self.node_id} was {NMT_NAMES.get(state, state)}: "
                                              "NMT Start for Free Run (PDOs travel only when OPERATIONAL); it goes "
                                              "back when the link closes"))

    def _restore_node(self) -> None:
        """Give back what the link changed (CANopen cannot go back to INITIALISING; everything else it can)."""
        with contextlib.suppress(LinkError):
            if self._saved_heartbeat is not None:
                saved = self._saved_heartbeat
                self._sdo(lambda sdo: sdo.download(0x1017, 0, saved))
            if self._started_from in NMT_BACK:
                self.network.send_message(0, bytes([NMT_BACK[self._started_from], self.node_id]))

    def _sdo(self, action):
        """Run an SDO action; a missing answer is ConnectionLost, an abort a LinkError with the controller's
        error number where there is one."""
        if self._lost and not self._virtual_clock():   # on a virtual clock no heartbeat says it is back: ask
            raise ConnectionLost(self._cut or f"lost connection to CANopen node {self.node_id}: it does not answer")
        with self._sdo_lock:
            started = time.monotonic()
            try:
                result = action(self.remote.sdo)
                # another master's request on our channel while ours ran: the answer we took may be its answer
                # (the same object read by both is indistinguishable), so say the collision instead of a value
                if self._foreign_request.get(self.remote.sdo.rx_cobid, 0) >= started:
                    raise self._collision() or LinkError("another master used the SDO channel during the transfer")
                return result
            except (SdoCommunicationError, can.CanError, OSError) as exc:
                if self._cut:     # the heartbeat or the transport said so first: in words, not as a socket error
                    raise ConnectionLost(self._cut) from None
                if not isinstance(exc, SdoCommunicationError):
                    raise ConnectionLost(f"lost connection to CANopen node {self.node_id}: its CAN interface "
                                         f"{self.interface}:{self.channel} failed ({exc})") from None
                raise self._collision() or ConnectionLost(f"CANopen node {self.node_id} does not answer: {exc}") \
                    from None
            except SdoAbortedError as exc:
                raise self._collision() or LinkError(f"CANopen node {self.node_id} refused: {exc}",
                                                     ABORT_ERRORS.get(exc.code, 0)) from None

    def _exchange(self, message: bytes) -> bytes:
        def transfer(sdo):
            # the node answers a message when it has carried it out (an `advance` of a virtual clock computes
            # first): wait longer than for a parameter; a silent node is still seen by the heartbeat at once
            sdo.RESPONSE_TIMEOUT = max(self.sdo_timeout_s, MESSAGE_TIMEOUT_S)
            if not (self._producer_ms or self._subscribers):   # a silence is counted from here (N54)
                self._last_beat = max(self._last_beat or 0.0, time.monotonic())
            self._long_transfer = True
            try:
                self._write_domain(sdo, objects.LINK_MESSAGE, message)
                return self._read_domain(sdo, objects.LINK_MESSAGE)
            finally:
                sdo.RESPONSE_TIMEOUT = self.sdo_timeout_s
                self._long_transfer = False
        return self._sdo(transfer)

    # DOMAIN objects by block transfer where the node serves it (N14), else segmented
    def _write_domain(self, sdo, index: int, data: bytes) -> None:
        if self._blocks and len(data) > 4:
            try:
                with sdo.open(index, 0, "wb", buffering=0, size=len(data), block_transfer=True) as raw:
                    view = memoryview(data)
                    while view:
                        view = view[raw.write(view[:7]) or 7:]
                return
            except (SdoAbortedError, SdoCommunicationError) as exc:
                if not _no_blocks(exc) or self._collision():   # another master's answer is no refusal
                    raise
                self._blocks = False
        sdo.download(index, 0, data)

    def _read_domain(self, sdo, index: int) -> bytes:
        if self._blocks:
            try:
                return block_upload(sdo, index)
            except (SdoAbortedError, SdoCommunicationError) as exc:
                if not _no_blocks(exc) or self._collision():   # another master's answer is no refusal
                    raise
                self._blocks = False
        return sdo.upload(index, 0)

    # --- requests -----------------------------------------------------------------------------------------
    def request(self, request: Request) -> Any:
        if self._closed.is_set():
            raise ConnectionLost("the link is closed")
        op, args = request.op, request.args
        if op == "read_parameter":
            return self._read_parameter(args["key"])
        if op == "write_parameter":
            return self._write_parameter(args["key"], args["value"])
        if op == "stream":
            return self._stream(list(args.get("signals") or []), int(args.get("interval_ms", 1)))
        return super().request(request)

    def _parameter(self, key):
        try:
            p = database().get(key)
        except ParameterError:
            raise LinkError(f"unknown parameter {key}", 112) from None
        return p, self.od[PARAMETER_BASE + p.index]

    def _read_parameter(self, key) -> int:
        p, var = self._parameter(key)
        return var.decode_raw(self._sdo(lambda sdo: sdo.upload(var.index, 0)))

    def _write_parameter(self, key, value) -> None:
        p, var = self._parameter(key)
        try:
            data = var.encode_raw(int(value))
        except (struct.error, OverflowError, ValueError):
            data = None
        try:
            if data is None:
                raise LinkError(f"{p.label}: {value} does not fit the parameter's type", 183)
            self._sdo(lambda sdo: sdo.download(var.index, 0, data))
        except LinkError as exc:
            if exc.number != 183:
                raise
            try:    # the reason in the words the controller uses (ParameterStore.set validates the same way)
                p.validate(value * 10 ** p.conversion_index if p.conversion_index else value)
            except ParameterError as reason:
                raise LinkError(str(reason), 183) from None
            raise

    def read_object(self, index: int, sub: int = 0):
        """One object by SDO, decoded as the EDS says (an integer, a text or bytes)."""
        entry = self.od[index]
        if isinstance(entry, ODVariable):
            if sub:
                raise LinkError(f"object 0x{index:04X} has no sub-index {sub}")
            var = entry
        else:
            var = entry[sub]
        return var.decode_raw(self._sdo(lambda sdo: sdo.upload(index, sub)))

    def _stream(self, signals: list[str], interval_ms: int) -> None:
        """Free Run over PDOs; an empty list stops it."""
        self._stream_request = (signals, interval_ms) if signals else None
        with self._sdo_lock:
            try:
                if signals:
                    self._make_operational()
                    self.pdo_stream.start(signals, interval_ms)
                else:
                    self.pdo_stream.stop()
            except SdoCommunicationError as exc:
                raise ConnectionLost(f"CANopen node {self.node_id} does not answer: {exc}") from None
            except SdoAbortedError as exc:
                raise LinkError(f"CANopen node {self.node_id} refused the PDO set-up: {exc}") from None

    # --- heartbeat consumer --------------------------------------------------------------------------------
    def _on_heartbeat(self, state: int) -> None:
        known = self._last_beat is not None
        self._last_beat, self._state = sent_at(self.remote.nmt.timestamp), state
        self._beat_seen.set()
        if state == 0 and known:       # a boot-up of a node we knew: the drive lost what the link set up
            self._rebooted = True
            if not self._lost:
                threading.Thread(target=self._restore, args=("the controller started again",), daemon=True).start()

    def _silent(self) -> bool:
        beat = self._last_beat
        return beat is None or time.monotonic() - beat > self.consumer_ms / 1000

    def _set_connection(self, *, lost: bool, text: str = "") -> None:
        """Where heartbeats (or guarding answers) are watched, they alone say the node is back: an SDO answer while
        they are silent (the drive's link messages are served while its clock stands still) made the link flap
        between lost and restored."""
        watched = self._producer_ms or self._subscribers
        if not lost and self._lost and watched and self._silent():
            return
        if not lost:
            self._cut = None
        super()._set_connection(lost=lost, text=text)

    def _lose(self, reason: str, event_reason: str) -> None:
        """The node is gone (no heartbeat, the transport ended): transfers waiting for its answers stop now, in
        words (a download waited its full 10 s after kill -9 of the drive, then said 'Bad file descriptor')."""
        self._cut = f"lost connection to CANopen node {self.node_id}: {reason}"
        for client in self.remote.sdo_channels:
            client.responses.put(None)
        self._set_connection(lost=True, text=self.lost_text(event_reason))

    def _watchdog(self) -> None:
        while not self._closed.wait(0.05):
            error = self._transport_error
            if error is not None:          # the interface ended (the slcan server went away): open it again
                if not self._lost:
                    where = f"{self.interface}:{self.channel}"
                    self._lose(f"its CAN interface {where} failed ({error})", f"CAN interface {where}: {error}")
                self._reopen()
                continue
            if self._virtual_clock():
                continue
            if self._lost:     # a pause: ask (read-only) until the node answers, whoever subscribes and whatever
                self._guard()  # heartbeat the node has now (a restarted one has none)
                if not self._silent():
                    self._restore("heartbeats again")
                continue
            if not self._producer_ms:      # no heartbeat of its own: a watching master (one that subscribes, as
                if not (self._subscribers or self._long_transfer and self._identity is not None):  # the IDE),
                    continue   # or one waiting up to 10 s for an answer, asks by node guarding, changing nothing
                self._guard()
            if self._silent() and self._last_beat is not None:
                what = "heartbeat" if self._producer_ms else "answer to node guarding"
                self._lose(f"no {what} for {self.consumer_ms} ms",
                           f"no {what} from CANopen node {self.node_id} for {self.consumer_ms} ms")

    def _guard(self) -> None:
        now = time.monotonic()
        if now - self._last_guard >= GUARD_S:
            self._last_guard = now
            with contextlib.suppress(can.CanError, OSError):
                self.network.send_message(0x700 + self.node_id, b"", remote=True)

    def _virtual_clock(self) -> bool:
        return self._identity is not None and self._identity.clock == "virtual"

    def _reopen(self) -> None:
        """The transport broke (e.g. the slcan server went away): open it again, once a second."""
        if self._closed.wait(1.0):
            return
        self._disconnect()
        with contextlib.suppress(ConnectionLost):
            self._connect()

    def _restore(self, why: str) -> None:
        """Heartbeats again: after a boot-up or a new transport set the node up again (heartbeat, NMT, the Free Run
        PDOs); after a pause (a stopped process) it still has all that. Then say so."""
        rebooted, self._rebooted = self._rebooted, False
        lost, self._lost = self._lost, False      # the set-up below talks to the node
        cut, self._cut = self._cut, None
        try:
            if rebooted:
                if self.sdo_channel == 2:       # a restarted node has SDO 2 NOT_VALID again
                    self._enable_sdo2()
                self._configure()
                if self._stream_request is not None:
                    self._stream(*self._stream_request)
        except LinkError:
            self._lost, self._rebooted, self._cut = lost, rebooted, cut
            return
        self._lost = lost
        self._set_connection(lost=False, text=self.restored_text(why) if self.patience_s > 0 else
                             f"Connection to CANopen node {self.node_id} restored ({why})")

    def close(self) -> None:
        if not self._closed.is_set() and not self._lost:
            if self.pdo_stream.running:
                with contextlib.suppress(LinkError):
                    self._stream([], 1)
            self._restore_node()
        super().close()
        self._watch.join(timeout=2.0)
        self._disconnect()


def _no_blocks(exc: Exception) -> bool:
    """The node answered a block request as a node without block transfers does."""
    if isinstance(exc, SdoAbortedError):
        return exc.code == 0x05040001
    return "Unexpected response" in str(exc)


def scan(interface: str, channel: str, ids=range(1, 128), wait_s: float = 0.3, bitrate: int | None = None
         ) -> list[int]:
    """Node ids that answer an SDO request for 0x1000 (device type), in ascending order."""
    bus = open_bus(interface, channel, bitrate)
    network = canopen.Network(bus)
    network.notifier = notifier = can.Notifier(bus, network.listeners, 0.5)
    try:
        found: set[int] = set()
        for node in ids:
            network.subscribe(0x580 + node, lambda can_id, data, ts: found.add(can_id - 0x580))
            network.send_message(0x600 + node, bytes([0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]))
        time.sleep(wait_s)
        return sorted(found)
    finally:
        notifier.stop(1.0)
        bus.shutdown()


def open_canopen(spec: LinkSpec) -> CanopenLink:
    """`canopen:INTERFACE:CHANNEL[#NODE]` (comms/links.py)."""
    spec.check_options(OPTIONS)
    interface, _, channel = spec.target.partition(":")
    if not interface or not channel:
        raise LinkError(f"link '{spec.text}': give canopen:INTERFACE:CHANNEL[#NODE], e.g. "
                        "canopen:slcan:socket://127.0.0.1:4002#1 or canopen:socketcan:can0#3")
    heartbeat = spec.option("heartbeat", None, int, 0, 65535)   # 0x1017 is an UNSIGNED16 in ms
    return CanopenLink(interface, channel, spec.node or 1, heartbeat_ms=heartbeat,
                       consumer_ms=spec.option("consumer", None, int, 0, 65535),
                       sdo_timeout_s=spec.option("timeout", 1.0, float, 0.001, 60),
                       bitrate=spec.option("bitrate", None, int, 10_000, 1_000_000), eds_path=spec.option("eds", None),
                       client=spec.option("client", "fast"), sdo_channel=spec.option("sdo", 1, int, 1, 2))


def scan_spec(spec: LinkSpec, ids) -> list[int]:
    """The IDE's scan range (comms/links.py scan_controllers): nodes answering an SDO request for 0x1000."""
    interface, _, channel = spec.target.partition(":")
    return scan(interface, channel, [n for n in ids if 1 <= n <= 127],
                bitrate=spec.option("bitrate", None, int, 10_000, 1_000_000))


register_link_scheme("canopen", open_canopen, "canopen:INTERFACE:CHANNEL[#NODE]",
                     "a controller over CANopen on any python-can interface (slcan, socketcan, pcan, virtual …)",
                     scan=scan_spec)
