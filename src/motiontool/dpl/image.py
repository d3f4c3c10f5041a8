"""The DPL program image: what `download` carries over a Link to an APC controller
(docs/formats/dpl-program-image.md).

The SM-Applications module gets a compiled binary from SyPT; our simulated module compiles the program itself,
so the image is the program's source with its name: ``DPL1`` NUL name NUL source, name and source UTF-8.
"""

from __future__ import annotations

from dataclasses import dataclass

MAGIC = b"DPL1\x00"
MAX_SOURCE_BYTES = 4 * 1024 * 1024   # far beyond the module's 384 kB of flash (L537-589); a bound for readers


class DplImageError(ValueError):
    """Bytes that are not a DPL program image; the message names the byte offset."""


@dataclass(frozen=True)
class DplImage:
    name: str
    source: str

    def to_bytes(self) -> bytes:
        if "\x00" in self.name:
            raise DplImageError("a program name cannot contain NUL")
        data = MAGIC + self.name.encode("utf-8") + b"\x00" + self.source.encode("utf-8")
        if len(data) > MAX_SOURCE_BYTES:
            raise DplImageError(f"the program is {len(data)} bytes, more than {MAX_SOURCE_BYTES}")
        return data

    @classmethod
    def from_bytes(cls, data: bytes) -> DplImage:
        if len(data) > MAX_SOURCE_BYTES:
            raise DplImageError(f"{len(data)} bytes: a DPL program image holds at most {MAX_SOURCE_BYTES}")
        if not data.startswith(MAGIC):
            raise DplImageError("byte 0: not a DPL program image (it starts with 'DPL1' and a NUL)")
        end = data.find(b"\x00", len(MAGIC))
        if end < 0:
            raise DplImageError(f"byte {len(MAGIC)}: the program name is not terminated by a NUL")
        try:
            name = data[len(MAGIC):end].decode("utf-8")
        except UnicodeDecodeError as exc:
            raise DplImageError(f"byte {len(MAGIC) + exc.start}: the name is not UTF-8") from None
        try:
            source = data[end + 1:].decode("utf-8")
        except UnicodeDecodeError as exc:
            raise DplImageError(f"byte {end + 1 + exc.start}: the source is not UTF-8") from None
        return cls(name, source)
