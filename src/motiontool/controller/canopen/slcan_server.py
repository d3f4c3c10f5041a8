"""A CAN bus behind a TCP port that speaks the slcan (Lawicel) ASCII protocol, so that any python-can client
reaches it exactly as it reaches a USB-CAN adapter: ``can.Bus(interface="slcan", channel="socket://127.0.0.1:PORT")``.

The bus itself is a python-can ``virtual`` channel in this process: the virtual drive's CANopen nodes and its
bridge to the simulated controllers sit on it (server.py). Every client that has opened the channel (``O``) is one
more node on that bus: what it sends reaches the channel and the other clients, what the others send reaches it.

Lawicel commands served (each ends with CR; OK is CR, an error BEL): ``O`` / ``L`` open (``L`` listen only),
``C`` close, ``S0``-``S8`` and ``sxxyy`` bit rate (accepted; a client's lines are read as a 1 Mbit/s bus carries
frames, LINES_S), ``V``/``v`` version, ``N`` serial
number, ``F`` status flags, ``Z0``/``Z1`` time stamps, ``M``/``m`` acceptance filter (accepted, everything passes),
``tiiil…`` / ``Tiiiiiiiil…`` data frames and ``riiil`` / ``Riiiiiiiil`` remote frames (answered ``z``/``Z`` as an
adapter confirms a transmission). Frames to a client: ``tiiil<data>`` CR (``Z1`` appends a 16-bit ms stamp).
Listens on 127.0.0.1 only unless told otherwise.
"""

from __future__ import annotations

import contextlib
import socket
import threading
import time
from collections import deque

import can

from motiontool.comms.canopen.slcan import ERROR, MAX_LINE, OK, READ_SIZE, frame_text, parse_frame
from motiontool.controller.drive.listeners import refuse

VERSION, SERIAL = b"V1013\r", b"NMT15\r"
MAX_QUEUED = 1 << 20        # bytes waiting for one client (~45 000 frames) before its frames are dropped
MAX_CLIENTS = 16            # adapters' clients at once; more are closed at once
# A client's lines (frames, commands) are read no faster than a CAN bus carries frames: 1 Mbit/s full of 8-byte
# frames (~135 bits) is ~7 400 a second (shorter frames are faster on a real bus; no master needs that here). A
# client flooding frames or garbage lines is held back by TCP instead of taking the drive's cores from the other
# clients; a master that waits for answers never reaches it. Bytes without a CR are not lines: they are dropped at
# MAX_LINE, at little cost (decision N53).
LINES_S = 7_500
READ_SLACK_S = 0.2


def open_local_bus(interface: str, channel: str, ids: set[int] | None = None) -> can.BusABC:
    """A bus of this process: python-can's ``virtual`` (tests with a link in the same process) or the drive's
    hub (hub.py)."""
    if interface == "hub":
        from motiontool.controller.canopen.hub import HubBus

        return HubBus(channel, ids)
    return can.Bus(interface="virtual", channel=channel, receive_own_messages=False)




class _Client:
    def __init__(self, server: SlcanServer, sock: socket.socket):
        self.server, self.sock = server, sock
        self.open = False
        self.listen_only = False
        self.stamps = False
        self.alive = True
        self.overruns = 0                      # frames dropped because the client did not read them
        self._out: deque[bytes] = deque()
        self._queued = 0
        self._frames: list[can.Message] = []   # the frames of the lines read last, handed on together
        self._ready = threading.Condition()
        self._sending = False                  # the writer thread is sending what was queued
        threading.Thread(target=self._write_loop, name="slcan-client-out", daemon=True).start()

    def write(self, data: bytes) -> None:
        """Queue bytes for the client; a client that stops reading loses frames (as an adapter's receive buffer
        overruns) instead of stalling the bus for everyone."""
        with self._ready:
            if self._queued > MAX_QUEUED:
                self.overruns += 1
                return
            if not self._out and not self._sending:
                # what the socket takes now is sent from this thread: waking the writer for every answer kept a
                # flooded drive's threads waiting on each other (N55); the writer sends only what is left
                try:
                    data = data[self.sock.send(data, socket.MSG_DONTWAIT):]
                except (BlockingIOError, InterruptedError):
                    pass
                except OSError:
                    self.alive = False
                    return
                if not data:
                    return
            self._out.append(data)
            self._queued += len(data)
            self._ready.notify()

    def _write_loop(self) -> None:
        while self.alive:
            with self._ready:
                while not self._out and self.alive:
                    self._ready.wait(0.5)
                data = b"".join(self._out)
                self._out.clear()
                self._queued = 0
                self._sending = bool(data)
            if data:
                try:
                    self.sock.sendall(data)
                except OSError:
                    self.alive = False
                with self._ready:
                    self._sending = False

    def stop(self) -> None:
        with self._ready:
            self.alive = False
            self._ready.notify()

    def serve(self) -> None:
        buffer = b""
        bus_free = 0.0       # when the bus would have carried what this client sent so far
        try:
            while self.alive and not self.server.closed:
                chunk = self.sock.recv(READ_SIZE)
                if not chunk:
                    break
                buffer += chunk
                *lines, buffer = buffer.split(b"\r")
                answers = [self.command(line.decode("ascii", "replace").strip()) if len(line) <= MAX_LINE
                           else ERROR for line in lines if line.strip()]
                if len(buffer) > MAX_LINE:   # no CR in sight: not slcan; refused, and not kept
                    buffer = b""
                    answers.append(ERROR)
                if self._frames:
                    frames, self._frames = self._frames, []
                    self.server.transmit(frames, self)
                if answers:
                    self.write(b"".join(answers))
                now = time.monotonic()     # then the bus is busy carrying what was read
                bus_free = max(bus_free, now) + chunk.count(b"\r") / LINES_S
                if bus_free - now > READ_SLACK_S:
                    time.sleep(bus_free - now - READ_SLACK_S)
        except OSError:
            pass
        finally:
            self.stop()
            self.server.forget(self)
            with contextlib.suppress(OSError):
                self.sock.close()

    def command(self, line: str) -> bytes:
        head = line[:1]
        if head in ("t", "T", "r", "R"):
            msg = parse_frame(line)
            if msg is None or not self.open or self.listen_only:
                return ERROR
            self._frames.append(msg)
            return (b"Z" if head in ("T", "R") else b"z") + OK
        if head in ("O", "L"):
            self.open, self.listen_only = True, head == "L"
            return OK
        if head == "C":
            self.open = False
            return OK
        if head in ("S", "s", "M", "m", "X", "W"):
            return OK
        if head == "Z":
            self.stamps = line[1:2] == "1"
            return OK
        if head in ("V", "v"):
            return VERSION
        if head == "N":
            return SERIAL
        if head == "F":
            return b"F00" + OK
        return ERROR


