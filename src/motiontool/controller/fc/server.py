"""The virtual drive on an FC bus: `motiontool drive --listen fc:socket://127.0.0.1:PORT` or `--listen fc:pty`.

`FcSlave` answers telegrams for every node of a VirtualDrive as the drives on one RS-485 cable would: each node
answers its own address (format 1 or 2, the ADR echoed), nobody answers a broadcast (a broadcast parameter write is
applied by every node), an address without a node stays silent. Parameter telegrams are the public protocol's;
text telegrams on the extension PNU carry Link messages (comms/fc/extension.py).

The TCP listener behaves like a serial-to-Ethernet converter with those nodes on its RS-485 side: a byte stream
in each direction, no framing of its own; several clients may connect, one telegram is answered at a time.
The pty listener opens a pseudo-terminal and serves its master side; its slave path is the port to open.
With ``,baud=N`` the answers are paced as the line would carry them (11 bits a character, request and answer).
"""

from __future__ import annotations

import contextlib
import os
import select
import socket
import threading
import time
from collections.abc import Callable

from motiontool.cliargs import shown
from motiontool.comms.chunks import SlaveChannel
from motiontool.comms.fc.extension import MAX_CHUNK, frame_telegram, is_frame, telegram_frame
from motiontool.comms.fc.telegram import (
    AK_NONE,
    AK_READ,
    AK_REFUSED,
    AK_VALUE_DWORD,
    AK_WRITE_DWORD,
    AK_WRITE_DWORD_EEPROM,
    AK_WRITE_WORD,
    AK_WRITE_WORD_EEPROM,
    Telegram,
    TelegramError,
    TelegramReader,
    decode_address,
    encode,
    parameter,
    wire_time,
)
from motiontool.comms.fc.values import from_pwe, to_pwe
from motiontool.comms.links import LinkSpec
from motiontool.comms.protocol import LinkError
from motiontool.controller.drive.listeners import exposed, listen_port, refuse, url_host, warn_exposed
from motiontool.kernel import fc300
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.fc300_table import FC_PARAMETERS
from motiontool.paramdb import ParameterError, database

WRITES = (AK_WRITE_WORD, AK_WRITE_DWORD, AK_WRITE_WORD_EEPROM, AK_WRITE_DWORD_EEPROM)
BUSY_AFTER_S = 0.02       # an extension request still running after this is answered BUSY
MAX_CONNECTIONS = 16      # masters at once on the TCP listener (a serial converter takes a few); more are closed
LINE_SLACK_S = 0.2         # what a paced connection may read ahead of its line before it waits
GAP_S = 0.05              # a partial telegram older than this is dropped (a character time-out, as UARTs do)


