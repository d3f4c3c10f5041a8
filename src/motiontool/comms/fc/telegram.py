"""The FC protocol telegram of Danfoss FC 300 drives (RS-485 / USB), byte for byte (docs/protocols/fc.md).

    STX LGE ADR data… BCC

- STX = 0x02; LGE = number of data bytes + ADR + BCC: 6 (process block), 14 (parameter block + process block),
  10 + n (text block: parameter block + n text bytes, AK 15);
- ADR, format 1 (bit 7 = 0): address 1..31 in bits 0-4, bit 5 = broadcast; format 2 (bit 7 = 1): address 1..126
  in bits 0-6, 0 = broadcast. The slave echoes ADR; nobody answers a broadcast;
- parameter block: PKE (AK in bits 15-12, PNU in bits 11-0), IND, PWE high, PWE low — big-endian words;
  process block: PCD1 (control word / status word), PCD2 (reference / main actual value);
- BCC = XOR of every byte before it, from STX on.

On the line every byte is an 11-bit character: start bit, 8 data bits (least significant first), even parity,
stop bit (`character`); the UART adds and checks the parity, this module only computes it for tests and timing.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

STX = 0x02
BITS_PER_CHARACTER = 11
LGE_PROCESS, LGE_PARAMETER, LGE_TEXT_BASE = 6, 14, 10
MAX_TEXT = 255 - LGE_TEXT_BASE   # LGE is one byte

# AK codes, master → slave
AK_NONE, AK_READ, AK_WRITE_WORD, AK_WRITE_DWORD = 0, 1, 2, 3
AK_WRITE_DWORD_EEPROM, AK_WRITE_WORD_EEPROM, AK_TEXT = 13, 14, 15
# AK codes, slave → master
AK_VALUE_WORD, AK_VALUE_DWORD, AK_REFUSED, AK_TEXT_TRANSFERRED = 1, 2, 7, 15

FAULTS = {  # PWE low after AK 7 (FC 300 design guide, "RS-485 Installation and Set-up")
    0: "illegal parameter number", 1: "parameter cannot be changed", 2: "upper or lower limit exceeded",
    3: "subindex corrupted", 4: "no array", 5: "wrong data type", 9: "description element not available",
    11: "no parameter write access", 15: "no text available", 17: "not while running", 18: "other error",
    130: "no bus access for this parameter", 131: "write to factory set-up not possible", 132: "no LCP access",
    252: "unknown viewer", 253: "request not supported", 254: "unknown attribute", 255: "no error",
}


class TelegramError(ValueError):
    """Bytes that are not a valid telegram; the text names the byte offset."""


def bcc(data: bytes) -> int:
    value = 0
    for byte in data:
        value ^= byte
    return value


def character(byte: int) -> int:
    """The 11-bit character of a byte as it goes on the line, first bit in bit 0: start (0), data bits 0-7,
    even parity (the 9 bits data + parity hold an even number of ones), stop (1)."""
    parity = bin(byte & 0xFF).count("1") & 1
    return (byte & 0xFF) << 1 | parity << 9 | 1 << 10


def from_character(bits: int) -> int:
    """The byte of an 11-bit character; TelegramError on a framing or parity error."""
    if bits & 1 or not bits >> 10 & 1:
        raise TelegramError("framing error: start bit must be 0 and stop bit 1")
    byte = bits >> 1 & 0xFF
    if (bin(byte).count("1") + (bits >> 9 & 1)) & 1:
        raise TelegramError(f"parity error in character 0x{byte:02x}")
    return byte


def wire_time(nbytes: int, baud: int) -> float:
    """Seconds `nbytes` take on the line at `baud` (11 bits a character)."""
    return nbytes * BITS_PER_CHARACTER / baud


# --- addresses ----------------------------------------------------------------------------------------------
def encode_address(address: int, broadcast: bool = False, fmt: int | None = None) -> int:
    """ADR byte: format 1 for addresses 1..31 unless `fmt` = 2, format 2 (bit 7) for 1..126."""
    if fmt is None:
        fmt = 1 if address <= 31 else 2
    if fmt == 1:
        if broadcast:
            return 0x20 | (address & 0x1F)
        if not 1 <= address <= 31:
            raise ValueError(f"address {address}: format 1 holds addresses 1..31")
        return address
    if fmt == 2:
        if broadcast:
            return 0x80
        if not 1 <= address <= 126:
            raise ValueError(f"address {address}: FC addresses are 1..126")
        return 0x80 | address
    raise ValueError(f"address format {fmt}: 1 or 2")


def decode_address(adr: int) -> tuple[int, bool, int]:
    """(address, broadcast, format) of an ADR byte; address 0 for a broadcast."""
    if adr & 0x80:
        address = adr & 0x7F
        return address, address == 0, 2
    if adr & 0x20:
        return 0, True, 1
    return adr & 0x1F, False, 1


# --- telegrams ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Telegram:
    adr: int                         # the ADR byte as sent (encode_address)
    pke: int | None = None           # parameter block (None: process block only)
    ind: int = 0
    pwe: int = 0                     # PWE high << 16 | PWE low
    pcd: tuple[int, int] | None = (0, 0)   # process block (None in a text telegram)
    text: bytes | None = None        # text block (AK 15)

    @property
    def ak(self) -> int:
        return (self.pke or 0) >> 12

    @property
    def pnu(self) -> int:
        return (self.pke or 0) & 0x0FFF

    @property
    def address(self) -> int:
        return decode_address(self.adr)[0]

    @property
    def broadcast(self) -> bool:
        return decode_address(self.adr)[1]


def parameter(adr: int, ak: int, pnu: int, value: int = 0, ind: int = 0, pcd: tuple[int, int] = (0, 0)) -> Telegram:
    if not 0 <= pnu <= 0x0FFF:
        raise ValueError(f"PNU {pnu}: 12 bits (0..4095)")
    return Telegram(adr, ak << 12 | pnu, ind, value & 0xFFFFFFFF, pcd)


def text_telegram(adr: int, ak: int, pnu: int, ind: int, pwe: int, text: bytes) -> Telegram:
    if len(text) > MAX_TEXT:
        raise ValueError(f"text of {len(text)} bytes: at most {MAX_TEXT} fit a telegram")
    return Telegram(adr, ak << 12 | pnu, ind, pwe & 0xFFFFFFFF, None, bytes(text))


def encode(t: Telegram) -> bytes:
    if t.text is not None:
        data = struct.pack(">HHI", t.pke, t.ind, t.pwe) + t.text
    elif t.pke is None:
        data = struct.pack(">HH", *(t.pcd or (0, 0)))
    else:
        data = struct.pack(">HHIHH", t.pke, t.ind, t.pwe, *(t.pcd or (0, 0)))
    body = bytes((STX, len(data) + 2, t.adr)) + data
    return body + bytes((bcc(body),))


def expected_length(lge: int) -> int:
    """Bytes of a whole telegram with this LGE (STX and LGE included)."""
    return lge + 2


def decode(raw: bytes) -> Telegram:
    """A whole telegram → Telegram; TelegramError naming the byte offset of the first defect."""
    if len(raw) < 2:
        raise TelegramError(f"telegram of {len(raw)} bytes is too short for STX and LGE")
    if raw[0] != STX:
        raise TelegramError(f"byte 0: 0x{raw[0]:02x} where STX (0x02) was expected")
    lge = raw[1]
    if lge < LGE_PROCESS:
        raise TelegramError(f"byte 1: LGE {lge} is below the shortest telegram's {LGE_PROCESS}")
    if len(raw) != expected_length(lge):
        raise TelegramError(f"byte 1: LGE {lge} announces {expected_length(lge)} bytes, got {len(raw)}")
    if bcc(raw[:-1]) != raw[-1]:
        raise TelegramError(f"byte {len(raw) - 1}: BCC 0x{raw[-1]:02x}, computed 0x{bcc(raw[:-1]):02x}")
    adr, data = raw[2], raw[3:-1]
    if lge == LGE_PROCESS:
        return Telegram(adr, None, 0, 0, struct.unpack(">HH", data))
    if len(data) < 8:
        raise TelegramError(f"byte 1: LGE {lge} is too short for a parameter block")
    pke, ind, pwe = struct.unpack_from(">HHI", data)
    if pke >> 12 == AK_TEXT:
        return Telegram(adr, pke, ind, pwe, None, bytes(data[8:]))
    if lge != LGE_PARAMETER:
        raise TelegramError(f"byte 1: LGE {lge} for AK {pke >> 12} (a parameter telegram has LGE {LGE_PARAMETER})")
    return Telegram(adr, pke, ind, pwe, struct.unpack_from(">HH", data, 8))


class TelegramReader:
    """Telegrams out of a byte stream: `feed(bytes)` returns the whole telegrams found (and TelegramErrors for
    damaged ones); after a damaged telegram it looks for the next STX (re-synchronisation)."""

    def __init__(self) -> None:
        self.buffer = bytearray()

    def missing(self) -> int:
        """How many more bytes the telegram at the start of the buffer needs (at least 1): a reader asks the port for
        exactly that many, so a telegram arrives in two reads (STX and LGE, then the rest)."""
        buf = self.buffer
        if len(buf) < 2 or buf[0] != STX:
            return max(1, 2 - len(buf))
        return max(1, expected_length(max(buf[1], LGE_PROCESS)) - len(buf))

    def feed(self, data: bytes) -> list[Telegram | TelegramError]:
        self.buffer += data
        found: list[Telegram | TelegramError] = []
        buf = self.buffer
        while buf:
            if buf[0] != STX:
                start = buf.find(STX)
                skipped = len(buf) if start < 0 else start
                del buf[:skipped]
                found.append(TelegramError(f"{skipped} bytes without STX skipped"))
                continue
            if len(buf) < 2 or len(buf) < expected_length(max(buf[1], LGE_PROCESS)):
                break
            n = expected_length(buf[1])
            if buf[1] < LGE_PROCESS:
                n = 1
            raw = bytes(buf[:n])
            try:
                found.append(decode(raw))
                del buf[:n]
            except TelegramError as exc:
                found.append(exc)
                del buf[:1]              # re-synchronise on the next STX
        return found
