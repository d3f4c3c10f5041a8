"""The master's side of an FC bus: one serial port (any pyserial URL) shared by every address on it.

`transact(telegram)` writes one telegram and waits for the slave's answer. A missing answer (timeout), a damaged
one (BCC, length, parity errors the UART reports as garbage) or one that does not echo the request (another
address, another PNU or sequence number — a late answer to an earlier try) is a failed try: the same telegram is
sent again after a back-off (10 ms, doubling), and after `retries` repeats the bus reports `ConnectionLost`.
A telegram identical to the request is the line's echo of it (a 2-wire RS-485 adapter hears what it sends) and
is passed over: an answer differs from its request (another AK, or the drive's status word in PCD1).
Repeating the same telegram is safe: parameter writes are idempotent and extension frames are deduplicated by the
slave (comms/chunks.py).

Several links on one port (controllers 1 and 2 on one RS-485 cable) share one `FcBus`: `FcBus.open(url, …)` hands
out the open bus of a URL with a reference count; the bus closes when its last link does.
"""

from __future__ import annotations

import contextlib
import os
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from motiontool.comms.fc.telegram import (
    LGE_PARAMETER,
    MAX_TEXT,
    Telegram,
    TelegramError,
    TelegramReader,
    decode_address,
    encode,
    wire_time,
)
from motiontool.comms.protocol import ConnectionLost, LinkError

READ_TIMEOUT_S = 0.01      # one port read; the answer's deadline is checked between reads
REOPEN_S = 0.5             # a port that failed is opened again at most this often
SETTLE_S = 0.02            # after a damaged answer: time for whatever else is on its way before the next try
DEFAULT_BAUD = 9600          # FC 300 8-32 factory setting
PARITIES = {"E": "E", "EVEN": "E", "N": "N", "NONE": "N", "O": "O", "ODD": "O"}


@dataclass
class BusSettings:
    url: str
    baud: int = DEFAULT_BAUD
    parity: str = "E"            # 8-33: even parity, 1 stop bit
    stopbits: int = 1
    timeout_s: float = 0.2       # answer time allowed beyond the telegrams' own time on the line
    retries: int = 3
    backoff_s: float = 0.01
    faults: object = None        # comms/faults.py Faults of a fault-injecting port (tests)

    def key(self) -> tuple:
        return (self.url, self.baud, self.parity, self.stopbits, id(self.faults) if self.faults else None)


@dataclass
class BusStatistics:
    telegrams: int = 0
    repeats: int = 0
    timeouts: int = 0
    damaged: int = 0
    mismatched: int = 0
    echoes: int = 0
    problems: list[str] = field(default_factory=list)

    def note(self, problem: str) -> None:
        self.problems = (self.problems + [problem])[-20:]


