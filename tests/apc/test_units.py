"""APC units and calculators (seed 004 §3.11.2, §4.12, §5.3, §8.4): each pinned to the manual's numbers."""

import pytest
from hypothesis import given
from hypothesis import strategies as st

from motiontool.apc import intmath
from motiontool.apc.units import (
    EmbeddedConverter,
    UserDefinedConverter,
    UserUnits,
    accel_from_ramp,
    counts_per_rev,
    jerk_from_time,
    kp_speed,
    rpm_to_speed,
    speed_to_rpm,
)


def test_manual_defaults_convert_to_their_stated_values():
    """L3876-3890 "48318382" max speed = 2700 rpm; L4242-4252 output clamp 53687091 = 3000 rpm; L4071-4084 P clamp
    5368709 = 300 rpm; L3747-3758 locking speed 17895 ≈ 1 rpm; L712 "APCSpeed%=MULDIV(SpeedRPM%, 1073741824, 60000)"."""
    assert rpm_to_speed(2700) == 48318382
    assert rpm_to_speed(3000) == 53687091
    assert rpm_to_speed(300) == 5368709
    assert rpm_to_speed(1) == 17895
    assert speed_to_rpm(48318382) == pytest.approx(2700, abs=1e-5)


def test_default_acceleration_is_1_25_rpm_per_250us():
    """L3839-3862 default accel 22369; L728 "APCAccel%=MULDIV(APCSpeed%, 250, AccelTimeMicroSec%)":
    1000 rpm in 0.2 s (5000 rpm/s = 1.25 rpm per 250 µs) gives 22369."""
    assert accel_from_ramp(rpm_to_speed(1000), 200_000) == 22369
    assert speed_to_rpm(22369) == pytest.approx(1.25, abs=1e-4)


def test_pos_rate_codes():
    """L655-673 #81.12: 1 = 0.25 ms, 2 = 0.5, 3 = 1, 4 = 2, 5 = 4, 6 = 8 ms; [13] reports 0..5 (L7711)."""
    from motiontool.apc import ApcDrive
    from motiontool.apc.units import pos_rate_code
    assert [pos_rate_code(us) for us in (250, 500, 1000, 2000, 4000, 8000)] == [1, 2, 3, 4, 5, 6]
    with pytest.raises(ValueError, match="250, 500"):
        pos_rate_code(3000)
    assert ApcDrive(pos_rate=5).read(13) == 4 and ApcDrive(pos_rate=5).period_us == 4000


def test_jerk_from_jerk_time():
    """L740 "APCJerk%=MULDIV(APCAccel%, 250, JerkTimeMicroSec%)"."""
    assert jerk_from_time(22369, 250_000) == 22


def test_turns_bits_window():
    """L2812-2818: 10 turns bits give 1024 turns and 4194304 counts per revolution."""
    assert counts_per_rev(10) == 4194304
    assert counts_per_rev(16) == 65536
    from motiontool.apc.units import counts_to_window
    word = (3 << 32) | (0x1234 << 16) | 0xABCD          # 3 turns, coarse 0x1234, fine 0xABCD
    assert counts_to_window(word, 16) == (3 << 16) | 0x1234
    assert counts_to_window(word, 10) == (3 << 22) | (0x1234 << 6) | (0xABCD >> 10)


def test_p_gain_in_apc_units():
    """L744 Kp in 0.01 (rad/s)/rad: 2500 and one revolution of error ask for 25 rev/s (derived, spec §1.15)."""
    assert kp_speed(2500, 65536, 16) == 26843545          # 25·2^32/4000 = 26843545.6, truncated
    assert kp_speed(2500, -65536, 16) == -26843545
    assert kp_speed(2500, 1, 16) == 409                   # "1 count of error gives about 410 APC speed units"


def test_user_units_remainder_identity():
    """L2236-2247 "UU = Round(APC Pos * (UPR N/(2^(32-[14]) * UPR D)))", "Rem = (APC Pos * UPR N) - (UU *
    (2^(32-[14]) * UPR D))"; the nip roll example N 314, D 1 (L2165-2172)."""
    u = UserUnits(314, 1, 16)
    assert u.conv_n == 65536 and u.conv_d == 314
    uu, rem = u.to_user(100000)
    assert uu == round(100000 * 314 / 65536)
    assert uu * 65536 + rem == 100000 * 314
    assert u.to_counts(uu, rem) == (100000, 0)


