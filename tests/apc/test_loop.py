"""Position loop, output channel, plant and offsets (seed 004 §4.9, §4.11, §4.2.3.2, §5.2.5.2, §5.2.6)."""

import pytest

from motiontool.apc import ApcDrive, PlantConfig
from motiontool.apc.units import kp_speed, rpm_to_speed, speed_to_rpm_x10

from .helpers import VirtualMaster, enabled_drive


def cruising(ff_gain=1000, kp=2500, rpm=600, plant=None):
    d = ApcDrive(plant)
    d.APCSetupOutputChannel(2, 0, 0)
    d.APCEnableOutputChannel()
    d.APCSetRunMode(2)
    d.APCSetSpeedFFwdGain(ff_gain)
    d.APCSetPGain(kp)
    d.APCSetSpeedSetPoint(rpm_to_speed(rpm))
    d.APCSelectReference(2)
    d.run_ms(1500)
    return d


def test_following_error_without_feed_forward_is_speed_over_kv():
    """L1855-1870 "With no proportional gain, an increasing following error will occur"; with P only the error
    settles where Kp·error gives the speed: error ≈ v/Kv (Kp in 0.01 (rad/s)/rad, L744)."""
    d = cruising(ff_gain=0, kp=2500, rpm=200)             # below the 300 rpm P clamp
    v = rpm_to_speed(200)
    expected = v * 400000 / (2500 << 16)          # counts: the error whose P output is the speed
    assert d.read(130) == pytest.approx(expected, rel=0.01)
    assert d.read(135) == pytest.approx(v, rel=0.001)


def test_feed_forward_leaves_only_the_plant_lag_error():
    """L1857-1866 the speed feed-forward path gives the main speed reference; the P path trims: at constant speed
    with FF 1000 the following error is a few counts (the output channel's latency and the speed loop)."""
    d = cruising(ff_gain=1000)
    assert abs(d.read(130)) <= 3
    assert abs(d.read(135) - rpm_to_speed(600)) <= kp_speed(2500, 3, 16)


def test_without_feed_forward_the_p_clamp_limits_the_speed():
    """L1871-1873 "It is important to ensure the clamp is not set too low as it will restrict the response": with
    FF 0 and the 300 rpm P clamp the axis cannot follow 600 rpm and the error keeps growing."""
    d = cruising(ff_gain=0, rpm=600)
    first = d.read(130)
    d.run_ms(500)
    assert d.read(135) == rpm_to_speed(300) and d.read(130) > first


def test_p_clamp_and_output_clamp_saturate_the_output():
    """L1871-1873 the P output is clamped ([132]); L4201-4252 the output ratio applies before the output clamp [140]."""
    d = enabled_drive()
    d.APCDisableProfile()
    d.APCSetPGainSpeedClamp(rpm_to_speed(100))
    d.APCSetOutputSpeedClamp(rpm_to_speed(150))
    d.APCSetPositionSetPoint(10_000_000)
    d.APCSelectReference(1)
    d.tick()
    assert d.read(135) == rpm_to_speed(150)             # FF of the 10^7-count step + P, clamped
    d.APCSetSpeedFFwdGain(0)
    d.tick()
    assert d.read(135) == rpm_to_speed(100)             # P alone, at its clamp
    d.APCSetOutputRatioNumerator(500)
    d.tick()
    assert d.read(135) == rpm_to_speed(100) // 2        # output ratio before the output clamp


