"""Curve Info limits and marker positions from the axis parameters, Qt-free.

Slave limits [DG L3813-3829, ide-spec 4.51/4.53 DERIVED]: qc per revolution = 4 × 32-01 ENCODER (incremental
encoder, quadrature), qc per UU = 32-12 POSFACT_Z / 32-11 POSFACT_N [DG L8131], VELMAX 32-80 [rpm], RAMPMIN
32-81 [s].  Marker detection point [DG L1572-1606, ide-spec 4.45 DERIVED]: marker position − marker distance,
reduced modulo the cycle (the controller buffers markers further away than one cycle).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from motiontool.camcurve.model import Curve
from motiontool.camcurve.spline import slave_acceleration_limit, slave_velocity_limit
from motiontool.paramdb import database

#: Parameters the Curve Info card and the marker display read.
LIMIT_PARAMETERS = ("32-01", "32-11", "32-12", "32-80", "32-81")


def parameter(parameters: dict[str, int | float], number: str) -> int | float:
    """The configuration's value, else the parameter's factory default."""
    return parameters.get(number, database().get(number).default)


@dataclass(frozen=True)
class SlaveLimits:
    velocity: float  # UU/MU
    acceleration: float  # UU/MU²


def slave_limits(curve: Curve, parameters: dict[str, int | float]) -> SlaveLimits:
    qc_per_rev = 4 * parameter(parameters, "32-01")
    qc_per_uu = parameter(parameters, "32-12") / parameter(parameters, "32-11")
    velmax, rampmin = parameter(parameters, "32-80"), parameter(parameters, "32-81")
    return SlaveLimits(
        slave_velocity_limit(velmax, qc_per_rev, qc_per_uu, curve.master_length, curve.cycles_per_min),
        slave_acceleration_limit(velmax, qc_per_rev, qc_per_uu, rampmin, curve.master_length, curve.cycles_per_min))


def marker_detection(position: float, distance: float, length: float) -> float:
    """Where on the curve the marker is detected: (position − distance) mod length.

    DG L1582-1606: master marker position 1000 and distance 2375 on a 4000 cycle → 2625; a distance beyond one
    cycle is buffered, so 4100 → 900, 3900 → 1100 and, with position 800, 3900 → 900."""
    return math.fmod(math.fmod(position - distance, length) + length, length)


def percent(value: float, limit: float) -> float:
    """``value`` as % of ``limit`` (infinite for a zero limit)."""
    return math.inf if limit <= 0 else 100.0 * abs(value) / limit