class FcBus:
    _open: dict[tuple, FcBus] = {}
    _open_lock = threading.Lock()

    def __init__(self, settings: BusSettings, port=None):
        self.settings = settings
        self.port = port if port is not None else _open_port(settings)
        self.lock = threading.RLock()
        self.users = 0
        self.closed = False
        self.stats = BusStatistics()
        self._reader = TelegramReader()
        # one extension message at a time per node: a slave keeps one chunk channel per address and connection,
        # so two links of this process to one node must not interleave their frames (a long `advance` answered
        # BUSY, fetched later, got another link's answer)
        self._node_locks: dict[int, threading.Lock] = {}
        self._wrap: Callable | None = None
        self.broken = ""              # why the port failed (a converter or drive that went away): reopened on use
        self._reopen_at = 0.0

    def node_lock(self, address: int) -> threading.Lock:
        with self.lock:
            return self._node_locks.setdefault(address, threading.Lock())

    @classmethod
    def open(cls, settings: BusSettings, wrap: Callable | None = None) -> FcBus:
        """The shared bus of this port (opened on first use); `wrap` wraps a newly opened port (fault injection)."""
        with cls._open_lock:
            bus = cls._open.get(settings.key())
            if bus is None or bus.closed:
                port = _open_port(settings)
                bus = cls(settings, wrap(port) if wrap else port)
                bus._wrap = wrap
                cls._open[settings.key()] = bus
            bus._reopen_at = 0.0   # a new link (Reconnect) tries a failed port at once, not after the others' wait
            bus.users += 1
            return bus

    def release(self) -> None:
        with self._open_lock:
            self.users -= 1
            if self.users <= 0:
                self.close()

    def close(self) -> None:
        with self.lock:
            if not self.closed:
                self.closed = True
                with contextlib.suppress(OSError):
                    self.port.close()
            if FcBus._open.get(self.settings.key()) is self:
                del FcBus._open[self.settings.key()]

    def _break(self, why: str) -> None:
        """The port failed (a TCP converter or a virtual drive that restarted, a USB adapter pulled): closed now and
        opened again by the next telegram, so the links on it come back as a CANopen link does (issue 24 item 9)."""
        self.broken = why or "the port failed"
        with contextlib.suppress(OSError):
            self.port.close()

    def _reopen(self) -> None:
        now = time.monotonic()
        if now < self._reopen_at:      # not more often than every REOPEN_S: a dead port is not hammered
            raise ConnectionLost(f"{self.description}: {self.broken}")
        self._reopen_at = now + REOPEN_S
        try:
            port = _open_port(self.settings)
        except LinkError as exc:       # _open_port names the port and the reason
            raise ConnectionLost(f"{self.description}: {self.broken}; opening it again: {exc}") from None
        self.port = self._wrap(port) if self._wrap else port
        self._reader = TelegramReader()
        self.broken = ""

    @property
    def serial_line(self) -> bool:
        """True when the bytes go over a serial line at `baud` (a port, or rfc2217:// to a remote port), False for
        a raw socket (a converter's own baud rate is unknown here)."""
        url = self.settings.url
        return "://" not in url or url.startswith(("rfc2217://", "spy://", "loop://"))

    @property
    def description(self) -> str:
        s = self.settings
        line = f" {s.baud} baud" if self.serial_line else ""
        return f"FC: {s.url}{line}"

    # --- telegrams ------------------------------------------------------------------------------------
    def transact(self, telegram: Telegram, matches: Callable[[Telegram], bool] | None = None, *,
                 retries: int | None = None, timeout_s: float | None = None) -> Telegram | None:
        """Send a telegram and return the answer that echoes it (None for a broadcast: nobody answers).
        `retries` and `timeout_s` replace the settings' for this telegram only (a scan's short probes): the
        settings are shared by every link on the bus."""
        raw = encode(telegram)
        address, broadcast, _ = decode_address(telegram.adr)
        reply_bytes = MAX_TEXT + 10 if telegram.text is not None else LGE_PARAMETER + 2
        retries = self.settings.retries if retries is None else retries
        timeout_s = self.settings.timeout_s if timeout_s is None else timeout_s
        # a serial line's own time at its baud rate; a socket (a converter, the virtual drive) has none we know
        # of, so it notices a silent slave after `timeout_s` a try, not after a 9600-baud line's time (F30)
        line = wire_time(len(raw) + reply_bytes, self.settings.baud) if self.serial_line else 0.0
        wait = timeout_s + line
        problem = ""
        with self.lock:
            if self.closed:
                raise ConnectionLost(f"{self.description} is closed")
            if self.broken:
                self._reopen()
            for attempt in range(retries + 1):
                if attempt:
                    self.stats.repeats += 1
                    time.sleep(self.settings.backoff_s * 2 ** (attempt - 1))
                try:
                    self._write(raw)
                    if broadcast:
                        time.sleep(wire_time(len(raw), self.settings.baud))
                        return None
                    reply = self._read_reply(telegram, matches, wait)
                except (OSError, ValueError) as exc:   # pyserial's SerialException is an OSError
                    self._break(str(exc))
                    raise ConnectionLost(f"{self.description}: {exc}") from None
                if isinstance(reply, Telegram):
                    return reply
                problem = reply
                self.stats.note(problem)
        raise ConnectionLost(f"no valid answer from address {address} on {self.description} after "
                             f"{retries + 1} tries ({problem})")

    def _write(self, raw: bytes) -> None:
        self.port.reset_input_buffer()
        self._reader.buffer.clear()
        self.port.write(raw)
        self.stats.telegrams += 1

    def _read_reply(self, request: Telegram, matches, wait: float) -> Telegram | str:
        """The answer, or a text saying why there is none."""
        deadline = time.monotonic() + wait
        problem = "no answer (timeout)"
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                if problem.startswith("no answer"):
                    self.stats.timeouts += 1
                return problem
            data = self.port.read(self._reader.missing())
            if not data:
                continue
            for item in self._reader.feed(data):
                if isinstance(item, TelegramError):
                    self.stats.damaged += 1
                    problem = f"damaged answer: {item}"
                    deadline = min(deadline, time.monotonic() + SETTLE_S)  # the rest of it is garbage too
                    continue
                if item == request:          # our own telegram, echoed by the line
                    self.stats.echoes += 1
                    continue
                if item.adr != request.adr or (matches is not None and not matches(item)):
                    self.stats.mismatched += 1
                    problem = "an answer that does not echo the request"
                    continue
                return item


def _open_port(settings: BusSettings):
    import serial

    def open_with(parity: str):
        return serial.serial_for_url(settings.url, baudrate=settings.baud, bytesize=serial.EIGHTBITS, parity=parity,
                                     stopbits=settings.stopbits, timeout=READ_TIMEOUT_S, write_timeout=2.0)

    try:
        try:
            return open_with(settings.parity)
        except _TERMIOS_ERRORS:
            # A pseudo-terminal (the virtual drive's fc:pty) has no parity bit: it keeps PARENB off, so opening it
            # again asks it to change nothing else and it refuses (EINVAL). Parity means nothing there.
            if settings.parity == "N" or not os.path.realpath(settings.url).startswith("/dev/pts/"):
                raise
            return open_with("N")
    except _OPEN_ERRORS as exc:
        raise LinkError(f"cannot open {settings.url}: {exc}") from None


try:  # the settings of a POSIX port are refused with termios.error (not an OSError)
    import termios

    _TERMIOS_ERRORS: tuple[type[Exception], ...] = (termios.error,)
except ImportError:  # Windows
    _TERMIOS_ERRORS = ()
_OPEN_ERRORS: tuple[type[Exception], ...] = (OSError, ValueError, *_TERMIOS_ERRORS)
