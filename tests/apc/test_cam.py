"""The CAM reference (seed 004 §4.7, §5.2.4.5): coordinates, laws, walk, ratio, single shot, resets, limits."""

import itertools
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.apc.calculators import counts_per_second, ramp_counts, steady_counts
from motiontool.apc.cam import Cam, CamError
from motiontool.apc.camlaws import LAW_NAMES, law_value

from .helpers import VirtualMaster, enabled_drive

IN = [109227, 218454, 54613]
OUT1 = [109227, 436908, 54613]
CODES = [2, 0, 3]


def test_worked_example_coordinates():
    """L1283-1331: "(100/60) x 65536 = 109227 cps", "(200/60) x 65536 = 218454", accel "(218454 x 1)/2 = 109227",
    decel "(218454 x 0.5)/2 = 54613", steady "218454 x 2 = 436908"; Table 4-10 absolute 109227, 546135, 600748.
    (200/60 x 65536 is 218453.3: the manual's 218454 is twice the rounded 109227, decision A32.)"""
    master = counts_per_second(100, 65536)
    assert master == 109227 and counts_per_second(200, 65536) == 218453
    slave = 2 * master
    assert [steady_counts(master, 1), steady_counts(master, 2), ramp_counts(slave, 1)] == [109227, 218454, 109227]
    assert [ramp_counts(slave, 1), steady_counts(slave, 2), ramp_counts(slave, 0.5)] == OUT1
    assert [sum(OUT1[:k + 1]) for k in range(3)] == [109227, 546135, 600748]


def cam(in_array=IN, out1=OUT1, codes=CODES, **settings) -> Cam:
    c = Cam()
    c.initialise(in_array, out1, settings.pop("out2", None), codes)
    c.mode = -1 if codes is not None else settings.pop("mode", 0)
    c.start_index, c.size = settings.pop("start", 0), settings.pop("size", len(in_array))
    for key, value in settings.items():
        setattr(c, key, value)
    c.engage()
    return c


