"""The Design Guide walk-throughs: S1 stamping (92), S3 marker (112), S5 slavesync (108)."""

from __future__ import annotations

import numpy as np
import pytest

from motiontool.camcurve import (
    curve_info,
    decode,
    element_count,
    encode,
    engage_path,
    interpolation_points,
    max_start_stop_len,
    slave,
    velocity,
)
from tests.camcurve.conftest import marker_curve, slavesync_curve, stamping_curve


def test_stamping_is_92_elements(stamping):
    """DG L1476: "DIM stamping[92] // Number of elements from the title bar of the CAM-Editor"."""
    assert len(encode(stamping)) == element_count(stamping) == 92
    assert max_start_stop_len(stamping) == 2


def test_marker_is_112_elements(marker):
    """DG L1552: "DIM marker[112] // Number of elements from the title bar of the CAM-Editor"."""
    assert len(encode(marker)) == element_count(marker) == 112
    assert max_start_stop_len(marker) == 6  # span 500 / interval 100 + 1


def test_slavesync_is_108_elements(slavesync):
    """DG L1729: "DIM slavesync[108] // Number of elements from the title bar of the CAM-Editor"."""
    assert len(encode(slavesync)) == element_count(slavesync) == 108
    assert max_start_stop_len(slavesync) == 9  # span 800 / interval 100 + 1


def test_s1_slave_length_and_flat_velocity(stamping):
    """S1 step 6: "Slave Length = 3600. Velocity on 1500-2500 is constant at 1.2 UU/MU"."""
    assert stamping.slave_length == 3600
    xs = np.linspace(1500, 2500, 201)
    np.testing.assert_allclose(velocity(stamping, xs), 1.2, atol=1e-12)
    np.testing.assert_allclose(slave(stamping, xs), 1200 + 1.2 * (xs - 1500), atol=1e-9)


def test_s1_interval_time(stamping):
    """DG L1438: "The Number of Intervals = 40 results in a reasonable interval time of 25 ms"."""
    info = curve_info(stamping)
    assert info.interval_size == 100
    assert info.interval_time_ms == pytest.approx(25.0)
    assert info.max_velocity == pytest.approx(1.2)
    assert info.master_velocity == pytest.approx(4000.0)  # MU/s at 60 cycles/min


def test_s5_interval_times(slavesync):
    """DG L1659: "Number of Intervals = 36 produces a reasonable interval time of 27.7 ms" (at 60/min);
    S5 step 2: 83.3 ms at 20 cycles/min."""
    assert slavesync.interval_time_ms == pytest.approx(83.333, abs=1e-3)
    assert 60000 / 60 / slavesync.intervals == pytest.approx(27.78, abs=0.01)
    np.testing.assert_allclose(velocity(slavesync, np.linspace(1200, 2400, 50)), 1000 / 1200, atol=1e-12)


def test_interpolation_points_hit_fix_points_on_grid(stamping):
    """DG L1366: "The Fix points are used directly as interpolation points provided that this is permitted by the
    interval distance."""
    pts = interpolation_points(stamping)
    assert len(pts) == 41
    assert (pts[0], pts[15], pts[25], pts[40]) == (0, 1200, 2400, 3600)
    assert all(isinstance(v, int) for v in pts)


def test_cyclic_repetition_has_no_velocity_jump(stamping):
    """DG L1356: "In order to prevent speed leaps in the case of repeated curve cycles, the velocity at the
    beginning and the end is equated." (AVERAGE_GRADIENTS, the default)."""
    assert velocity(stamping, 0.0) == pytest.approx(velocity(stamping, 4000 - 1e-9), abs=1e-9)
    assert slave(stamping, 4000 + 1500) == pytest.approx(3600 + 1200)


def test_s3_engage_path(marker):
    """S3 step 6: the engage curve runs from slave position 0 at 1000 onto the profile at 1500."""
    xs, ys = engage_path(marker, 1)
    assert xs[0] == 1000 and xs[-1] == 1500 and len(xs) == 6
    assert ys[0] == 0 and ys[-1] == pytest.approx(slave(marker, 1500))
    fine_x, fine_y = engage_path(marker, 1, points=2001)
    v = np.gradient(fine_y, fine_x)
    assert v[0] == pytest.approx(0, abs=1e-3) and v[-1] == pytest.approx(velocity(marker, 1500), abs=1e-3)


@pytest.mark.parametrize("make", [stamping_curve, marker_curve, slavesync_curve])
def test_walkthrough_round_trip(make):
    curve = make()
    values = encode(curve)
    decoded = decode(values)
    assert decoded.values() == values
    assert decoded.to_curve() == curve
    assert list(decoded.interpolation_points) == interpolation_points(curve)
