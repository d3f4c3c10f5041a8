"""FcLink: a controller on an FC bus (RS-485 or USB, or a serial-to-Ethernet converter), `--link fc:URL[#ADDRESS]`.

Parameters travel as the public protocol's parameter telegrams (AK 1 read; AK 2/3 write a word/double word in RAM,
by the parameter's data type), so they work with any FC 300 drive. Every other request, and the event polling,
travels in the motiontool extension (comms/fc/extension.py) as chunked Link messages (comms/remote.py). Every write
is verified: the drive's answer echoes the value it now holds, and a different value is an error.

Options (`fc:URL#ADDRESS,KEY=VALUE,…`): baud (default 9600, FC 300 8-32), parity E|N|O (8-33, default E),
stopbits 1|2, timeout (s an answer may take beyond its time on the line, default 0.2), retries (default 3),
format 1|2 (address format; default 1 for addresses 1..31, 2 above), poll (event poll interval in s; by default
a quarter of the line at most).
"""

from __future__ import annotations

import random
from typing import Any

from motiontool.comms.chunks import MasterChannel
from motiontool.comms.faults import FAULT_OPTIONS, FaultyPort, faults_from_options
from motiontool.comms.fc.bus import DEFAULT_BAUD, PARITIES, BusSettings, FcBus
from motiontool.comms.fc.extension import EXTENSION_PNU, MAX_CHUNK, frame_telegram, is_frame, telegram_frame
from motiontool.comms.fc.telegram import (
    AK_NONE,
    AK_READ,
    AK_REFUSED,
    AK_VALUE_DWORD,
    AK_VALUE_WORD,
    AK_WRITE_DWORD,
    AK_WRITE_WORD,
    FAULTS,
    Telegram,
    encode_address,
    parameter,
    wire_time,
)
from motiontool.comms.fc.values import from_pwe, to_pwe
from motiontool.comms.links import LinkSpec, register_link_scheme
from motiontool.comms.protocol import ConnectionLost, LinkError, Request
from motiontool.comms.remote import POLL_INTERVAL_S, RemoteLink
from motiontool.kernel.fc300_table import FC_PARAMETERS, link_number
from motiontool.paramdb import Parameter, ParameterError, database

PARAMETER_ANSWERS = (AK_VALUE_WORD, AK_VALUE_DWORD, AK_REFUSED)   # what a slave answers to a read or a write
OPTIONS = {"baud", "parity", "stopbits", "timeout", "retries", "format", "poll"} | FAULT_OPTIONS


def fault_text(code: int) -> str:
    return FAULTS.get(code, f"fault {code}")


class FcLink(RemoteLink):
    kind = "fc"

    def __init__(self, bus: FcBus, address: int = 1, fmt: int | None = None,
                 poll_interval_s: float = POLL_INTERVAL_S):
        self.bus = bus
        self.address = address
        self.adr = encode_address(address, fmt=fmt)
        self.channel = MasterChannel(self._transfer, MAX_CHUNK, first_seq=random.getrandbits(16))
        super().__init__(self._exchange_message, f"{bus.description} #{address}", poll_interval_s)
        # a status request and its answer are ~230 bytes: at most a tenth of the line (2.6 s at 9600 baud)
        self.status_interval_s = 10 * wire_time(230, bus.settings.baud) if bus.serial_line else 0.0

    # --- the extension ---------------------------------------------------------------------------------
    def _exchange_message(self, message: bytes) -> bytes:
        with self.bus.node_lock(self.address):
            return self.channel.exchange(message)

    def _transfer(self, frame):
        # a refusal of the extension names its PNU; one of another parameter is a late answer to something else
        reply = self.bus.transact(frame_telegram(self.adr, frame), lambda t: (is_frame(t) and t.ind == frame.seq) or (
            t.text is None and t.ak == AK_REFUSED and t.pnu == EXTENSION_PNU))
        if not is_frame(reply):
            raise LinkError(f"controller {self.address} on {self.bus.description} offers parameter access only "
                            f"(it refused the motiontool extension: {fault_text(reply.pwe & 0xFFFF)})")
        return telegram_frame(reply)

    # --- parameters: the public protocol ------------------------------------------------------------------
    def request(self, request: Request) -> Any:
        if request.op == "read_parameter":
            return self._read(_parameter(request.args.get("key")))
        if request.op == "write_parameter":
            return self._write(_parameter(request.args.get("key")), request.args.get("value"))
        return super().request(request)

    def _transact_parameter(self, p: Parameter, ak: int, value: int = 0) -> Telegram:
        if self._closed.is_set():
            raise ConnectionLost("the link is closed")
        reply = self.patiently(lambda: self.bus.transact(parameter(self.adr, ak, p.index, value), lambda t: (
            t.text is None and t.pke is not None and t.pnu == p.index and t.ak in PARAMETER_ANSWERS)))
        if reply.ak == AK_REFUSED:
            code = reply.pwe & 0xFFFF
            number = {0: 112, 1: 112, 2: 183}.get(code, 0)
            raise LinkError(f"parameter {p.label}: the drive refused it ({fault_text(code)}, FC fault {code})",
                            number)
        return reply

    def _read(self, p: Parameter) -> int:
        reply = self._transact_parameter(p, AK_READ)
        return from_pwe(p, reply.pwe, word=reply.ak == AK_VALUE_WORD)

    def _write(self, p: Parameter, value) -> None:
        if p.read_only:
            raise LinkError(f"error 112: Unknown param. ({p.label} is read-only)", 112)
        try:
            raw = int(value)
            p.validate(raw if not p.conversion_index else raw * 10 ** p.conversion_index)
        except (ParameterError, TypeError, ValueError) as exc:
            raise LinkError(f"error 183: {exc}", 183) from None
        word = to_pwe(p, raw)[0] == AK_VALUE_WORD
        reply = self._transact_parameter(p, AK_WRITE_WORD if word else AK_WRITE_DWORD, raw)
        echoed = from_pwe(p, reply.pwe, word=reply.ak == AK_VALUE_WORD)
        if echoed != raw:
            raise LinkError(f"parameter {p.label}: wrote {raw}, the drive answered {echoed} (write not verified)")

    def close(self) -> None:
        released = self._closed.is_set()
        super().close()
        if not released:          # once: the bus counts its links, a second release would close it under others
            self.bus.release()