def test_one_cycle_advances_exactly_the_sum_of_out():
    """L1240-1259 "the feedback absolute position when the CAM has run one cycle, is the sum of all of the
    feedback co-ordinates": 600748 per cycle, whatever the master's steps."""
    c = cam()
    total, master = 0, 0
    steps = [109, 110, 1, 5000, 37, 0, 12345]
    k = 0
    while master < 5 * sum(IN):
        step = min(steps[k % len(steps)], 5 * sum(IN) - master)
        total += c.step(step)
        master += step
        k += 1
        if master % sum(IN) == 0:
            assert total == 600748 * (master // sum(IN))
    assert total == 5 * 600748


def test_slopes_join_at_twice_the_master_speed_in_the_worked_example():
    """L1337-1340 Square1, Linear, Square2 for the §4.7.2 profile: the slave runs at 200 rpm against 100 rpm, so the
    slope is 2 at every join (Square1 ends at 2Y/X, Linear is Y/X, Square2 starts at 2Y/X)."""
    h = 100
    end0 = (law_value(2, IN[0], IN[0], OUT1[0]) - law_value(2, IN[0] - h, IN[0], OUT1[0])) / h
    mid1 = (law_value(0, IN[1], IN[1], OUT1[1]) - law_value(0, IN[1] - h, IN[1], OUT1[1])) / h
    start2 = law_value(3, h, IN[2], OUT1[2]) / h
    for slope in (end0, mid1, start2):
        assert slope == pytest.approx(2, abs=0.01)


@pytest.mark.parametrize("code, start, end", [
    (0, 1.0, 1.0),      # L1406 "Y (velocity) = X (velocity) * ((Y co-ordinate)/(X co-ordinate))"
    (1, 0.0, 0.0),      # L1410-1416 smooth point to point (sinusoidal speed from and to rest)
    (2, 0.0, 2.0),      # L1440 Square1 final "((2*Y co-ordinate)/(X co-ordinate))"
    (3, 2.0, 0.0),      # L1457 Square2
    (4, 0.0, 2.0),      # L1474 Cosine1
    (5, 2.0, 0.0),      # L1494 Cosine2
])
def test_end_of_segment_speed_ratios_per_law(code, start, end):
    """The slave/master speed ratio at both ends of a segment, in units of Y/X (§4.7.3)."""
    big_x, y, h = 1_000_000, 1_000_000, 200
    first = law_value(code, h, big_x, y) / h
    last = (y - law_value(code, big_x - h, big_x, y)) / h
    assert first == pytest.approx(start, abs=0.005)
    assert last == pytest.approx(end, abs=0.005)
    assert law_value(code, big_x, big_x, y) == y and law_value(code, 0, big_x, y) == 0


def test_law_names_are_the_interpolation_codes():
    """L3557-3563 "0 = Linear 1 = Cosine 2 = Square1 3 = Square2 4 = Cosine1 5 = Cosine2"."""
    assert LAW_NAMES == ("Linear", "Cosine", "Square1", "Square2", "Cosine1", "Cosine2")


def test_cosine_peak_is_pi_y_over_2x():
    """L1422 prints "Y/(2*X)"; the half-cosine peaks at π·Y/(2X) (spec §9.2, decision A30)."""
    big_x = y = 1_000_000
    mid = big_x // 2
    slope = (law_value(1, mid + 1000, big_x, y) - law_value(1, mid - 1000, big_x, y)) / 2000
    assert slope == pytest.approx(math.pi / 2, abs=0.001)


def test_output_ratio_remainder_is_carried():
    """L1546-1552 "using the ratio to apply the denominator means that any remainder is automatically compensated
    for": a 7:3 ratio over many cycles gives exactly 7/3 of ΣOut, floor."""
    c = cam()
    c.ratio.numerator, c.ratio.denominator = 7, 3
    total = sum(c.step(997) for _ in range(2000))
    master = 997 * 2000
    cycles, rest = divmod(master, sum(IN))
    c2 = cam()
    plain = sum(c2.step(997) for _ in range(2000))
    assert total == plain * 7 // 3
    assert cycles == 5 and rest > 0


def test_out2_adds_a_linear_offset():
    """L1340-1376: OutArray2 54613 / 109227 / 27307 adds a steady 50 rpm offset, linearly interpolated."""
    c = cam(out2=[54613, 109227, 27307])
    assert sum(c.step(1000) for _ in range(sum(IN) // 1000)) + c.step(sum(IN) % 1000) == 600748 + 191147


def test_master_running_backwards_retraces_the_cam():
    """L1259 "The CAM is a Monotonic reference i.e. increments when the reference moves forward, and decrements when
    the reference moves backward"."""
    c = cam()
    forward = [c.step(3001) for _ in range(150)]
    backward = [c.step(-3001) for _ in range(150)]
    assert sum(forward) + sum(backward) == 0
    assert (c.segment, c.position) == (0, 0)
    assert sum(c.step(-1000) for _ in range(5)) < 0 and c.segment == 2     # wraps back into the last segment


def test_delta_segment_limit_breach():
    """L3524-3546 "if the reference were to change by 256 counts the APC would stop the axis due to the CAM delta
    segment limit breach" (1-count segments, limit 256)."""
    c = cam([1] * 600, [1] * 600, None, mode=0)
    c.step(255)
    with pytest.raises(CamError) as err:
        c.step(256)
    assert err.value.code == 2


def test_start_index_and_size_apply_at_the_wrap():
    """L1520-1526 "The CAM Start Index, and the CAM size, can be changed whilst the CAM reference is running, but
    will not take effect until the current cycle has finished"."""
    c = cam([100] * 6, [10, 20, 30, 40, 50, 60], None, mode=0, size=3)
    c.step(150)
    c.start_index, c.size = 3, 2
    assert c.segment == 1
    out = c.step(150)                         # to the end of the old window (150 more → wrap into the new one)
    assert c.wrapped == 1 and (c.segment, c.position) == (3, 0)
    assert out == (20 - 10) + 30
    assert c.step(200) == 40 + 50 and c.wrapped == 1 and c.segment == 3


def test_single_shot_absolute_reset_room_plus_9000_minus_1000():
    """L3664-3668 "a CAM of 1 segment, containing 10000 counts, started in single shot at 1000 counts, will be able
    to move forward by 9000 counts, or reverse by 1000 before the CAM will stop"."""
    forward = cam([10000], [10000], None, mode=0, single_shot=True, absolute_reset=True, reset_position=1000)
    assert forward.step(20000) == 9000 and forward.complete == 1
    assert forward.step(5) == 0
    backward = cam([10000], [10000], None, mode=0, single_shot=True, absolute_reset=True, reset_position=1000)
    assert backward.step(-20000) == -1000 and backward.complete == 1


def test_single_shot_zero_reset_runs_one_cycle_either_way():
    """L3661-3664 "run the CAM in either the forward or reverse direction until the CAM start index is next
    reached"."""
    c = cam(single_shot=True)
    assert sum(c.step(7000) for _ in range(100)) == 600748 and c.complete == 1
    c = cam(single_shot=True)
    assert sum(c.step(-7000) for _ in range(100)) == -600748 and c.complete == 1


def test_absolute_reset_outside_the_window_is_error_4():
    """L1585-1587, Table 4-11: "4 CAM absolute reset failure"."""
    with pytest.raises(CamError) as err:
        cam(absolute_reset=True, reset_index=5)
    assert err.value.code == 4


# --- through the drive -------------------------------------------------------------------------------------------
def cam_drive(**kw):
    d = enabled_drive()
    vm = VirtualMaster(d, kw.pop("per_sample", 0))
    d.APCCamInitialise2(IN, OUT1, CODES)
    d.APCSetCAMInterpolationMode(-1)
    d.APCSetCAMStartIndex(0)
    d.APCSetCAMSize(3)
    return d, vm


def test_size_zero_selects_stop_and_trips():
    """L3512-3516 "If the CAM size is set to 0, then the Stop reference will be automatically selected"; Table
    4-11 "3 CAM size has been specified as 0"; #81.38 = 1 trips Tr81 (L2309-2312)."""
    d, _ = cam_drive()
    d.APCSetCAMSize(0)
    d.APCSelectReference(3)
    d.tick()
    assert d.read(100) == 0 and d.params["90.49"] == 3 and d.trip == "Tr81"


def test_over_limit_master_jump_selects_stop_and_trips():
    """L3541-3546 "If this limit is exceeded, then the reference will automatically be switched to Stop and trip
    Tr81"."""
    d, vm = cam_drive()
    d.APCSetCAMDeltaSegLimit(2)
    d.APCSelectReference(3)
    d.tick()
    vm.per_sample = 400_000               # more than a whole cycle in one sample
    d.tick()
    assert d.read(100) == 0 and d.params["90.49"] == 2 and d.trip == "Tr81"


def test_cam_on_the_drive_follows_the_virtual_master_exactly():
    """L1240-1259 with the §8.4 virtual master at 100 rpm: after the master has moved whole cycles the CAM output
    [117] has moved exactly 600748 per cycle."""
    d, vm = cam_drive(per_sample=1000)
    start = d.read(117)
    d.APCSelectReference(3)
    cycle = sum(IN)
    for _ in range(3 * cycle // 1000 + 1):
        d.tick()
        master = d.read(28)
        if master % cycle == 0 and master:
            assert d.read(117) - start == 600748 * (master // cycle)
    assert d.read(28) >= 3 * cycle


segments = st.lists(st.tuples(st.integers(1, 5000), st.integers(-20000, 20000), st.integers(0, 5)),
                    min_size=1, max_size=6)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(segments, st.lists(st.integers(-3000, 3000), min_size=1, max_size=200))
def test_cam_output_depends_only_on_the_master_position(table, steps):
    """L1259 the CAM is a monotonic function of the master, forward and backward; whatever path the master takes
    the slave is at F(M) = whole cycles · ΣY + the law inside the segment (ratio 1:1)."""
    in_array = [x for x, _, _ in table]
    out1 = [y for _, y, _ in table]
    codes = [c for _, _, c in table]
    c = cam(in_array, out1, codes, seg_limit=65535)
    length, total_y = sum(in_array), sum(out1)

    def f(master: int) -> int:
        cycles, rest = divmod(master, length)
        value = cycles * total_y
        for x, y, code in table:
            if rest >= x:
                value, rest = value + y, rest - x
            else:
                return value + law_value(code, rest, x, y)
        return value

    master = slave = 0
    for step in steps:
        slave += c.step(step)
        master += step
        assert slave == f(master)


def test_delta_seg_limit_and_out_ratio_numerator_clamp():
    """L3525 "DeltaLimit%: Unsigned 16bit. Negative values will be clamped to zero, values over 65535 will be clamped
    to 65535"; L3568 "Ratio%: Unsigned 31bit value to set as numerator. Negative values will be clamped at zero."
    Both then answer 1, "Operation successful" (L3528, L3571; decision A6)."""
    d = enabled_drive()
    assert d.APCSetCAMDeltaSegLimit(-7) == 1 and d.read(76) == 0
    assert d.APCSetCAMDeltaSegLimit(70000) == 1 and d.read(76) == 65535
    assert d.APCSetCAMDeltaSegLimit(300) == 1 and d.read(76) == 300
    assert d.APCSetCAMOutRatioNumerator(-1000) == 1 and d.read(80) == 0
    assert d.APCSetCAMOutRatioNumerator(2500) == 1 and d.read(80) == 2500


def window_drive(select_in: int, window_in: int, task: str = "pos0"):
    """Six 1000-count segments, window 0..2 set up front; a virtual master of 100 counts per sample; in POS task
    `task` the CAM is selected in sample `select_in` and the window 3..5 written in sample `window_in`; the CAM's
    segments [82] in the order it runs them."""
    d = enabled_drive()
    vm = VirtualMaster(d, 100)
    d.APCCamInitialise1([1000] * 6, [10, 20, 30, 40, 50, 60])
    d.APCSetCAMStartIndex(0)
    d.APCSetCAMSize(3)
    segments = []

    def pos_task():
        if d.samples == window_in:
            d.APCSetCAMStartIndex(3)
            d.APCSetCAMSize(3)
        if d.samples == select_in:
            d.APCSelectReference(3)
    d.pos0 = lambda: (vm.pos0(), pos_task() if task == "pos0" else None)
    d.pos1 = lambda: (pos_task() if task == "pos1" else None, segments.append(d.read(82)))
    d.run_ms(select_in + 1)
    segments.clear()                                      # from the first sample the CAM runs
    d.run_ms(100)
    return d, [k for k, _ in itertools.groupby(segments)]


def test_start_index_and_size_set_along_with_selecting_the_cam_wait_for_its_wrap():
    """L3505-3508 (start index) and L3517-3520 (size): "If the start index and size are set along with selecting the
    CAM reference, then the new CAM size and start index will not take effect until the CAM reaches the end and
    wraps over. To prevent this effect the user should set the CAM size and start index, then in the next Pos task
    sample select the CAM Reference." POS0 and POS1 alike; the CAM starts with the window it had before."""
    for task in ("pos0", "pos1"):
        d, segments = window_drive(select_in=10, window_in=10, task=task)
        assert segments[:5] == [0, 1, 2, 3, 4] and d.read(74) == 3 and d.read(75) == 3   # the old window first


def test_start_index_and_size_set_a_sample_before_selecting_take_effect_at_once():
    """L3507-3508 "the user should set the CAM size and start index, then in the next Pos task sample select the CAM
    Reference": the CAM starts at segment 3; the same from outside the POS tasks."""
    d, segments = window_drive(select_in=10, window_in=9)
    assert segments[:4] == [3, 4, 5, 3]
    d, _ = cam_drive()
    d.APCSetCAMStartIndex(1)
    d.APCSetCAMSize(2)
    d.APCSelectReference(3)
    d.tick()
    assert d.read(82) == 1 and d.read(100) == 3


def test_a_cam_selected_with_its_first_size_in_the_same_pass_has_size_0():
    """L3517-3520 with L3512-3516: a size written in the POS task that selects the CAM acts from the wrap on, so a
    CAM whose size was 0 before starts with size 0: "the Stop reference will be automatically selected", 90.49 = 3,
    and the message says why."""
    d = enabled_drive()
    d.APCCamInitialise1([1000] * 3, [10, 20, 30])
    errors = []
    d.listeners.append(lambda kind, details: errors.append(details.get("text", "")) if kind == "error" else None)

    def pos0():
        d.APCSetCAMSize(3)
        d.APCSelectReference(3)
    d.pos0 = pos0
    d.tick()
    assert d.read(100) == 0 and d.params["90.49"] == 3 and "set them a sample before" in errors[0]