def test_output_channel_latency_is_one_pos_period_plus_250us():
    """L2112-2120 "the data written during the n-th POS task will be written to the multi-port RAM at the very start
    of the n+1th POS task, and the Unidrive SP will pass this to the associated parameter 250µs later"."""
    d = ApcDrive(PlantConfig(speed_tau_ms=1e-9), pos_rate=4)       # 2 ms; an instant speed loop
    d.APCSetupOutputChannel(2, 0, 0)
    d.APCEnableOutputChannel()
    d.APCSetRunMode(2)
    d.run_ms(10)
    d.APCDisableProfile()
    d.APCSetPGain(0)
    d.APCEnableExternalRefSpeed()
    d.APCSetExternalRefSpeed(rpm_to_speed(600))
    d.tick()                                    # sample n: [135] = 600 rpm
    assert d.read(135) == rpm_to_speed(600) and d.params["1.21"] == 6000
    before = d.plant.position
    d.tick()                                    # the drive still runs the old value through sample n+1
    assert d.plant.position == before
    d.tick()                                    # from 250 µs into sample n+1: 1750 µs of 600 rpm
    assert d.plant.position - before == pytest.approx(rpm_to_speed(600) * 7, rel=1e-6)


def test_inverted_output_channel_modes():
    """L2136-2145 modes 10-14 invert the speed sent to the drive; mode 10 is inverted mode 0 (spec §9.6)."""
    d = cruising()
    assert d.params["1.21"] > 0
    for mode, key in ((12, "1.21"), (10, "3.22")):
        d.APCSetupOutputChannel(mode, 0, 0)
        d.tick()
        assert d.params[key] == -speed_to_rpm_x10(d.read(135))
    assert d.APCSetupOutputChannel(1, 0, 0) == -5          # "1: Not allocated"


def test_over_range_output_trips_tr44_with_81_17():
    """L2147-2151 "if the output from the APC exceeds parameter 1.06 and x.17 or 81.17 is set to 1, the
    SM-Applications will trip on Tr44"."""
    d = enabled_drive()
    d.params["81.17"] = 1
    d.params["1.06"] = 500
    d.APCSetSpeedSetPoint(rpm_to_speed(1000))
    d.APCSelectReference(2)
    d.run_ms(500)
    assert d.trip == "Tr44" and d.params["1.11"] == 0


def test_user_output_channel_value():
    """L4259 mode 4: "Data provided by user at the end of the motion engine period is written to Menu%.Parameter%
    at the start of the next motion engine period": after the sample that latched it the parameter still holds
    the old value; the next sample writes it before its POS0."""
    d = enabled_drive()
    d.APCSetupOutputChannel(4, 18, 21)
    d.APCWriteOutputChannel(1234)
    d.tick()
    assert d.params["18.21"] == 0
    seen = []
    d.pos0 = lambda: seen.append(d.params["18.21"])
    d.tick()
    assert seen == [1234] and d.params["18.21"] == 1234


def test_parameter_output_channel_writes_at_the_start_of_the_next_sample():
    """L2109 "the data written during the n-th POS task will be written to the multi-port RAM at the very start of
    the n+1th POS task": mode 3 ([135] in rpm×10 to Menu%.Parameter%) and its inverse 13 write in the next
    sample, and what POS0, POS1 and the world between samples read is the output of the sample before."""
    for mode, sign in ((3, 1), (13, -1)):
        d = enabled_drive()
        d.APCSetupOutputChannel(mode, 18, 22)
        d.APCSetSpeedSetPoint(rpm_to_speed(600))
        d.APCSelectReference(2)
        outputs, pos0, pos1, between = [], [], [], []
        d.pos0 = lambda d=d, seen=pos0: seen.append(d.params["18.22"])

        def task1(d=d, outputs=outputs, seen=pos1, sign=sign):
            seen.append(d.params["18.22"])
            outputs.append(sign * speed_to_rpm_x10(d.read(135)))
        d.pos1 = task1
        for _ in range(300):
            d.tick()
            between.append(d.params["18.22"])
        assert pos0 == pos1 == between and pos0[0] == 0 and pos0[1:] == outputs[:-1]
        assert len(set(outputs)) > 100 and between[-1] == outputs[-2]


