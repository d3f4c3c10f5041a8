"""Byte, word and bit selection of a 32-bit value for stream (PDO), Single Shot and polled curves (ide-spec 6.43:
"byte selection … bit selection … signed or unsigned"). No Qt.

A selection is written like the APOSS suffixes (aposs-language.md 5.4), numbered from 1 as there:

| suffix | selects | result |
|---|---|---|
| `b1` … `b4` | byte n, b1 = least significant | 0 … 255 |
| `sb1` … `sb4` | byte n, signed | −128 … 127 |
| `w1`, `w2` | word n, w1 = low 16 bits | 0 … 65535 |
| `sw1`, `sw2` | word n, signed | −32768 … 32767 |
| `1` … `32` | bit n, 1 = least significant | 0 or 1 |

The sample is first taken as a 32-bit two's-complement integer (rounded to the nearest integer, wrapped
modulo 2³²), so −2 selects `.b1` = 254 like `0x1FFFE.b1` does in APOSS. Samples that are not finite (NaN, ±inf)
stay NaN. A curve shows the suffix after its name: "1: REG_STAT [4104].b2", "1: APOS.3" (docs/formats/zbo.md).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

_PATTERN = re.compile(r"(?P<sign>s?)(?P<kind>[bw])(?P<n>\d+)|(?P<bit>\d+)")
CHOICES = (["b1", "b2", "b3", "b4", "sb1", "sb2", "sb3", "sb4", "w1", "w2", "sw1", "sw2"]
           + [str(n) for n in range(1, 33)])


@dataclass(frozen=True)
class Selection:
    shift: int          # bit position of the selected field's least significant bit
    width: int          # 8, 16 or 1
    signed: bool
    suffix: str         # canonical text without the dot: "b2", "sw1", "17"

    def apply(self, values) -> np.ndarray:
        """The selected field of each sample (float array, NaN where the sample is not finite)."""
        v = np.asarray(values, dtype=float)
        finite = np.isfinite(v)
        word = np.mod(np.rint(np.where(finite, v, 0.0)), 4294967296.0).astype(np.int64)  # 0 … 2**32-1
        field = (word >> self.shift) & ((1 << self.width) - 1)
        if self.signed:
            field = np.where(field >= 1 << (self.width - 1), field - (1 << self.width), field)
        out = field.astype(float)
        out[~finite] = np.nan
        return out


@lru_cache(maxsize=256)  # asked per packet and per poll for each curve; a Selection is immutable
def parse_selection(text: str | None) -> Selection | None:
    """"b2", ".b2", "sw1", "3" … → Selection; None or "" → None (the whole value). ValueError otherwise."""
    if text is None:
        return None
    s = str(text).strip().lower()
    if not s:
        return None
    s = s.removeprefix(".")
    m = _PATTERN.fullmatch(s)
    if m is None:
        raise ValueError(f"'{text}' is not a byte/word/bit selection (b1…b4, sb1…sb4, w1, w2, sw1, sw2, 1…32)")
    if m["bit"] is not None:
        n = int(m["bit"])
        if not 1 <= n <= 32:
            raise ValueError(f"bit .{n}: bits are numbered 1…32")
        return Selection(n - 1, 1, False, str(n))
    n, width = int(m["n"]), 8 if m["kind"] == "b" else 16
    count = 32 // width
    if not 1 <= n <= count:
        raise ValueError(f".{s}: a 32-bit value has {m['kind']}1…{m['kind']}{count}")
    return Selection((n - 1) * width, width, bool(m["sign"]), f"{m['sign']}{m['kind']}{n}")


def canonical(text: str | None) -> str | None:
    """The stored form of a selection ("b2", "17") or None for the whole value; ValueError if invalid."""
    sel = parse_selection(text)
    return None if sel is None else sel.suffix


def split_signal(text: str) -> tuple[str, str | None]:
    """"4104.b2" → ("4104", "b2"), "APOS.3" → ("APOS", "3"), "APOS" → ("APOS", None): a signal typed with an
    APOSS suffix. A trailing part that is not a selection is left in the signal."""
    text = str(text).strip()
    head, dot, tail = text.rpartition(".")
    if not dot or not head:
        return text, None
    try:
        return head, canonical(tail)
    except ValueError:
        return text, None


def with_suffix(name: str, select: str | None) -> str:
    """The curve name with the selection's suffix: "1: REG_STAT [4104]" + "b2" → "1: REG_STAT [4104].b2"."""
    return name if not select else f"{name}.{select}"


def without_suffix(name: str, select: str | None) -> str:
    """Undo with_suffix; a name that does not end in the suffix (renamed by the user) is returned as it is."""
    if select and name.endswith(f".{select}"):
        return name[: -len(select) - 1]
    return name


def apply(select: str | None, values) -> np.ndarray:
    """The values a curve with this selection stores (unchanged float array when select is None)."""
    sel = parse_selection(select)
    return np.asarray(values, dtype=float) if sel is None else sel.apply(values)
