"""The main profile generator (seed 004 §4.2.3, §4.4-4.6, §5.2.5, §8.6): limits, exact landing, retargets, flags,
stop modes."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.apc import trajectory as tj
from motiontool.apc.calculators import s_ramp, s_ramp_from_time
from motiontool.apc.profile import ProfileGenerator
from motiontool.apc.units import rpm_to_speed

from .helpers import enabled_drive

SCALE = 1 << 16


def run_to(pg: ProfileGenerator, target: int, n: int, retarget=None):
    """Samples of (position, speed, accel, jerk) in APC units until the generator rests on its target."""
    trace = []
    v, a = pg.max_speed / SCALE, min(pg.accel, pg.decel) / SCALE        # counts per quarter, per quarter²
    far = abs(target - pg.position) + (abs(retarget[1] - target) if retarget else 0)
    quarters = far / v + 4 * v / a + (4 * a / (pg.jerk / SCALE) if pg.jerk else 0)
    max_samples = int(2 * quarters / n) + (retarget[0] if retarget else 0) + 1000
    for k in range(max_samples):
        if retarget and k == retarget[0]:
            target = retarget[1]
        pg.to_position(target, n)
        trace.append((pg.position, pg.output_speed(), pg.output_acceleration(), pg.output_jerk()))
        if pg.at_target() and k > (retarget[0] if retarget else 0):
            return trace, target
    raise AssertionError("the profile never reached its target")


def check_limits(pg: ProfileGenerator, trace, n: int):
    accel, decel, vmax, jerk = pg.accel, pg.decel, pg.max_speed, pg.jerk
    prev_pos = None
    for pos, v, a, j in trace:
        assert abs(v) <= vmax + 1
        assert abs(a) <= max(accel, decel) + 1
        if abs(v) > abs(a) * n:          # clearly on one side of zero speed: accel away from it, decel toward it
            assert abs(a) <= (accel if (a > 0) == (v > 0) else decel) + 1
        if jerk:
            assert abs(j) <= jerk + 1
        if prev_pos is not None:    # the sampled positions move no faster than the maximum speed
            assert abs(pos - prev_pos) <= vmax * n / SCALE + 1
        prev_pos = pos


moves = st.tuples(
    st.integers(-2_000_000, 2_000_000),                       # target, counts
    st.integers(2000, 200_000), st.integers(2000, 200_000),   # accel, decel
    st.integers(2_000_000, 60_000_000),                       # max speed
    st.sampled_from([0, 0, 50, 500, 5000]),                   # jerk (0 = linear)
    st.sampled_from([1, 2, 4, 8]),                            # quarters per sample
)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(moves)
def test_profile_never_exceeds_its_limits_and_lands_exactly(move):
    """L803-820 moves within accel, decel and maximum speed; L822-841 jerk limits the change of acceleration;
    L1193-1199 the axis "will stop at" the set point — exactly, in counts."""
    target, accel, decel, vmax, jerk, n = move
    pg = ProfileGenerator(accel=accel, decel=decel, jerk=jerk, max_speed=vmax)
    trace, _ = run_to(pg, target, n)
    check_limits(pg, trace, n)
    assert pg.position == target and pg.output_speed() == 0 and pg.output_acceleration() == 0


@settings(max_examples=40, deadline=None, derandomize=True)
@given(moves, st.integers(-2_000_000, 2_000_000), st.integers(1, 400))
def test_profile_retargeted_mid_move_stays_in_limits_and_lands_exactly(move, second, when):
    """L1193-1199 "the position setpoint can be set dynamically while a profile is already in progress"."""
    target, accel, decel, vmax, jerk, n = move
    pg = ProfileGenerator(accel=accel, decel=decel, jerk=jerk, max_speed=vmax)
    trace, final = run_to(pg, target, n, retarget=(when, second))
    check_limits(pg, trace, n)
    assert pg.position == final


def test_retarget_from_100000_to_200000_at_50000():
    """L1195-1197 "If the position set point is set to 100000, and the feedback axis has travelled to 50000, then if
    the setpoint is changed to 200000, the Feedback axis will stop at 200000"."""
    d = enabled_drive()
    d.APCSetPositionSetPoint(100000)
    d.APCSelectReference(1)
    while d.read(48) < 50000:
        d.tick()
    d.APCSetPositionSetPoint(200000)
    peak = 0
    for _ in range(3000):
        d.tick()
        peak = max(peak, d.read(117))
    assert d.read(117) == 200000 and peak == 200000
    assert abs(d.read(48) - 200000) <= 1