def test_a_held_speed_reference_reaches_the_drive_as_fast_as_the_shortcut():
    """L2109: whichever mode, the channel's data reach the drive at the start of the next sample; mode 3 writing
    #1.21 moves the motor as mode 2 does (the drive follows #1.21; rpm×10 loses a little resolution)."""
    positions = []
    for mode, menu, par in ((2, 0, 0), (3, 1, 21)):
        d = enabled_drive()
        d.APCSetupOutputChannel(mode, menu, par)
        d.APCSetSpeedSetPoint(rpm_to_speed(600))
        d.APCSelectReference(2)
        d.run_ms(200)
        positions.append(d.read(48))
    assert abs(positions[0] - positions[1]) < 0.001 * positions[0]


def test_position_offset_shifts_a_locked_axis_by_exactly_x():
    """L843-852, L3990-4000 the position offset phase-advances the feedback axis through the offset profile
    generator: on a locked digital lock a +X offset moves the slave by exactly X."""
    d = enabled_drive()
    VirtualMaster(d, 500)
    d.APCSelectReference(4)
    d.run_ms(200)
    assert d.read(61) == 1
    before = d.read(144) - d.read(28)
    d.APCSetPositionOffset(12345)
    d.APCSelectOffset(1)
    d.run_ms(500)
    assert d.read(144) - d.read(28) == before + 12345 and d.read(157) == 12345


def test_offsets_switched_off_are_profiled_back_by_the_main_generator():
    """L848-852 "changed to offsets disabled, the output of the Offset Profile Generator is set to 0, and therefore
    the Main Profile Generator accel and decel rate will be used to profile back"."""
    d = enabled_drive()
    d.APCSetPositionSetPoint(0)
    d.APCSelectReference(1)
    d.APCSetPositionOffset(50_000)
    d.APCSelectOffset(1)
    d.run_ms(400)
    assert d.read(144) == 50_000
    d.APCSelectOffset(0)
    d.tick()
    assert d.read(157) == 0 and abs(d.read(144) - 50_000) < 2000        # no step
    d.run_ms(500)
    assert d.read(144) == 0


def test_stop_forces_the_offsets_off():
    """L3930-3944 "When the Stop reference is selected, [100] = 0, the offset selector [102] will be set to 0"."""
    d = enabled_drive()
    d.APCSelectReference(2)
    d.APCSetSpeedOffset(rpm_to_speed(60))
    d.APCSelectOffset(2)
    d.run_ms(100)
    d.APCSelectReference(0)
    d.tick()
    assert d.read(102) == 0


def test_external_references():
    """L1990-2056 "the user can generate their own position reference, within POS0 user code and write directly into
    the position loop external speed and position references"."""
    d = enabled_drive()
    d.APCEnableExternalRefPosition()
    d.APCSetExternalRefPosition(1000)
    d.tick()
    assert d.read(142) == 1000 and d.read(130) == 1000 - d.read(48)


@pytest.mark.parametrize(("mode", "key", "sign"), [(2, "1.21", 1), (12, "1.21", -1), (0, "3.22", 1)])
def test_speed_reference_parameter_shows_the_value_clamped_at_1_06(mode, key, sign):
    """L2148 "Drive parameter 1.06 clamps the speed reference sent to the drive from the output channel": with
    #1.06 = 500 rpm and 1100 rpm asked, #1.21 / #3.22 hold what the drive receives, 500 rpm (rpm×10, A46)."""
    d = ApcDrive()
    d.params["1.06"] = 500
    d.APCSetupOutputChannel(mode, 0, 0)
    d.APCEnableOutputChannel()
    d.APCSetRunMode(2)
    d.APCSetSpeedFFwdGain(1000)
    d.APCSetSpeedSetPoint(rpm_to_speed(1100))
    d.APCSelectReference(2)
    d.run_ms(300)
    assert abs(d.read(135)) > rpm_to_speed(1000)          # the APC still asks for more than #1.06
    assert d.params[key] == sign * 5000                    # mode 12 inverts (L2140)