class FcSlave:
    """The nodes of a drive as FC slaves, for one master connection: `on_bytes(data) -> answer bytes`."""

    def __init__(self, drive, baud: int | None = None):
        self.drive = drive
        self.baud = baud
        self.reader = TelegramReader()
        self.channels: dict[int, SlaveChannel] = {}
        self.damaged = 0
        self._last_bytes = 0.0

    def on_bytes(self, data: bytes) -> list[bytes]:
        now = time.monotonic()
        if self.reader.buffer and now - self._last_bytes > GAP_S:
            self.reader.buffer.clear()
        self._last_bytes = now
        answers = []
        for item in self.reader.feed(data):
            if isinstance(item, TelegramError):
                self.damaged += 1       # a damaged telegram gets no answer; the master repeats it
                continue
            answer = self.on_telegram(item)
            if answer is not None:
                raw = encode(answer)
                if self.baud:
                    time.sleep(wire_time(len(encode(item)) + len(raw), self.baud))
                answers.append(raw)
        return answers

    def on_telegram(self, t: Telegram) -> Telegram | None:
        address, broadcast, _ = decode_address(t.adr)
        if broadcast:
            if t.pke is not None and t.ak in WRITES and t.text is None:
                for n in self.drive.nodes:
                    self._parameter(n, t)
            return None
        node = self.drive.nodes.get(address)
        if node is None:
            return None
        node.last_contact = time.monotonic()
        if t.text is not None:
            if not is_frame(t):
                return parameter(t.adr, AK_REFUSED, t.pnu, 253, t.ind)   # request not supported
            channel = self.channels.get(address)
            if channel is None:
                channel = self.channels[address] = SlaveChannel(node.handle_message, MAX_CHUNK, BUSY_AFTER_S)
            return frame_telegram(t.adr, channel.on_frame(telegram_frame(t)))
        if t.pke is None:                      # process block only: answer the status word
            return Telegram(t.adr, None, 0, 0, self._status_words(address))
        return self._parameter(address, t)

    def _status_words(self, address: int) -> tuple[int, int]:
        """PCD1 status word (bit 0 control ready, bit 1 drive ready, bit 7 warning = controller error pending,
        bit 11 running = a program runs), PCD2 the actual position's low word."""
        with self.drive.lock:
            c = self.drive.nodes[address].service.controller
            word = 0x0003 | (0x0080 if c.error else 0) | (0x0800 if c.program_state == "running" else 0)
            return word, int(c.axis.apos) & 0xFFFF

    def _parameter(self, address: int, t: Telegram) -> Telegram:
        service = self.drive.nodes[address].service
        pcd = self._status_words(address)
        if t.ak == AK_NONE:
            return parameter(t.adr, AK_NONE, t.pnu, 0, t.ind, pcd)
        if t.ak not in (AK_READ, *WRITES):
            return parameter(t.adr, AK_REFUSED, t.pnu, 253, t.ind, pcd)
        try:
            p = database().get(t.pnu)
        except ParameterError:
            if t.pnu in FC_PARAMETERS:   # the drive's own parameter (4-13 is PNU 413), beside the option's
                return self._drive_parameter(address, t, pcd)
            return parameter(t.adr, AK_REFUSED, t.pnu, 0, t.ind, pcd)
        try:
            with self.drive.lock:
                if t.ak in WRITES:
                    value = from_pwe(p, t.pwe, word=t.ak in (AK_WRITE_WORD, AK_WRITE_WORD_EEPROM))
                    if p.read_only:
                        return parameter(t.adr, AK_REFUSED, t.pnu, 1, t.ind, pcd)
                    service.controller.params.set(p.index, value, source="link")
                value = service.controller.params.get(p.index)
        except Exception as exc:  # noqa: BLE001 - the controller's refusal becomes an FC fault code
            code = 2 if getattr(exc, "number", 0) == 183 else 18
            return parameter(t.adr, AK_REFUSED, t.pnu, code, t.ind, pcd)
        ak, pwe = to_pwe(p, value)
        return parameter(t.adr, ak, t.pnu, pwe, t.ind, pcd)

    def _drive_parameter(self, address: int, t: Telegram, pcd) -> Telegram:
        """An FC 300 parameter, at the telegram's index (5-40 index 1), as GETVLTSUB/SETVLTSUB reach it."""
        controller = self.drive.nodes[address].service.controller
        try:
            with self.drive.lock:
                if t.ak in WRITES:
                    word = t.ak in (AK_WRITE_WORD, AK_WRITE_WORD_EEPROM)
                    value = t.pwe - (1 << 16 if word else 1 << 32) if t.pwe >> (15 if word else 31) else t.pwe
                    fc300.write(controller, t.pnu, t.ind, value)
                value = fc300.read(controller, t.pnu, t.ind)
        except ControllerError as exc:
            read_only = "read only" in str(exc)
            code = 1 if read_only else 3 if "no index" in str(exc) else 2 if exc.number == 183 else 18
            return parameter(t.adr, AK_REFUSED, t.pnu, code, t.ind, pcd)
        return parameter(t.adr, AK_VALUE_DWORD, t.pnu, value & 0xFFFFFFFF, t.ind, pcd)

    def close(self) -> None:
        for channel in self.channels.values():
            channel.close()


# --- listeners ---------------------------------------------------------------------------------------------------
class _Serving:
    """Runs `serve` on a daemon thread until close()."""

    url = ""

    def __init__(self) -> None:
        self._stop = threading.Event()
        self._threads: list[threading.Thread] = []

    def _spawn(self, target: Callable, *args) -> None:
        thread = threading.Thread(target=target, args=args, daemon=True, name=f"fc-{target.__name__}")
        self._threads = [t for t in self._threads if t.is_alive()]   # a connection's thread is kept while it serves
        self._threads.append(thread)
        thread.start()

    def close(self) -> None:
        self._stop.set()
        for thread in self._threads:
            thread.join(timeout=2.0)