def test_indexing_past_2_31_wraps_seamlessly():
    """L1205-1209 "the position reference will roll-over with the feedback once -2^31 to 2^31-1 is exceeded. This
    means that the user can Index in one direction infinitely"."""
    pg = ProfileGenerator(max_speed=rpm_to_speed(3000), accel=200000, decel=200000)
    pg.reset(2**31 - 100_000)
    target = pg.position
    for _ in range(3):
        target = (target + 150_000 + 2**31) % 2**32 - 2**31     # setpoint += index, in int32
        trace, _ = run_to(pg, target, 4)
        assert all(v >= 0 for _, v, _, _ in trace)             # never backwards
        assert pg.position == target
    assert pg.position < 0                                     # it crossed +2^31


def test_s_ramp_closed_forms_with_the_p3_erratum():
    """L7060-7110 §8.6 Case A; P3 = T_S·V − J·T_S³/6 (the printed A³/(4J²) is wrong, spec §9.3), so
    P_total = (V/2)(V/A + A/J) = (2T_S + T_A)·V/2."""
    r = s_ramp(1000.0, 200.0, 400.0)
    assert r.t_s == 0.5 and r.t_a == 4.5
    assert r.p1 + r.p2 + r.p3 == pytest.approx(r.p_total)
    assert r.p_total == pytest.approx((2 * r.t_s + r.t_a) * 1000 / 2)
    assert r.p3 != pytest.approx(200.0 ** 3 / (4 * 400.0 ** 2))
    a, j = s_ramp_from_time(1000.0, 2.0, 50)         # Case B: half of the ramp time in jerk
    assert a == pytest.approx(1000 / 1.5) and j == pytest.approx(a / 0.5)


def test_the_generator_follows_the_s_ramp_distance():
    """The planner's ramp from rest to V with A and J covers the §8.6 P_total (L7106-7110)."""
    lim = tj.Limits(accel=2.0, decel=2.0, speed=1000.0, jerk=0.5)
    pieces = tj.speed_change(0.0, 0.0, 100.0, lim)
    assert tj.distance(0.0, pieces) == pytest.approx(s_ramp(100.0, 2.0, 0.5).p_total)
    assert sum(p.duration for p in pieces) == pytest.approx(100 / 2 + 2 / 0.5)


def test_profiled_stop_ends_at_the_predicted_stop_position():
    """L1172-1176 "the stop reference being loaded with the current position plus the stopping distance … The Final
    calculated stopping position is shown by read parameter [91]"."""
    d = enabled_drive()
    d.APCSetSpeedSetPoint(rpm_to_speed(1000))
    d.APCSelectReference(2)
    d.run_ms(300)
    predicted = d.read(91)
    d.APCSelectReference(0)
    d.run_ms(500)
    assert d.read(117) == predicted == d.read(91)


def test_instant_stop_freezes_the_reference():
    """L1178-1182 "setting the stop reference to the current position, and bypassing the profile generator"."""
    d = enabled_drive()
    d.APCSetStopMode(1)
    d.APCSetSpeedSetPoint(rpm_to_speed(600))
    d.APCSelectReference(2)
    d.run_ms(200)
    here = d.read(117)
    d.APCSelectReference(0)
    d.tick()
    assert d.read(117) == here and d.read(118) == 0