class SlcanServer:
    """The TCP server; `url` is the python-can channel (``socket://127.0.0.1:PORT``)."""

    def __init__(self, channel: str, host: str = "127.0.0.1", port: int = 0, interface: str = "virtual"):
        self.channel = channel
        self.bus = open_local_bus(interface, channel)
        self.closed = False
        self.clients: list[_Client] = []
        self._clients_lock = threading.Lock()
        self.frames_in = self.frames_out = 0
        self.refused = 0
        self.on_disconnect: list = []          # called with the SDO request COB-IDs whose client went away
        self._sdo_clients: dict[int, _Client] = {}   # COB-ID → the client that sent its last SDO request
        self._listener = socket.create_server((host, port), family=socket.AF_INET6 if ":" in host else socket.AF_INET)
        self.host, self.port = self._listener.getsockname()[:2]
        self._threads = [threading.Thread(target=self._accept, name="slcan-accept", daemon=True),
                         threading.Thread(target=self._pump, name="slcan-pump", daemon=True)]
        for thread in self._threads:
            thread.start()

    @property
    def url(self) -> str:
        return f"socket://[{self.host}]:{self.port}" if ":" in self.host else f"socket://{self.host}:{self.port}"

    def _accept(self) -> None:
        while not self.closed:
            try:
                sock, _ = self._listener.accept()
            except OSError:
                return
            with self._clients_lock:
                full = len(self.clients) >= MAX_CLIENTS
            if full:
                self.refused = refuse(sock, f"canopen:slcan:{self.url}", MAX_CLIENTS, "clients", self.refused)
                continue
            sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            client = _Client(self, sock)
            with self._clients_lock:
                self.clients.append(client)
            threading.Thread(target=client.serve, name="slcan-client", daemon=True).start()

    def forget(self, client: _Client) -> None:
        with self._clients_lock:
            if client in self.clients:
                self.clients.remove(client)
            cob_ids = [n for n, c in self._sdo_clients.items() if c is client]
            for n in cob_ids:
                del self._sdo_clients[n]
        if cob_ids:
            for callback in self.on_disconnect:
                callback(cob_ids)

    def _receivers(self, sender: _Client | None) -> list[_Client]:
        with self._clients_lock:
            return [c for c in self.clients if c is not sender and c.open and c.alive]

    def transmit(self, frames: list[can.Message], sender: _Client) -> None:
        """Frames a client sent in one read: onto the bus, and to the other clients in one write each (a write per
        frame woke its writer per frame: 40 % of a flooded drive's profile, N55)."""
        self.frames_in += len(frames)
        for msg in frames:
            if 0x601 <= msg.arbitration_id <= 0x67F or 0x101 <= msg.arbitration_id <= 0x17F:   # SDO 1, 2 requests
                self._sdo_clients[msg.arbitration_id] = sender
            self.bus.send(msg)
        for client in self._receivers(sender):
            client.write(b"".join(frame_text(msg, client.stamps) for msg in frames))

    def _pump(self) -> None:
        """Frames from the bus to every open client, in batches (one write per client for all that waited)."""
        bus = self.bus
        while not self.closed:
            msg = bus.recv(timeout=0.2)
            if msg is None:
                continue
            batch = [msg]
            while len(batch) < 256 and (more := bus.recv(timeout=0)) is not None:
                batch.append(more)
            self.frames_out += len(batch)
            for client in self._receivers(None):
                client.write(b"".join(frame_text(m, client.stamps) for m in batch))

    def close(self) -> None:
        self.closed = True
        # shutdown wakes the thread blocked in accept(); on Linux a close() alone does not, and the join below
        # then waited its full 2 s at every close (a drive's SIGTERM, every test's teardown)
        with contextlib.suppress(OSError):
            self._listener.shutdown(socket.SHUT_RDWR)
        with contextlib.suppress(OSError):
            self._listener.close()
        with self._clients_lock:
            clients = list(self.clients)
        for client in clients:
            with contextlib.suppress(OSError):
                client.sock.shutdown(socket.SHUT_RDWR)
        for thread in self._threads:
            thread.join(timeout=2.0)
        self.bus.shutdown()
