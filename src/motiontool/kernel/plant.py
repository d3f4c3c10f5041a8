"""The simulated machine behind the controller: FC 300 speed loop, motor and load, encoder, switches.

The manual describes none of this (kernel-spec p.2); docs/plant.md documents the model and its defaults.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields


@dataclass
class PlantConfig:
    speed_tau_ms: float = 4.0          # first-order lag of the drive's speed loop (FC 300 + motor + load)
    speed_limit: float = 1.0           # largest speed the drive runs, as a fraction of VELMAX (FC 3-03 = VELMAX)
    friction: float = 0.0              # constant speed loss in qc/ms while moving (dry friction)
    blocked: bool = False              # a blocked axis: the motor cannot turn (provokes error 108)
    home_switch_qc: int = 20000        # raw encoder position where the reference switch starts
    home_switch_side: int = 1          # +1: switch active from home_switch_qc upwards; -1: downwards
    home_switch_width_qc: int = 8192   # length of the switch cam (HOME_TYPE 2/3 leave it in the same direction)
    neg_limit_switch_qc: int | None = None  # hardware limit switches (inputs with I_FUNCTION 3-6), None = none
    pos_limit_switch_qc: int | None = None
    index_period_qc: int | None = None      # index pulse every n qc; None = one per revolution (4 * 32-01)
    start_position_qc: float = 0.0
    # a marker sensor on the slave side, wired to input 6 (kernel/markers.py MarkerSensor), raw encoder qc
    slave_marker_period_qc: float = 0.0
    slave_marker_offset_qc: float = 0.0
    slave_marker_width_qc: float = 100.0
    slave_marker_positions_qc: tuple = ()

    @classmethod
    def from_mapping(cls, values: dict) -> PlantConfig:
        known = {f.name for f in fields(cls)}
        unknown = set(values) - known
        if unknown:
            raise ValueError(f"unknown plant setting(s): {', '.join(sorted(unknown))}")
        return cls(**values)


@dataclass
class Plant:
    config: PlantConfig = field(default_factory=PlantConfig)
    position: float = 0.0   # motor position in qc (continuous)
    velocity: float = 0.0   # qc/ms

    def __post_init__(self) -> None:
        self.position = float(self.config.start_position_qc)
        self._alpha = 1.0 - math.exp(-1.0 / max(self.config.speed_tau_ms, 1e-6))

    def step(self, speed_reference: float, vmax: float) -> None:
        """One millisecond: the speed follows the reference with the drive's lag, the position integrates
        (kernel/tick.py repeats it for a CAM axis: change both)."""
        cfg = self.config
        if cfg.blocked:
            self.velocity = 0.0
            return
        limit = cfg.speed_limit * vmax
        ref = limit if speed_reference > limit else (-limit if speed_reference < -limit else speed_reference)
        v = self.velocity + (ref - self.velocity) * self._alpha
        if cfg.friction:
            v = math.copysign(max(abs(v) - cfg.friction, 0.0), v)
        self.velocity = v
        self.position += v

    def home_switch(self) -> bool:
        cfg = self.config
        distance = (self.position - cfg.home_switch_qc) * (1 if cfg.home_switch_side > 0 else -1)
        return 0 <= distance <= cfg.home_switch_width_qc

    def limit_switches(self) -> tuple[bool, bool]:
        cfg = self.config
        neg = cfg.neg_limit_switch_qc is not None and self.position <= cfg.neg_limit_switch_qc
        pos = cfg.pos_limit_switch_qc is not None and self.position >= cfg.pos_limit_switch_qc
        return neg, pos
