"""The drive and module parameters a DPL program reaches as `#menu.par` (seed 004 §11.3 L7880-7932, §11.6
L8200-8215, §6.2 L4631-4723).

A plain store of integers by (menu, parameter), with the defaults the kernel relies on, plus virtual
parameters computed from the kernel on read (menu 90 encoder views, #1.11 reference on, menu 91 CTSync
counters). Values are held as the manual's programs use them: #1.06 in rpm (`#01.06 = 1000 // Max Speed
(1000rpm)`, L5093), the output channel writes rpm×10 into #1.21 and #3.22 (L4255-4257). Anything not modelled
reads 0 and keeps what is written, so programs that tune drive menus run unchanged.
"""

from __future__ import annotations

from collections.abc import Callable

# #1.06 and #81.06, read every sample: a dictionary look-up of the key object it holds skips comparing tuples
MAX_SPEED, RS485_MODE = (1, 6), (81, 6)

DEFAULTS: dict[tuple[int, int], int] = {
    MAX_SPEED: 3000,  # maximum speed, rpm (the output clamp's default 53687091 is 3000 rpm, L4242-4252)
    (1, 14): 3,       # reference selector: preset (what the examples set, L5097)
    (1, 15): 1,
    (1, 21): 0,       # preset speed 1, rpm×10 from the output channel
    (3, 22): 0,       # hard speed reference, rpm×10
    (3, 23): 0,       # hard speed reference select
    RS485_MODE: 1,    # RS485 mode; 25 CTSync master, 26 slave (L8205)
    (81, 12): 3,      # POS rate: 1 ms (the examples' setting; the module's own default is 0 = disabled)
    (81, 13): 1,
    (81, 16): 1,      # encoder update every POS task (recommended, L938-946; the only rate modelled, A69)
    (81, 17): 0,      # parameter over-range trip (Tr44) off
    (81, 38): 1,      # APC runtime error trips Tr81 (the basic setup, L4678-4723; printed default 0, A69)
}


def parse_key(key) -> tuple[int, int]:
    """(menu, parameter) from (1, 6), "1.06", "#1.06", "01.06" or 106 (menu·100 + parameter)."""
    if isinstance(key, tuple) and len(key) == 2:
        menu, par = key
    elif isinstance(key, int) and not isinstance(key, bool):
        menu, par = divmod(key, 100)
    else:
        text = str(key).strip().lstrip("#")
        menu_text, dot, par_text = text.partition(".")
        if not dot or not menu_text.isdigit() or not par_text.isdigit():
            raise ValueError(f"drive parameter {key!r}: write it as menu.parameter, e.g. #1.06 or 90.49")
        menu, par = int(menu_text), int(par_text)
    if not (0 <= menu <= 99 and 0 <= par <= 99):
        raise ValueError(f"drive parameter #{menu}.{par:02d} does not exist (menus 0-99, parameters 0-99)")
    return int(menu), int(par)


class DriveParameters:
    """#menu.par values; `virtual` maps (menu, par) to a reader (and optionally a writer) in the kernel."""

    def __init__(self) -> None:
        self.values: dict[tuple[int, int], int] = dict(DEFAULTS)
        self.readers: dict[tuple[int, int], Callable[[], int]] = {}
        self.writers: dict[tuple[int, int], Callable[[int], None]] = {}

    def read(self, key) -> int:
        k = parse_key(key)
        reader = self.readers.get(k)
        return int(reader()) if reader else self.values.get(k, 0)

    def write(self, key, value: int) -> None:
        k = parse_key(key)
        writer = self.writers.get(k)
        if writer:
            writer(int(value))
        elif k in self.readers:
            raise ValueError(f"#{k[0]}.{k[1]:02d} is read-only")
        else:
            self.values[k] = int(value)

    def __getitem__(self, key) -> int:
        return self.read(key)

    def __setitem__(self, key, value: int) -> None:
        self.write(key, value)
