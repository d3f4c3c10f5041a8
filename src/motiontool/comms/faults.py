"""A fault-injecting transport: wraps a serial port (pyserial's interface) and spoils what passes through it.

For tests, benchmarks and anyone checking how a link copes with a bad line: every telegram in each direction — a
write, and the answer that follows it (its first read) — is, with the given probabilities (in %, each drawn from
one seeded generator, so a run can be repeated):

- drop: lost (a write never reaches the line; the bytes of the answer's first read vanish, the rest is garbage);
- corrupt: one byte of it gets one to eight bits flipped;
- duplicate: a write goes out twice;
- delay: a write is held back `delay_s` (longer than an answer may take, so its answer comes late).

FC links take them as options, ``--link fc:URL#1,drop=5,corrupt=5,seed=7`` (docs/protocols/fc.md).
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from motiontool.comms.links import LinkSpec


@dataclass
class Faults:
    drop: float = 0.0          # % of writes and of reads
    corrupt: float = 0.0
    duplicate: float = 0.0     # % of writes
    delay: float = 0.0
    delay_s: float = 0.3
    seed: int | None = None
    counts: dict[str, int] = field(default_factory=lambda: {"drop": 0, "corrupt": 0, "duplicate": 0, "delay": 0})

    @property
    def active(self) -> bool:
        return any((self.drop, self.corrupt, self.duplicate, self.delay))


class FaultyPort:
    """A serial-like object whose traffic suffers `faults`; everything else is the wrapped port's."""

    def __init__(self, port, faults: Faults):
        self._port = port
        self.faults = faults
        self._rng = random.Random(faults.seed)
        self._answer_due = False          # the next read is the first of an answer: the answer's fault is drawn

    def __getattr__(self, name):
        return getattr(self._port, name)

    def __setattr__(self, name, value):
        if name in ("_port", "faults", "_rng", "_answer_due"):
            object.__setattr__(self, name, value)
        else:
            setattr(self._port, name, value)

    def _hit(self, kind: str, percent: float) -> bool:
        if percent and self._rng.random() * 100 < percent:
            self.faults.counts[kind] += 1
            return True
        return False

    def _spoil(self, data: bytes) -> bytes:
        spoiled = bytearray(data)
        spoiled[self._rng.randrange(len(spoiled))] ^= self._rng.randrange(1, 256)
        return bytes(spoiled)

    def write(self, data: bytes) -> int:
        self._answer_due = True
        f = self.faults
        if self._hit("drop", f.drop):
            return len(data)
        if self._hit("corrupt", f.corrupt):
            data = self._spoil(data)
        if self._hit("delay", f.delay):
            time.sleep(f.delay_s)
        self._port.write(data)
        if self._hit("duplicate", f.duplicate):
            self._port.write(data)
        return len(data)

    def read(self, size: int = 1) -> bytes:
        data = self._port.read(size)
        if not data or not self._answer_due:
            return data
        self._answer_due = False
        if self._hit("drop", self.faults.drop):
            return b""
        if self._hit("corrupt", self.faults.corrupt):
            return self._spoil(data)
        return data


def faults_from_options(spec: LinkSpec) -> Faults:
    """The fault options of a link spec (drop, corrupt, duplicate, delay in %; seed)."""
    def percent(name: str) -> float:
        return spec.option(name, 0.0, float, 0, 100)
    return Faults(drop=percent("drop"), corrupt=percent("corrupt"), duplicate=percent("duplicate"),
                  delay=percent("delay"), seed=spec.option("seed", None, int))


FAULT_OPTIONS = {"drop", "corrupt", "duplicate", "delay", "seed"}
