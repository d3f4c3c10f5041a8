"""The motiontool extension of the FC protocol: Link messages (comms/wire.py) as text telegrams on one reserved
parameter number (docs/protocols/fc.md "Extension").

The public protocol reads and writes parameters; program download, start/break, events, the debugger, arrays and
recordings are not in it. They travel as chunk frames (comms/chunks.py), one frame per text telegram:

    PKE = AK 15 | PNU 4095 (EXTENSION_PNU)      read/write text, on a parameter number no drive has
    IND = frame sequence number (16 bit)         the slave echoes it
    PWE = operation << 24 | flags << 16 | chunk index (16 bit)
          operation: 1 DATA, 2 FETCH (master); 3 ACK, 4 RESULT, 5 BUSY, 6 ERROR (slave); flags: bit 0 FIRST,
          bit 1 LAST
    text = the chunk (at most MAX_CHUNK bytes), or an ERROR's reason

A drive without the extension refuses PNU 4095 with AK 7 (fault 0, illegal parameter number): the link then says
that this controller only offers parameter access.
"""

from __future__ import annotations

from motiontool.comms.chunks import Frame
from motiontool.comms.fc.telegram import AK_TEXT, MAX_TEXT, Telegram, text_telegram

EXTENSION_PNU = 0x0FFF
MAX_CHUNK = MAX_TEXT        # 245 bytes: a frame fills the longest telegram LGE allows
FIRST, LAST = 0x01, 0x02


def frame_telegram(adr: int, frame: Frame) -> Telegram:
    flags = (FIRST if frame.first else 0) | (LAST if frame.last else 0)
    pwe = frame.op << 24 | flags << 16 | (frame.index & 0xFFFF)
    return text_telegram(adr, AK_TEXT, EXTENSION_PNU, frame.seq & 0xFFFF, pwe, frame.payload)


def is_frame(t: Telegram) -> bool:
    return t.text is not None and t.ak == AK_TEXT and t.pnu == EXTENSION_PNU


def telegram_frame(t: Telegram) -> Frame:
    flags = t.pwe >> 16 & 0xFF
    return Frame(t.ind, t.pwe >> 24, bool(flags & FIRST), bool(flags & LAST), t.pwe & 0xFFFF, t.text or b"")
