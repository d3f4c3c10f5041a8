"""MCO curve → APC table with continuous slave speed (issue 23 item 10; decision C21). The six laws change speed
only from or to rest ("Square1 … used for linear velocity acceleration", 004 L1440), so the law-by-law
conversion stepped the speed at every join; "a second output array which is a dedicated output offset array
(OutArray2%)" for "a continuous speed offset … through the profile" (004 L1337), added "but it only uses linear
interpolation" (L3446), makes each Square1 segment a speed ramp from Y2/X to (2·Y1 + Y2)/X."""

from __future__ import annotations

import pytest

from motiontool.apc import ApcDrive
from motiontool.camcurve import spline
from motiontool.cameditor.apcconvert import curve_to_smooth_table, curve_to_table
from motiontool.cameditor.apcdpl import table_program
from motiontool.dpl.driver import check_source
from motiontool.dpl.runtime import DplRuntime
from tests.camcurve.conftest import slavesync_curve, stamping_curve


def _joins(table):
    window = table.window
    return [(window[k].end_speed(), window[(k + 1) % len(window)].start_speed()) for k in range(len(window))]


@pytest.mark.parametrize("make, scale", [(stamping_curve, 1), (stamping_curve, 10), (slavesync_curve, 7),
                                         (stamping_curve, 100)])
def test_the_speed_is_continuous_at_every_join_and_the_positions_follow_the_curve(make, scale):
    curve = make()
    old = curve_to_table(curve, counts_per_mu=scale, counts_per_uu=scale, tolerance=2.0).table
    assert sum(a != b for a, b in _joins(old)) >= len(old.segments) - 2  # what the user met: a step at each join
    result = curve_to_smooth_table(curve, counts_per_mu=scale, counts_per_uu=scale, tolerance=2.0)
    table = result.table
    assert [(a, b) for a, b in _joins(table) if a != b] == []  # exact, in whole counts, the wrap included
    assert not [f for f in table.check() if "speed step" in f.message]
    assert {s.law for s in table.segments} == {2} and table.has_slave2
    assert len({s.master for s in table.segments}) == 1  # equal lengths make the joins exact
    assert result.max_error <= 2.5  # counts; the kernel rounds every value to a count
    assert table.master_length == round(curve.master_length * scale)
    assert table.slave_travel == round((curve.fix_points[-1].slave - curve.fix_points[0].slave) * scale)
    speeds = [float(s.start_speed()) for s in table.segments]  # and the speed is the curve's, not just smooth
    masters = [sum(s.master for s in table.segments[:k]) for k in range(len(table.segments))]
    curve_speeds = spline.velocity(curve, [m / scale for m in masters])
    assert max(abs(a - b) for a, b in zip(speeds, curve_speeds, strict=True)) < 0.05 * max(abs(curve_speeds))


def test_the_simulated_apc_runs_the_smooth_table_as_drawn():
    """OutArray2 with per-segment laws (APCCamInitialise, mode -1): the kernel's reference equals the drawing."""
    table = curve_to_smooth_table(stamping_curve(), counts_per_mu=100, counts_per_uu=100).table
    drive = ApcDrive()
    runtime = DplRuntime(drive, check_source(table_program(table, master_rpm=100), "run.dpl"))
    runtime.start()
    runtime.advance(1)
    trace = []
    for _ in range(int(1.5 * table.master_length / 109)):  # 1.5 cycles at 100 rpm (109 counts per ms)
        runtime.advance(1)
        trace.append((drive.read("APC_RF_POS"), drive.read("APC_PROF_OUT_POS")))
    engaged_at = trace[0][0] - 109
    assert runtime.state == "running"
    assert [slave for _, slave in trace] == [table.reference(master - engaged_at) for master, _ in trace]
