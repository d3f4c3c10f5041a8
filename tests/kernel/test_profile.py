"""Profile generator (kernel spec a.4, a.5, c.1-c.5, p.3; DG 1860-1972, 8975-9172; docs/profile-generator.md).

Units: qc, qc/tick, qc/tick², qc/tick³; 1 tick = 1 ms.  The manual's defaults: VELMAX 1500 RPM at the encoder
with 1024 PPR = 4096 qc/rev -> 102.4 qc/ms [DG 9070-9086 scaling: v/VELRES × VELMAX × PPR × 4 / 60000], and
"Ramp for Home Motion [ms] = VELRES / HOME_RAMP × Shortest Ramp" [DG 9224-9246], i.e. ramp time to full speed
= RAMPMIN × VELRES / ACC = 1000 ms at ACC 100 % -> 0.1024 qc/ms².

Micro benchmark (CPython 3.11.7, this machine, `min(timeit.repeat(gen.step, number=200000, repeat=5))`;
"whole move" = `move_to(204800)` with vel 102.4, acc = dec 0.1024, JERKMIN 100 ms, then `while not g.done:
g.step()`; "re-plan" = one `move_to` to a new target while moving):

    per step()            in a ramp  cruising  final approach  standing still
    type 0 trapezoid       0.4-0.7    0.40       0.5-0.85        0.06 µs
    type 1 S-ramp (sin²)   0.8        0.40       0.55            0.06 µs
    type 2 limited jerk    0.4        0.40       0.55            0.06 µs
    whole move: type 0 3000 ticks 1.9 ms (0.62 µs/tick), type 1 4000 ticks 4.0 ms (0.99 µs/tick),
                type 2 3100 ticks 2.1 ms (0.68 µs/tick), all including the `done` check
    planning: move_to from rest 7 / 12 / 60 µs, re-plan while moving 20 / 45 / 230 µs (types 0 / 1 / 2)

Timing is not asserted here.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.kernel.profile import Limits, ProfileGenerator

REL = 1e-9
SETTINGS = settings(deadline=None, derandomize=True, max_examples=40)


def run(gen: ProfileGenerator, max_ticks: int = 200_000):
    """Step until done; arrays of position, velocity, acceleration including the starting state."""
    p, v, a = [gen.position], [gen.velocity], [gen.acceleration]
    for _ in range(max_ticks):
        if gen.done:
            break
        gen.step()
        p.append(gen.position)
        v.append(gen.velocity)
        a.append(gen.acceleration)
    else:
        raise AssertionError(f"not done after {max_ticks} ticks")
    return np.array(p), np.array(v), np.array(a)


def steps(gen: ProfileGenerator, n: int):
    p, v, a = [], [], []
    for _ in range(n):
        gen.step()
        p.append(gen.position)
        v.append(gen.velocity)
        a.append(gen.acceleration)
    return np.array(p), np.array(v), np.array(a)


def trapezoid_ticks(dist: float, vel: float, acc: float, dec: float) -> float:
    """Continuous time-optimal rest-to-rest time of a trapezoid (or triangle)."""
    vp = min(vel, math.sqrt(2.0 * dist * acc * dec / (acc + dec)))
    return dist / vp + vp / (2 * acc) + vp / (2 * dec) if vp > 0.0 else 0.0


def assert_limits(lim: Limits, p, v, a, vmax=None):
    """The sampled profile respects the limits, also as per-tick differences of CPOS."""
    vmax = lim.vel if vmax is None else max(vmax, lim.vel)
    amax = max(lim.acc, lim.dec)
    scale = 1e-12 * (np.max(np.abs(p)) + 1.0)  # rounding of position differences
    assert np.max(np.abs(v)) <= vmax * (1 + REL)
    assert np.max(np.abs(a)) <= amax * (1 + REL)
    dp = np.diff(p)
    assert np.max(np.abs(dp), initial=0.0) <= vmax * (1 + REL) + scale
    assert np.max(np.abs(np.diff(dp)), initial=0.0) <= amax * (1 + REL) + 2 * scale
    assert np.max(np.abs(np.diff(v)), initial=0.0) <= amax * (1 + REL) + 1e-12
    if lim.ramp_type == 2:
        assert np.max(np.abs(np.diff(a)), initial=0.0) <= max(lim.jerks()) * (1 + REL)


# ------------------------------------------------------------------------------------------- fixed cases


def test_manual_default_move_takes_3000_ticks():
    """VEL 100 % = 102.4 qc/ms, ACC = DEC 100 % (RAMPMIN 1000 ms × VELRES / ACC = 1 s to full speed, DG
    9224-9246): 204800 qc = 1 s ramp up + 1 s at full speed + 1 s ramp down."""
    lim = Limits(vel=102.4, acc=0.1024, dec=0.1024)
    gen = ProfileGenerator()
    gen.move_to(204800, lim)
    assert gen.remaining_ticks() == 3000
    p, v, a = run(gen)
    assert len(p) - 1 in (3000, 3001)
    assert p[-1] == 204800.0 and gen.position == 204800.0 and gen.done
    assert np.max(v) <= 102.4 * (1 + 1e-12) and np.max(np.abs(a)) <= 0.1024 * (1 + 1e-12)
    assert_limits(lim, p, v, a)
    assert np.all(np.diff(p) >= 0.0)
    assert v[1000] == pytest.approx(102.4) and v[2000] == pytest.approx(102.4)
    assert p[1000] == pytest.approx(51200.0) and p[1500] == pytest.approx(102400.0)
    gen.step()
    assert (gen.position, gen.velocity, gen.acceleration) == (204800.0, 0.0, 0.0) and gen.done


def test_triangle_when_vel_is_not_reached():
    lim = Limits(vel=100.0, acc=1.0, dec=1.0)
    gen = ProfileGenerator(10.0)
    gen.move_to(1010.0, lim)
    p, v, a = run(gen)
    assert len(p) - 1 == math.ceil(2 * math.sqrt(1000.0))  # t = 2 sqrt(d / acc) = 63.25
    assert math.sqrt(1000.0) - 1.0 < np.max(v) <= math.sqrt(1000.0)  # peak sqrt(d acc) < vel, sampled
    assert p[-1] == 1010.0
    assert_limits(lim, p, v, a)


def test_asymmetric_trapezoid_is_time_optimal_and_backwards():
    lim = Limits(vel=20.0, acc=0.5, dec=0.125)
    gen = ProfileGenerator(0.0)
    gen.move_to(-10000.0, lim)
    expected = trapezoid_ticks(10000.0, 20.0, 0.5, 0.125)  # 500 + 20 + 80
    assert gen.remaining_ticks() == math.ceil(expected)
    p, v, a = run(gen)
    assert len(p) - 1 == math.ceil(expected) and p[-1] == -10000.0
    assert np.all(np.diff(p) <= 0.0)
    assert_limits(lim, p, v, a)


def test_limited_jerk_and_s_ramp_are_slower_than_trapezoid():
    ticks = {}
    for rt in (0, 1, 2):
        gen = ProfileGenerator()
        lim = Limits(102.4, 0.1024, 0.1024, rt, (0.1024 / 200, 0, 0, 0))  # JERKMIN 200 ms
        gen.move_to(204800, lim)
        p, v, a = run(gen)
        assert p[-1] == 204800.0
        assert_limits(lim, p, v, a)
        ticks[rt] = len(p) - 1
    assert ticks[0] < ticks[2] < ticks[1]
    assert ticks[2] == 3000 + 200  # each velocity ramp is JERKMIN (200) longer, the cruise 200 shorter
    assert ticks[1] == 4000  # sin² ramps: peak acceleration = ACC, mean ACC/2, twice as long (docs)


def test_limited_jerk_seven_segments_use_the_four_jerks():
    """DG 1886-1892, 1945-1951: J1 acc ramp-up, J2 acc ramp-down, J3 dec ramp-up, J4 dec ramp-down, plateaus at
    ACC, VEL and DEC."""
    j = (0.001, 0.002, 0.0005, 0.00025)
    lim = Limits(vel=50.0, acc=0.1, dec=0.05, ramp_type=2, jerk=j)
    gen = ProfileGenerator()
    gen.move_to(200000.0, lim)
    p, v, a = run(gen)
    assert p[-1] == 200000.0
    assert_limits(lim, p, v, a)
    da = np.diff(a)
    # inside each phase the jerk is exactly the DG one (per-tick changes are J or a fraction of it at a corner)
    for sel, jl in (((a[1:] > 0) & (da > 0), j[0]), ((a[1:] > 0) & (da < 0) & (a[:-1] > 0), j[1]),
                    ((a[:-1] < 0) & (da < 0) & (a[1:] < 0), j[2]), ((a[1:] < 0) & (da > 0), j[3])):
        assert np.max(np.abs(da[sel])) == pytest.approx(jl, rel=1e-9)
    assert np.max(a) == pytest.approx(0.1) and np.min(a) == pytest.approx(-0.05) and np.max(v) == pytest.approx(50)
    # 7 segments: ramp 100 + hold + ramp 50, cruise, ramp 100 + hold + ramp 200
    assert len(gen._segs) == 7


def test_limited_jerk_short_move_skips_the_plateaus():
    """DG 1959: acc ramp-up (maybe up to max acc), acc ramp-down, dec ramp-up, maybe constant dec, ramp-down."""
    lim = Limits(vel=50.0, acc=0.1, dec=0.1, ramp_type=2, jerk=(0.001, 0, 0, 0))
    gen = ProfileGenerator()
    gen.move_to(100.0, lim)
    p, v, a = run(gen)
    assert p[-1] == 100.0 and np.max(np.abs(a)) < 0.1 and np.max(v) < 50
    assert np.all(np.diff(p) >= 0)
    # symmetric jerk-limited triangle: t = 4 (d / 2j)^(1/3)
    assert len(p) - 1 == math.ceil(4 * (100.0 / 0.002) ** (1 / 3))
    assert_limits(lim, p, v, a)


def test_limited_jerk_reversal_flows_through_zero_velocity():
    """DG 1898, 1940-1942: from -v to +v with ACC > DEC the deceleration plateau continues at v = 0 as acceleration."""
    lim = Limits(vel=20.0, acc=0.2, dec=0.1, ramp_type=2, jerk=(0.01, 0.01, 0.01, 0.01))
    gen = ProfileGenerator()
    gen.run_at(-20.0, lim)
    run(gen)
    assert gen.velocity == -20.0 and gen.acceleration == 0.0
    gen.run_at(20.0, lim)
    p, v, a = run(gen)
    assert gen.velocity == 20.0 and gen.acceleration == 0.0
    k = int(np.argmax(v >= 0))
    assert 0.1 * (1 - REL) <= a[k - 1] <= a[k] <= 0.11  # DEC plateau becomes acceleration: no ramp to 0
    assert np.max(a) == pytest.approx(0.2)
    assert_limits(lim, p, v, a)


def test_limited_jerk_stop_with_too_high_deceleration_overshoots_zero_and_comes_back():
    """DG 1922-1924: negative velocity, very high deceleration: J4 ramp-down, pass v = 0, J2, then J3/J4."""
    fast = Limits(vel=10.0, acc=1.0, dec=1.0, ramp_type=2, jerk=(1.0, 1.0, 1.0, 1.0))
    gen = ProfileGenerator()
    gen.run_at(-10.0, fast)
    run(gen)
    gen.run_at(0.0, fast)
    while gen.velocity < -1.0:  # braking at DEC = 1 with velocity -1
        gen.step()
    slow = Limits(vel=10.0, acc=1.0, dec=1.0, ramp_type=2, jerk=(0.01, 0.01, 0.01, 0.01))
    gen.stop(slow)
    p, v, a = run(gen)
    assert np.max(v) > 0.0  # came back
    assert gen.velocity == 0.0 and gen.acceleration == 0.0 and gen.done
    assert np.max(np.abs(np.diff(a))) <= 0.01 * (1 + REL)


def test_hold_idle_done_and_validation():
    gen = ProfileGenerator(5.0)
    assert gen.mode == "idle" and gen.done and gen.target is None and gen.remaining_ticks() == 0
    gen.step()
    assert (gen.position, gen.velocity, gen.acceleration) == (5.0, 0.0, 0.0)
    lim = Limits(10.0, 1.0, 1.0)
    gen.move_to(5.0, lim)  # already there
    assert gen.done and gen.mode == "position" and gen.target == 5.0
    gen.move_to(100.0, lim)
    steps(gen, 5)
    gen.hold()
    assert gen.mode == "idle" and gen.velocity == 0.0 and gen.acceleration == 0.0 and gen.done
    gen.hold(7.5)
    gen.step()
    assert gen.position == 7.5
    for bad in (dict(vel=0.0, acc=1, dec=1), dict(vel=1, acc=-1, dec=1), dict(vel=1, acc=1, dec=math.inf),
                dict(vel=1, acc=1, dec=1, ramp_type=3), dict(vel=1, acc=1, dec=1, ramp_type=2)):
        with pytest.raises(ValueError):
            Limits(**bad)
    assert Limits(1, 1, 1, 2, (0.5, 0, 0.25, 0)).jerks() == (0.5, 0.5, 0.25, 0.5)  # 0 = same as JERKMIN


def test_repeated_identical_move_to_keeps_the_plan():
    lim = Limits(10.0, 0.1, 0.1, 2, (0.01, 0, 0, 0))
    a = ProfileGenerator()
    b = ProfileGenerator()
    a.move_to(5000.0, lim)
    b.move_to(5000.0, lim)
    for _ in range(300):
        a.step()
        b.step()
        b.move_to(5000.0, lim)  # POSA in a NOWAIT loop
    assert (a.position, a.velocity, a.acceleration) == (b.position, b.velocity, b.acceleration)


# ------------------------------------------------------------------------------------------- properties


@st.composite
def limits(draw, ramp_type: int) -> Limits:
    vel = draw(st.floats(0.2, 200.0))
    acc = vel / draw(st.floats(1.0, 1500.0))  # ramp times of 1..1500 ticks
    dec = vel / draw(st.floats(1.0, 1500.0))
    jerk = tuple(max(acc, dec) / draw(st.floats(1.0, 400.0)) for _ in range(4))
    return Limits(vel, acc, dec, ramp_type, jerk)


@st.composite
def scenario(draw, ramp_type: int):
    """Limits, a prefix command that produces an arbitrary moving state, and the final target."""
    lim = draw(limits(ramp_type))
    start = draw(st.floats(-1e6, 1e6))
    prefix = draw(st.sampled_from(["rest", "run", "move"]))
    prefix_arg = draw(st.floats(-1.0, 1.0))
    prefix_ticks = draw(st.integers(0, 2000))
    new_vel = lim.vel * draw(st.sampled_from([1.0, 1.0, 0.5, 2.0, 0.25]))
    dist = draw(st.one_of(st.floats(-3000.0, 3000.0), st.floats(-1.0, 1.0))) * lim.vel
    return lim, start, prefix, prefix_arg, prefix_ticks, new_vel, dist


def prepare(lim: Limits, start, prefix, prefix_arg, prefix_ticks) -> ProfileGenerator:
    gen = ProfileGenerator(start)
    if prefix == "run":
        gen.run_at(prefix_arg * lim.vel, lim)
    elif prefix == "move":
        gen.move_to(start + prefix_arg * 2000 * lim.vel, lim)
    if prefix != "rest":
        steps(gen, prefix_ticks)
    return gen


def overshoot_allowance(lim: Limits, v0: float, a0: float) -> float:
    """|v| an unavoidable velocity overshoot may reach: a speeding-up acceleration must first ramp down (J2)."""
    if lim.ramp_type == 2 and v0 * a0 >= 0.0:
        return abs(v0) + a0 * a0 / (2 * lim.jerks()[1])
    return abs(v0)


def tick_bound(lim: Limits, v0: float, a0: float, dist: float) -> float:
    """A generous independent bound on the ticks of any move: stop, then go the whole way from rest."""
    k = 2.0 if lim.ramp_type == 1 else 1.0
    acc, dec = lim.acc / k, lim.dec / k
    ramps = 0.0
    if lim.ramp_type == 2:
        j = lim.jerks()
        ramps = 2 * (lim.acc / j[0] + lim.acc / j[1] + lim.dec / j[2] + lim.dec / j[3]) + 2 * abs(a0) / min(j)
    t_stop = abs(v0) / dec + ramps
    d_stop = abs(v0) * t_stop + 0.5 * lim.acc * t_stop**2
    return t_stop + trapezoid_ticks(abs(dist) + d_stop + 1e-9, lim.vel, acc, dec) + ramps + 3


@pytest.mark.parametrize("ramp_type", [0, 1, 2])
@SETTINGS
@given(data=st.data())
def test_property_move_reaches_target_exactly_within_limits(ramp_type, data):
    lim, start, prefix, prefix_arg, prefix_ticks, new_vel, dist = data.draw(scenario(ramp_type))
    gen = prepare(lim, start, prefix, prefix_arg, prefix_ticks)
    p0, v0, a0 = gen.position, gen.velocity, gen.acceleration
    new = Limits(new_vel, lim.acc, lim.dec, lim.ramp_type, lim.jerk)
    target = p0 + dist
    gen.move_to(target, new)
    planned = gen.remaining_ticks()
    p, v, a = run(gen)
    n = len(p) - 1
    assert p[-1] == target and gen.done and v[-1] == 0.0 and a[-1] == 0.0
    assert n == planned
    assert n <= tick_bound(new, v0, a0, dist)
    assert_limits(new, p, v, a, vmax=overshoot_allowance(new, v0, a0))
    for _ in range(3):  # and it stays there
        gen.step()
        assert (gen.position, gen.velocity, gen.acceleration) == (target, 0.0, 0.0) and gen.done
    # determinism: the same commands give bit-identical samples
    again = prepare(lim, start, prefix, prefix_arg, prefix_ticks)
    again.move_to(target, new)
    p2, v2, a2 = run(again)
    assert np.array_equal(p, p2) and np.array_equal(v, v2) and np.array_equal(a, a2)


@pytest.mark.parametrize("ramp_type", [0, 1, 2])
@SETTINGS
@given(data=st.data())
def test_property_no_overshoot_from_rest(ramp_type, data):
    lim = data.draw(limits(ramp_type))
    start = data.draw(st.floats(-1e6, 1e6))
    dist = data.draw(st.one_of(st.floats(-3000.0, 3000.0), st.floats(-1.0, 1.0))) * lim.vel
    gen = ProfileGenerator(start)
    gen.move_to(start + dist, lim)
    p, v, a = run(gen)
    s = 1.0 if dist > 0 else -1.0
    assert p[-1] == start + dist
    assert np.all(s * (p - (start + dist)) <= 0.0)
    assert np.all(s * v >= 0.0) and np.all(s * np.diff(p) >= 0.0)
    assert_limits(lim, p, v, a)
    if dist == 0.0:
        assert len(p) == 1
    elif ramp_type == 0:
        assert len(p) - 1 <= math.ceil(trapezoid_ticks(abs(dist), lim.vel, lim.acc, lim.dec) + 1e-6)
    else:
        assert len(p) - 1 >= math.floor(trapezoid_ticks(abs(dist), lim.vel, lim.acc, lim.dec) - 1e-6)


@pytest.mark.parametrize("ramp_type", [0, 1, 2])
@SETTINGS
@given(data=st.data())
def test_property_retargeting_mid_move_is_continuous(ramp_type, data):
    """NOWAIT ON: POSA/POSR, new VEL, CVEL and MOTOR STOP while moving; samples stay continuous and limited."""
    lim = data.draw(limits(ramp_type))
    gen = ProfileGenerator(0.0)
    vmax = lim.vel
    samples = [np.array([[gen.position, gen.velocity, gen.acceleration]])]
    for _ in range(data.draw(st.integers(2, 6))):
        cmd = data.draw(st.sampled_from(["move", "move", "vel", "run", "stop"]))
        new = Limits(lim.vel * data.draw(st.sampled_from([1.0, 0.5, 1.5])), lim.acc, lim.dec, ramp_type, lim.jerk)
        vmax = max(vmax, new.vel, overshoot_allowance(new, gen.velocity, gen.acceleration))
        if cmd == "move":
            gen.move_to(gen.position + data.draw(st.floats(-2000.0, 2000.0)) * lim.vel, new)
        elif cmd == "vel":
            gen.move_to(gen.target if gen.target is not None else gen.position, new)
        elif cmd == "run":
            gen.run_at(data.draw(st.floats(-1.0, 1.0)) * new.vel, new)
        else:
            gen.stop(new)
        p, v, a = steps(gen, data.draw(st.integers(1, 1500)))
        samples.append(np.stack([p, v, a], axis=1))
    final = Limits(lim.vel, lim.acc, lim.dec, ramp_type, lim.jerk)
    vmax = max(vmax, overshoot_allowance(final, gen.velocity, gen.acceleration))
    target = gen.position + data.draw(st.floats(-500.0, 500.0)) * lim.vel
    gen.move_to(target, final)
    p, v, a = run(gen)
    assert p[-1] == target
    samples.append(np.stack([p, v, a], axis=1)[1:])
    s = np.concatenate(samples)
    assert_limits(final, s[:, 0], s[:, 1], s[:, 2], vmax=vmax)


@pytest.mark.parametrize("ramp_type", [0, 1, 2])
@SETTINGS
@given(data=st.data())
def test_property_run_at_reaches_and_keeps_the_velocity(ramp_type, data):
    lim, start, prefix, prefix_arg, prefix_ticks, _new_vel, _dist = data.draw(scenario(ramp_type))
    gen = prepare(lim, start, prefix, prefix_arg, prefix_ticks)
    v0, a0 = gen.velocity, gen.acceleration
    target_v = data.draw(st.floats(-1.0, 1.0)) * lim.vel
    gen.run_at(target_v, lim)
    planned = gen.remaining_ticks()
    p, v, a = run(gen)
    assert len(p) - 1 == planned and gen.mode == "velocity" and gen.done
    assert v[-1] == target_v and a[-1] == 0.0
    assert_limits(lim, p, v, a, vmax=overshoot_allowance(lim, v0, a0))
    p2, v2, _ = steps(gen, 10)
    assert np.all(v2 == target_v) and np.allclose(np.diff(p2), target_v, rtol=1e-9, atol=1e-9)
    gen.run_at(5 * lim.vel, lim)  # clamped to VEL
    run(gen)
    assert gen.velocity == lim.vel


@pytest.mark.parametrize("ramp_type", [0, 1, 2])
@SETTINGS
@given(data=st.data())
def test_property_stop_ends_at_standstill_without_reversal(ramp_type, data):
    lim = data.draw(limits(ramp_type))
    gen = ProfileGenerator(data.draw(st.floats(-1e5, 1e5)))
    gen.run_at(data.draw(st.floats(-1.0, 1.0)) * lim.vel, lim)
    steps(gen, data.draw(st.integers(0, 2000)))  # constant velocity or still speeding up
    v0, a0 = gen.velocity, gen.acceleration
    gen.stop(lim)
    planned = gen.remaining_ticks()
    p, v, a = run(gen)
    assert gen.mode == "stop" and gen.done and len(p) - 1 == planned
    assert v[-1] == 0.0 and a[-1] == 0.0
    s = 1.0 if v0 > 0 else -1.0
    assert np.all(s * v >= 0.0) and np.all(s * np.diff(p) >= 0.0)
    assert_limits(lim, p, v, a, vmax=overshoot_allowance(lim, v0, a0))
    gen.step()
    assert gen.position == p[-1] and gen.velocity == 0.0


@pytest.mark.parametrize("ramp_type", [0, 1, 2])
@pytest.mark.parametrize("how", ["shift", "assign"])
def test_origin_shift_while_moving_carries_the_plan(ramp_type, how):
    """DEFORIGIN/HOME while moving: position and target move by the same amount, the profile is unchanged."""
    lim = Limits(20.0, 0.2, 0.1, ramp_type, (0.01, 0.02, 0.005, 0.004))
    ref, gen = ProfileGenerator(), ProfileGenerator()
    for g in (ref, gen):
        g.move_to(5000.0, lim)
        steps(g, 150)
    if how == "shift":
        gen.shift(-1000.0)
    else:  # what an axis may do: assign the attributes
        gen.position -= 1000.0
        gen.target -= 1000.0
    p_ref, v_ref, _ = run(ref)
    p, v, _ = run(gen)
    assert len(p) == len(p_ref) and p[-1] == 4000.0 and gen.done and gen.target == 4000.0
    assert np.allclose(p, p_ref - 1000.0, rtol=0, atol=1e-9) and np.array_equal(v, v_ref)
    ref.hold(gen.position)
    for g in (ref, gen):
        g.run_at(5.0, lim)
        steps(g, 30)
    gen.position += 3.0  # speed mode, no target
    p_ref, _, _ = steps(ref, 100)
    p, _, _ = steps(gen, 100)
    assert np.allclose(p - p_ref, 3.0, rtol=0, atol=1e-9)