class DriveParameter(Parameter):
    """An FC 300 parameter of the drive itself (\"4-13\"), read and written with the same telegrams as the
    option's: its PNU is its number without the dash (413), its value the integer the bus carries."""

    @property
    def read_only(self) -> bool:
        return self.group == "16"        # DG 7594: "Parameter groups 16-** and 34-** are read only"


def _parameter(key) -> Parameter:
    try:
        return database().get(key)
    except ParameterError:
        pass
    number = link_number(key)
    drive = FC_PARAMETERS.get(number) if number is not None else None
    if drive is None:
        raise LinkError(f"error 112: Unknown param. (parameter {key})", 112)
    # the range the drive may narrow (a limit that ends at another parameter) is checked by the drive
    return DriveParameter(drive.label, drive.number, drive.name, drive.source, drive.label.partition("-")[0],
                          drive.default, drive.low, drive.high, "", {}, None, "Int32", True, drive.source)


# --- opening and scanning ------------------------------------------------------------------------------------
def bus_settings(spec: LinkSpec) -> BusSettings:
    parity = spec.option("parity", "E", str).upper()
    if parity not in PARITIES:
        raise LinkError(f"link '{spec.text}': parity {parity!r}: choose E, N or O")
    if not spec.target:
        raise LinkError(f"link '{spec.text}': give the port, e.g. fc:/dev/ttyUSB0#1 or fc:socket://host:port#1")
    # ranges: what a serial port, the FC protocol (8-32: up to 115200 baud; a USB adapter goes further) and a
    # usable link allow
    return BusSettings(spec.target, spec.option("baud", DEFAULT_BAUD, int, 300, 4_000_000), PARITIES[parity],
                       spec.option("stopbits", 1, int, 1, 2), spec.option("timeout", 0.2, float, 0.001, 60),
                       spec.option("retries", 3, int, 0, 100))


def open_fc(spec: LinkSpec) -> FcLink:
    spec.check_options(OPTIONS)
    address = spec.node if spec.node is not None else 1
    fmt = spec.option("format", None, int, 1, 2)
    try:
        encode_address(address, fmt=fmt)
    except ValueError as exc:
        raise LinkError(f"link '{spec.text}': {exc}") from None
    settings = bus_settings(spec)
    faults = faults_from_options(spec)
    if faults.active:  # a spoilt line is a different bus from the clean one on the same port
        settings.faults = faults
    poll = spec.option("poll", None, float, 0.001, 3600)   # every option is checked before the port is opened
    bus = FcBus.open(settings, (lambda port: FaultyPort(port, faults)) if faults.active else None)
    return FcLink(bus, address, fmt, default_poll_interval(bus) if poll is None else poll)


def default_poll_interval(bus: FcBus) -> float:
    """Event polls take at most a quarter of a serial line (an empty poll and its answer are ~130 bytes: 0.15 s at
    9600 baud, so every 0.6 s; every 50 ms from 38400 baud on); a socket is polled every 50 ms."""
    return max(POLL_INTERVAL_S, 4 * wire_time(130, bus.settings.baud)) if bus.serial_line else POLL_INTERVAL_S


def scan(bus: FcBus, addresses, fmt: int | None = None) -> list[int]:
    """The addresses in `addresses` that answer a "no command" telegram (one try with a short timeout each, then one
    more round for those that did not: a drive busy for a moment, or a loaded PC, is not taken for absent)."""
    timeout_s = min(bus.settings.timeout_s, 0.05)

    def answers(address: int) -> bool:
        try:
            bus.transact(parameter(encode_address(address, fmt=fmt), AK_NONE, 0), retries=0, timeout_s=timeout_s)
        except ConnectionLost:
            if bus.closed:
                raise
            return False
        return True

    addresses = list(addresses)
    found = {address for address in addresses if answers(address)}
    found |= {address for address in addresses if address not in found and answers(address)}
    return sorted(found)


def scan_spec(spec: LinkSpec, addresses) -> list[int]:
    """The addresses that answer on the bus of a spec (for the IDE's controller ID scan range)."""
    spec.check_options(OPTIONS)
    bus = FcBus.open(bus_settings(spec))
    try:
        return scan(bus, addresses, spec.option("format", None, int, 1, 2))
    finally:
        bus.release()


register_link_scheme("fc", open_fc, "fc:URL[#ADDRESS][,baud=N,parity=E|N|O,timeout=S,retries=N]",
                     "FC protocol over RS-485/USB or any pyserial URL, e.g. fc:/dev/ttyUSB0#1, "
                     "fc:socket://127.0.0.1:4001#2", scan=scan_spec)