@given(st.integers(-2**31, 2**31 - 1), st.integers(1, 10**6), st.integers(1, 2**15 - 1))
def test_user_unit_round_trip_with_remainder_is_exact(counts, n, d):
    """L2211-2230: a position set with its remainder loses nothing (APC·N = UU·[96] + Rem)."""
    u = UserUnits(n, d, 16)
    if UserUnits.check(n, d, 16):
        return
    uu, rem = u.to_user(counts)
    assert counts * n == uu * u.conv_n + rem
    assert u.to_counts(uu, rem) == (counts, 0)


def test_denominator_bound_is_the_command_pages():
    """L4326 "Denominator% 1 to 2^([14]-1) -1" (spec §9.14: the quick reference's 2^31-1 is not used)."""
    assert UserUnits.check(1, 4095, 13) is None
    assert UserUnits.check(1, 4096, 13)
    assert UserUnits.check(2**20, 1, 16)         # N/D above 2^(32-TB)


def test_embedded_converter_rounding_example():
    """L4404-4412: UPR 5000, 9 turns bits: user 1000 → 1677722 (1677721.6 rounded) → back to 1000."""
    c = EmbeddedConverter()
    c.numerator, c.denominator = 5000, 1
    assert c.user_to_apc_position(1000, 9) == (1677722, 1)
    assert c.apc_to_user_position(1677722, 9) == (1000, 1)
    c.numerator = 500_000_000          # Table 5-1 row: 17 counts, back to 1013
    assert c.user_to_apc_position(1000, 9) == (17, 1)
    assert c.apc_to_user_position(17, 9) == (1013, 1)


def test_user_defined_converter_inch_mm():
    """L4474-4495 "numerator 254 and denominator 10 … Converting forwards will scale by 25.4"."""
    c = UserDefinedConverter()
    c.numerator, c.denominator = 254, 10
    assert c.forwards(10) == 254
    assert c.backwards(254) == 10


def test_word_blocks_match_the_manuals_examples():
    """L4502-4532: UnsignedTopWord(0x98768765) = 0x9876, SignedTopWord → 0xFFFF9876, UnsignedBottomWord → 0x8765,
    SignedBottomWord → 0xFFFF8765, PutTopWord(0x68, 0x57) = 0x680057, PutBottomWord(0xFFFFFFF7, 0x57043291) =
    0x5704FFF7."""
    x = intmath.wrap32(0x98768765)
    assert intmath.UnsignedTopWord(x) == 0x9876
    assert intmath.SignedTopWord(x) == intmath.wrap32(0xFFFF9876)
    assert intmath.UnsignedBottomWord(x) == 0x8765
    assert intmath.SignedBottomWord(x) == intmath.wrap32(0xFFFF8765)
    assert intmath.UnsignedTopWord(0x01234567) == 0x0123
    assert intmath.PutTopWord(0x68, 0x57) == 0x680057
    assert intmath.PutBottomWord(intmath.wrap32(0xFFFFFFF7), 0x57043291) == 0x5704FFF7


def test_muldivrm_virtual_master_averages_exactly_109_2267_counts_per_ms():
    """L6899-6905 "100 * 65536 / 60000 = 109.2266667"; L6919-6950: with MULDIVRM and the remainder accumulated
    the virtual master runs at exactly 100 rpm: after k samples the counter is ⌊k·6553600/60000⌋, so 75 ms give
    8192 counts (109.2267 counts/ms) with no drift over a million samples."""
    assert intmath.MULDIVRM(100, 65536, 60000) == (109, 13600)
    assert intmath.MULDIV(100, 65536, 60000) == 109
    counter = remainder_count = 0
    for k in range(1, 1_000_001):
        per_sample, remainder = intmath.MULDIVRM(100, 65536, 60000)
        remainder_count += remainder
        if remainder_count >= 60000:
            remainder_count -= 60000
            per_sample += 1
        elif remainder_count <= -60000:
            remainder_count += 60000
            per_sample -= 1
        counter += per_sample
        if k == 75:
            assert counter == 8192 and round(counter / k, 4) == 109.2267
    assert counter == 1_000_000 * 6553600 // 60000


def test_muldivrm_truncates_toward_zero():
    """L6940-6946 handles remainders down to -60000: the quotient truncates toward zero (decision A3)."""
    assert intmath.MULDIVRM(-100, 65536, 60000) == (-109, -13600)


def test_ratio_24_over_10_drifts_zero_counts_over_a_million_samples():
    """L1825-1840 "any remainder from the numerator denominator calculation is retained": N 24 / D 10."""
    ratio = intmath.Ratio(24, 10)
    total_in = total_out = 0
    for k in range(1_000_000):
        step = 7 + (k % 5)
        total_in += step
        total_out += ratio.step(step)
    assert total_out == total_in * 24 // 10