class FcSocketListener(_Serving):
    def __init__(self, drive, host: str, port: int, baud: int | None):
        super().__init__()
        self.drive, self.baud = drive, baud
        self.refused = 0
        family = socket.AF_INET6 if ":" in host else socket.AF_INET
        self.server = socket.create_server((host, port), family=family)
        self.server.settimeout(0.1)
        host, port = self.server.getsockname()[:2]
        self.url = f"fc:socket://{url_host(host)}:{port}" + _baud(baud)
        self._spawn(self._accept)

    def _accept(self) -> None:
        while not self._stop.is_set():
            try:
                conn, _ = self.server.accept()
            except TimeoutError:
                continue
            except OSError:
                return
            serving = sum(t.is_alive() for t in self._threads) - 1       # less this accepting thread
            if serving >= MAX_CONNECTIONS:
                self.refused = refuse(conn, self.url, MAX_CONNECTIONS, "masters", self.refused)
                continue
            conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            self._spawn(self._serve, conn)
        self.server.close()

    def _serve(self, conn: socket.socket) -> None:
        slave = FcSlave(self.drive, self.baud)
        conn.settimeout(0.1)
        line_free = 0.0      # a paced connection: when its line would have carried what was read so far
        try:
            while not self._stop.is_set():
                try:
                    data = conn.recv(4096)
                except TimeoutError:
                    continue
                if not data:
                    return
                if self.baud:
                    # no faster than the line: a master that waits for answers never gets ahead of it, a client
                    # flooding garbage is held back by TCP instead of taking the drive's cores from the others
                    now = time.monotonic()
                    line_free = max(line_free, now) + wire_time(len(data), self.baud)
                    if line_free - now > LINE_SLACK_S:
                        time.sleep(line_free - now - LINE_SLACK_S)
                for answer in slave.on_bytes(data):
                    conn.sendall(answer)
        except OSError:
            return
        finally:
            slave.close()
            conn.close()


class FcPtyListener(_Serving):
    def __init__(self, drive, baud: int | None):
        import tty

        super().__init__()
        self.drive, self.baud = drive, baud
        self.master_fd, self.slave_fd = os.openpty()
        tty.setraw(self.slave_fd)    # no echo, no line editing: a byte stream like a serial line
        self.path = os.ttyname(self.slave_fd)
        self.url = f"fc:{self.path}" + _baud(baud)
        self._spawn(self._serve)

    def _serve(self) -> None:
        slave = FcSlave(self.drive, self.baud)
        try:
            while not self._stop.is_set():
                ready, _, _ = select.select([self.master_fd], [], [], 0.1)
                if not ready:
                    continue
                try:
                    data = os.read(self.master_fd, 4096)
                except OSError:        # no process has the slave side open at the moment
                    time.sleep(0.05)
                    continue
                for answer in slave.on_bytes(data):
                    os.write(self.master_fd, answer)
        finally:
            slave.close()

    def close(self) -> None:
        super().close()
        for fd in (self.master_fd, self.slave_fd):
            with contextlib.suppress(OSError):
                os.close(fd)


def _baud(baud: int | None) -> str:
    """The printed URL is what a master gives to --link: with the line's pace, so it times the line as it is."""
    return f",baud={baud}" if baud else ""


def open_fc_listener(spec: LinkSpec, drive):
    spec.check_options({"baud", "any_host"})
    baud = spec.option("baud", None, int)
    if spec.node is not None:
        raise LinkError(f"--listen '{spec.text}': a listener serves every node; give the nodes with --node")
    if spec.target == "pty":
        return FcPtyListener(drive, baud)
    if spec.target.startswith("socket://"):
        host, _, port = spec.target[len("socket://"):].rpartition(":")
        if not host or not port:
            raise LinkError(f"--listen '{shown(spec.text)}': give socket://HOST:PORT (PORT 0 picks a free port)")
        host = host.strip("[]")
        number = listen_port(spec, port)
        public = exposed(spec, host)
        try:
            listener = FcSocketListener(drive, host, number, baud)
        except OSError as exc:
            raise LinkError(f"--listen '{spec.text}': {exc}") from None
        if public:
            warn_exposed(listener.url)
        return listener
    raise LinkError(f"--listen '{spec.text}': fc listens on socket://HOST:PORT or on pty")


def _register() -> None:
    from motiontool.controller.drive.listeners import register_listener_scheme

    register_listener_scheme("fc", open_fc_listener, "fc:socket://HOST:PORT | fc:pty [,baud=N]",
                             "the nodes on an FC bus behind a TCP serial converter or a pseudo-terminal")


_register()