def test_linear_stop_ignores_jerk_and_speed_stop_ramps_speed():
    """L1184-1191: mode 2 "linear ramps … regardless of whether S ramps (Jerk) are used"; mode 3 "speed ramps only"."""
    for mode in (2, 3):
        d = enabled_drive()
        d.APCSetProfileJerk(200)
        d.APCSetStopMode(mode)
        d.APCSetSpeedSetPoint(rpm_to_speed(600))
        d.APCSelectReference(2)
        d.run_ms(400)
        d.APCSelectReference(0)
        jerks = []
        for _ in range(400):
            d.tick()
            jerks.append(d.read(187))
        assert d.read(118) == 0
        assert (max(map(abs, jerks)) == 0) == (mode == 2)


def test_flags_during_a_position_move():
    """L854-918, Table 4-1: accelerating, constant speed, decelerating, profiling, at target; [186] holds them in
    bits 0-9."""
    d = enabled_drive()
    d.APCSetPositionSetPoint(2_000_000)
    d.APCSelectReference(1)
    seen = set()
    for _ in range(3000):
        d.tick()
        seen |= {n for n in range(120, 130) if d.read(n)}
        assert d.read(186) & 0x3FF == sum(d.read(120 + b) << b for b in range(10))
    assert {124, 125, 126, 129} <= seen and 127 not in seen and 128 not in seen
    assert d.read(120) == 1 and d.read(129) == 0


def test_speed_reference_runs_at_its_exact_speed():
    """L1211-1222 speed set point in 2^32 counts/rev per 250 µs: 100 rpm is 1092.27 counts per ms on average."""
    d = enabled_drive()
    speed = rpm_to_speed(100)
    d.APCSetSpeedSetPoint(speed)
    d.APCSelectReference(2)
    d.run_ms(100)
    start = d.read(117)
    d.run_ms(60_000)
    assert abs(d.read(117) - start - speed * 4 * 60_000 / 65536) < 1       # 65536 counts in 0.6 s: no drift


@pytest.mark.parametrize("code", [1, 2, 3, 4, 5, 6])
def test_every_pos_rate_runs_the_same_motion(code):
    """L655-673 "The motion/position task can be run at … 250μs, 500μs, 1ms, 2ms, 4ms & 8ms": the units are per
    250 µs whatever the rate, so a jog covers the same distance in the same time at every rate."""
    from motiontool.apc import ApcDrive
    d = ApcDrive(pos_rate=code)
    d.APCSetRunMode(2)
    d.run_ms(8)
    d.APCSetSpeedSetPoint(rpm_to_speed(600))
    d.APCSelectReference(2)
    d.run_ms(200)                            # up to speed (600 rpm at 5000 rpm/s takes 120 ms)
    start, t0 = d.read(117), d.time_ns
    d.run_ms(1000)
    assert d.time_ns - t0 == 1_000_000_000
    assert abs(d.read(117) - start - rpm_to_speed(600) * 4000 / 65536) <= 1


def test_reference_switching_is_bumpless():
    """L787-801 "bump-less" transfer: "the profile generator is used to ramp to the new position or speed reference,
    so that there are no sudden jumps in Feedback axis position or speed": from a running digital lock to Stop
    and then to Position, the speed changes by at most the ramp per sample."""
    from .helpers import VirtualMaster
    d = enabled_drive()
    VirtualMaster(d, 600)
    d.APCSelectReference(4)
    d.run_ms(300)
    assert d.read(61) == 1
    ramp = 22369 * 4 + 1                      # default accel/decel per 1 ms sample, APC units
    last = d.read(118)
    for reference, ms in ((0, 400), (1, 600)):
        d.APCSelectReference(reference)
        for _ in range(ms):
            d.tick()
            now = d.read(118)
            assert abs(now - last) <= ramp
            last = now
    assert d.read(117) == d.read(92) == 0
