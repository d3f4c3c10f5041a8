"""The simulated Unidrive SP behind the APC: speed loop, motor and load, encoders (docs/apc.md "Behaviour in
brief").

The APC manual describes none of this (**inferred** model, docs/decisions.md A44): the drive's speed loop
follows its speed reference as a first-order lag, the motor position integrates the speed, and the drive
encoder quantises it to its counts per revolution in the 48-bit turns|coarse|fine word (L998-1016). A trip
or a drive without "reference on" lets the motor coast down. Positions are in units of the 48-bit word
(2^32 per revolution) and speeds in APC units (2^32 per revolution per 250 µs), so one quarter of speed moves
the word by exactly the speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

WORD48 = (1 << 48) - 1
REV = 1 << 32


@dataclass
class PlantConfig:
    speed_tau_ms: float = 2.0       # the drive's closed speed loop as a first-order lag
    coast_tau_ms: float = 300.0     # how a tripped or disabled drive's motor runs down
    encoder_cpr: int = 65536        # counts per revolution of the drive encoder (4096 ppr quadrature = 16384)
    start_revolutions: float = 0.0  # motor position at power-up
    marker_angle: float | None = 0.0    # the encoder's marker (index) pulse at this fraction of a turn, or None


class Plant:
    """Motor + load + drive speed loop, stepped one POS period at a time with the output-channel latency."""

    def __init__(self, config: PlantConfig | None = None):
        self.config = config or PlantConfig()
        self.position = self.config.start_revolutions * REV    # 48-bit word units, float
        self.speed = 0.0                                       # APC speed units
        self.set_encoder_cpr(self.config.encoder_cpr)          # the drive encoder's word, kept with the position
        angle = self.config.marker_angle
        self.marker_phase = None if angle is None else angle * REV
        self._mark_window = (-math.inf, math.inf)   # the marker positions around the motor (see passed_marker)
        if self.marker_phase is not None:
            self._set_mark_window()
        self.configure(4)

    def _set_mark_window(self) -> None:
        phase = self.marker_phase
        assert phase is not None  # without a marker the window stays infinite: step() never asks for a new one
        k = math.floor((self.position - phase) / REV)
        self._mark_window = (k * REV + phase, (k + 1) * REV + phase)

    def update_marker_window(self) -> None:
        """After a marker was passed: the marker positions either side of the motor now."""
        self._set_mark_window()

    def configure(self, quarters: int) -> None:
        """Precompute the exact first-order response for the first 250 µs, the rest of the period, and a coast."""
        def lag(h: float, tau_ms: float) -> tuple[float, float]:
            tau = 4.0 * tau_ms
            e = math.exp(-h / tau) if tau > 0 else 0.0
            return e, tau * (1.0 - e)
        self.quarters = quarters
        self._first = lag(1, self.config.speed_tau_ms)
        self._rest = lag(quarters - 1, self.config.speed_tau_ms)
        self._coast = lag(quarters, self.config.coast_tau_ms)

    def step(self, old: float, new: float, running: bool) -> bool:
        """One POS period: the first 250 µs at the older demand, the rest at the newer one (the output channel's
        latency, L2112-2120). A drive that is not running coasts toward rest. True when a marker was passed
        (then `update_marker_window` must follow)."""
        v = self.speed
        if running:
            e, g = self._first
            d = v - old
            pos = self.position + old + d * g
            v = old + d * e
            q = self.quarters - 1
            if q:
                e, g = self._rest
                d = v - new
                pos += new * q + d * g
                v = new + d * e
        else:
            e, g = self._coast
            pos = self.position + v * g
            v *= e
        self.position = pos
        self.speed = v
        step = self._step
        if step:
            self.word = (int(pos // step) * step) & WORD48
        else:
            self.word = self._quantised()
        lo, hi = self._mark_window
        return pos < lo or pos >= hi

    def encoder_word(self) -> int:
        """The drive encoder's 48-bit word, quantised to its resolution (the attribute `word`, set with every
        position)."""
        return self.word

    def set_encoder_cpr(self, cpr: int) -> None:
        """The drive encoder's counts per revolution (4 × its lines, #3.34); the word is quantised anew. A count
        that does not divide the turn is placed at the nearest word below count·2^32/cpr, so a turn stays 2^32."""
        cpr = self.encoder_cpr = max(1, min(int(cpr), REV))
        self._step = REV // cpr if REV % cpr == 0 else 0      # 0: the exact (slower) form in _quantised
        self.word = self._quantised()

    def _quantised(self) -> int:
        cpr = self.encoder_cpr
        return (math.floor(self.position * cpr / REV) * REV // cpr) & WORD48

    def marker_crossings(self, before: float, after: float) -> list[float]:
        """Fractions (0, 1] of the sample at which the marker angle was passed (linear in between)."""
        phase = self.marker_phase
        if phase is None or before == after:
            return []
        k0 = math.floor((before - phase) / REV)
        k1 = math.floor((after - phase) / REV)
        if k0 == k1:
            return []
        if k1 - k0 in (1, -1):     # one marker, the usual case: the list below without building it
            return [((k1 if k1 > k0 else k0) * REV + phase - before) / (after - before)]
        lo, hi = (k0 + 1, k1) if k1 > k0 else (k1 + 1, k0)
        marks = [k * REV + phase for k in range(lo, hi + 1)]
        return sorted((m - before) / (after - before) for m in marks)


class SlotEncoder:
    """A position option module's encoder in slot 1-3 (SM-Universal Encoder Plus and the like): a master that
    runs at a set speed (APC units) unless something else moves it. Its word advances with the POS period."""

    def __init__(self, speed: int = 0, word: int = 0):
        self.speed = speed
        self.word = word & WORD48

    def advance(self, quarters: int) -> None:
        self.word = (self.word + self.speed * quarters) & WORD48
