"""The three curves of the Design Guide walk-throughs (seed 000 L1372-1744)."""

from __future__ import annotations

import pytest

from motiontool.camcurve import Curve, FixPoint, StartStopPair

STAMPING_POINTS = (FixPoint(0, 0), FixPoint(1500, 1200, "T"), FixPoint(2500, 2400, "T"), FixPoint(4000, 3600))


def stamping_curve() -> Curve:
    """S1 / DG L1435-1465: "A complete cycle length of the master is 400 mm; this corresponds to 4000 MU. The
    Number of Intervals = 40 results in a reasonable interval time of 25 ms." — "Master and slave must run
    synchronously with the same velocity between the position 1500 and 2500." Cycles/min Master = 60."""
    return Curve("stamping", 4000, STAMPING_POINTS, intervals=40, cycles_per_min=60)


def marker_curve() -> Curve:
    """S3 / DG L1500-1545: pairs "1 1000 1500 / 2 2500 3000", "Slave Stop Position = 0", "Correction Start = 3000
    Correction End = 1000", master marker position 1000 (OCR shows "100")."""
    return Curve("marker", 4000, STAMPING_POINTS, intervals=40, cycles_per_min=60,
                 start_stop_pairs=(StartStopPair(0, 0), StartStopPair(1000, 1500), StartStopPair(2500, 3000)),
                 correction_start=3000, correction_end=1000, master_marker_pos=1000)


def slavesync_curve() -> Curve:
    """S5 / DG L1660-1729: "master cycle length of 3600, the Number of Intervals = 36"; fix points (0,0) C,
    (1200,1500) T, (2400,2500) T, (3600,4000) C; "Cycles/min Master = 20"; "Engaging should take place between 20
    and 100 degrees" → pair (200,1000); "Slave-Marker-Position = 1000"; "Correction Start = 2800 Correction End
    = 750"."""
    points = (FixPoint(0, 0), FixPoint(1200, 1500, "T"), FixPoint(2400, 2500, "T"), FixPoint(3600, 4000))
    return Curve("slavesync", 3600, points, intervals=36, cycles_per_min=20,
                 start_stop_pairs=(StartStopPair(0, 0), StartStopPair(200, 1000)),
                 correction_start=2800, correction_end=750, slave_marker_pos=1000)


@pytest.fixture
def stamping() -> Curve:
    return stamping_curve()


@pytest.fixture
def marker() -> Curve:
    return marker_curve()


@pytest.fixture
def slavesync() -> Curve:
    return slavesync_curve()
