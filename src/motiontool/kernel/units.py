"""Unit scaling of the MCO 305 (spec a): user units, velocity and acceleration from parameters.

qc = quad counts; velocities in qc per ms, accelerations in qc per ms², jerk in qc per ms³.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Scaling:
    posfact_z: int = 1     # 32-12
    posfact_n: int = 1     # 32-11
    velmax_rpm: int = 1500  # 32-80
    encoder_ppr: int = 1024  # 32-01
    velres: int = 100      # 32-83
    rampmin_ms: int = 1000  # 32-81 (raw, ms)
    # derived in __post_init__: not arguments, not compared (a field without a default: no class attribute)
    vmax: float = field(init=False, repr=False, compare=False)
    amax: float = field(init=False, repr=False, compare=False)

    @classmethod
    def from_params(cls, p) -> Scaling:
        return cls(max(1, p["POSFACT_Z"]), max(1, p["POSFACT_N"]), max(1, p["VELMAX"]), max(1, p["ENCODER"]),
                   max(1, p["VELRES"]), max(1, p["RAMPMIN"]))

    # DG 300-304: UU → qc truncates, qc → UU rounds.
    def uu_to_qc(self, uu: int | float) -> int:
        q = uu * self.posfact_z
        n = self.posfact_n
        return int(q / n) if isinstance(q, float) else (abs(q) // n) * (1 if q >= 0 else -1)

    def qc_to_uu(self, qc: float) -> int:
        value = qc * self.posfact_n / self.posfact_z
        return int(value + 0.5) if value >= 0 else -int(-value + 0.5)

    def __post_init__(self) -> None:
        # plain attributes, not cached properties: the axis reads vmax every tick
        vmax = self.velmax_rpm * self.encoder_ppr * 4 / 60000.0
        object.__setattr__(self, "vmax", vmax)  # VELMAX in qc/ms (DG 9070-9086: 3000 rpm, 500 PPR → 100 qc/ms)
        object.__setattr__(self, "amax", vmax / self.rampmin_ms)  # VELMAX / RAMPMIN in qc/ms² (DG 8959-8973)

    def velocity(self, v: int) -> float:
        """VEL/CVEL/HOME_VEL value (fraction of VELMAX with denominator VELRES) → qc/ms (CR 713-740)."""
        return v * self.vmax / self.velres

    def acceleration(self, a: int) -> float:
        """ACC/DEC value (fraction of the maximum acceleration with denominator VELRES) → qc/ms²."""
        return a * self.amax / self.velres

    def velocity_uu_per_s(self, qc_per_ms: float) -> int:
        return self.qc_to_uu(qc_per_ms * 1000.0)
