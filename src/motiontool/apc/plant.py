"""The simulated Unidrive SP behind the APC: speed loop, motor and load, encoders (docs/apc.md "Plant").

The APC manual describes none of this (**inferred** model, docs/decisions.md A44): the drive's speed loop
follows its speed reference as a first-order lag, the motor position integrates the speed, and the drive
encoder quantises it to its counts per revolution in the 48-bit turns|coarse|fine word (L998-1016). A trip
or a drive without "reference on" lets the motor coast down. Positions are in units of the 48-bit word
(2^32 per revolution) and speeds in APC units (2^32 per revolution per 250 µs), so one quarter of speed moves
the word by exactly the speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

WORD48 = (1 << 48) - 1
REV = 1 << 32


@dataclass
class PlantConfig:
    speed_tau_ms: float = 2.0       # the drive's closed speed loop as a first-order lag
    coast_tau_ms: float = 300.0     # how a tripped or disabled drive's motor runs down
    encoder_cpr: int = 65536        # counts per revolution of the drive encoder (4096 ppr quadrature = 16384)
    start_revolutions: float = 0.0  # motor position at power-up
    marker_angle: float | None = 0.0    # the encoder's marker (index) pulse at this fraction of a turn, or None

    @classmethod
    def from_mapping(cls, values: dict) -> PlantConfig:
        known = {f.name for f in fields(cls)}
        unknown = set(values) - known
        if unknown:
            raise ValueError(f"unknown plant setting(s): {', '.join(sorted(unknown))}")
        return cls(**values)


class Plant:
    """Motor + load + drive speed loop, stepped one POS period at a time with the output-channel latency."""

    def __init__(self, config: PlantConfig | None = None):
        self.config = config or PlantConfig()
        self.position = self.config.start_revolutions * REV    # 48-bit word units, float
        self.speed = 0.0                                       # APC speed units
        self._step = REV // max(1, min(self.config.encoder_cpr, 1 << 32))
        self._factors: dict[tuple[int, bool], tuple[float, float]] = {}

    def _lag(self, quarters: int, coasting: bool) -> tuple[float, float]:
        """(e^(−h/τ), τ·(1 − e^(−h/τ))) for h quarters: the exact first-order response over h."""
        key = (quarters, coasting)
        if key not in self._factors:
            tau = 4.0 * (self.config.coast_tau_ms if coasting else self.config.speed_tau_ms)
            e = math.exp(-quarters / tau) if tau > 0 else 0.0
            self._factors[key] = (e, tau * (1.0 - e))
        return self._factors[key]

    def _run(self, demand: float, quarters: int, coasting: bool) -> None:
        e, g = self._lag(quarters, coasting)
        v = self.speed
        self.position += demand * quarters + (v - demand) * g
        self.speed = demand + (v - demand) * e

    def step(self, old: float, new: float, quarters: int, running: bool) -> None:
        """One POS period of `quarters`: the first 250 µs at the older demand, the rest at the newer one
        (the output channel's latency, L2112-2120). A drive that is not running coasts toward rest."""
        if not running:
            self._run(0.0, quarters, True)
            return
        self._run(old, 1, False)
        if quarters > 1:
            self._run(new, quarters - 1, False)

    def encoder_word(self) -> int:
        """The drive encoder's 48-bit word, quantised to its resolution."""
        step = self._step
        return (int(math.floor(self.position / step)) * step) & WORD48

    def marker_crossings(self, before: float, after: float) -> list[float]:
        """Fractions (0, 1] of the sample at which the marker angle was passed (linear in between)."""
        angle = self.config.marker_angle
        if angle is None or before == after:
            return []
        lo, hi = sorted((before, after))
        first = math.ceil((lo - angle * REV) / REV)
        last = math.floor((hi - angle * REV) / REV)
        marks = [(k + angle) * REV for k in range(first, last + 1)]
        return sorted((m - before) / (after - before) for m in marks if 0 < (m - before) / (after - before) <= 1)


class SlotEncoder:
    """A position option module's encoder in slot 1-3 (SM-Universal Encoder Plus and the like): a master that
    runs at a set speed (APC units) unless something else moves it. Its word advances with the POS period."""

    def __init__(self, speed: int = 0, word: int = 0):
        self.speed = speed
        self.word = word & WORD48
        self._rem = 0

    def advance(self, quarters: int) -> None:
        self.word = (self.word + self.speed * quarters) & WORD48
