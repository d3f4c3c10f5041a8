"""Freeze and marker capture between samples, freeze-triggered CAM and digital lock, re-arm, marker reset
(seed 004 §4.3.8, §4.7.9-4.7.10, §4.8.6, §5.2.2)."""

import pytest

from .helpers import VirtualMaster, enabled_drive


def master_drive(per_sample=1000):
    d = enabled_drive()
    vm = VirtualMaster(d, per_sample)
    d.APCEnableReferenceFreeze()
    d.APCResetRefSourceFreezeFlag()
    return d, vm


def test_freeze_between_samples_captures_the_interpolated_position():
    """L1026-1054 "The actual position is captured within a micro second on the drive, and is passed to the
    SM-Applications module on the following sample period": an event 0.3 ms after a sample latches the source [21]
    and integrated [29] positions of that instant (decision A13: interpolated between the samples)."""
    d, _ = master_drive(1000)
    d.run_ms(10)
    at_10 = (d.read(20), d.read(28))
    d.schedule("reference", "freeze", d.time_ns / 1000 + 300)
    d.tick()
    assert d.read(22) == 1
    assert (d.read(21), d.read(29)) == (at_10[0] + 300, at_10[1] + 300)


def test_freeze_flag_latches_until_reset():
    """L1080-1084 "the freeze flags will be set, and will remain latched on, so that further Freeze signals will not
    be detected until the user resets them"."""
    d, _ = master_drive(1000)
    d.schedule("reference", "freeze", 2500)
    d.run_ms(5)
    first = d.read(21)
    d.schedule("reference", "freeze", 7500)
    d.run_ms(5)
    assert d.read(21) == first
    d.APCResetRefSourceFreezeFlag()
    d.schedule("reference", "freeze", d.time_ns / 1000 + 500)
    d.tick()
    assert d.read(21) == first + (d.time_ns / 1000 - 500 - 2500)


def test_freeze_needs_its_enable():
    """L2940-3040: APCEnableReferenceFreeze (90.47) must be active for a capture."""
    d, _ = master_drive()
    d.APCDisableReferenceFreeze()
    d.schedule("reference", "freeze", d.time_ns / 1000 + 100)
    d.tick()
    assert d.read(22) == 0 and d.params["90.47"] == 0


def test_cam_selected_by_freeze_loses_no_position():
    """L1144-1151 "When a freeze signal is used to trigger the CAM or Digital Lock reference, there is no lost
    position, from when the freeze was triggered to when the reference is engaged": a 1:1 linear CAM started by a
    freeze 0.4 ms after a sample has moved exactly the master's travel since the freeze."""
    d, _ = master_drive(1000)
    d.APCCamInitialise1([10_000_000], [10_000_000])
    d.APCSetCAMSize(1)
    d.APCSelectActionOnFreeze(2)
    d.run_ms(5)
    start = d.read(117)
    d.schedule("reference", "freeze", d.time_ns / 1000 + 400)
    d.tick()
    assert d.read(100) == 3
    for _ in range(50):
        d.tick()
        assert d.read(117) - start == d.read(28) - d.read(29)


def test_digital_lock_selected_by_freeze_aims_at_the_freeze_position():
    """L1842-1853 "This will synchronise the Slave axis to the Master axis, at the exact point the freeze
    occurred": rigid lock engaged by a freeze ends with slave − master = slave − master at the freeze."""
    d, _ = master_drive(800)
    d.APCEnableRigidLock()
    d.APCSelectActionOnFreeze(1)
    d.run_ms(5)
    before = d.read(117)
    d.schedule("reference", "freeze", d.time_ns / 1000 + 250)
    d.tick()
    assert d.read(100) == 4
    while d.read(61) != 1:
        d.tick()
    d.run_ms(10)
    assert d.read(117) - before == d.read(28) - d.read(29)


def test_single_shot_re_arm_runs_one_cam_per_mark():
    """L1605-1622 re-arm: "when a single shot completes, the stop reference will automatically be selected, the
    reference freeze will be reset, and the freeze trigger system will be reset"; a mark pitch shorter than the CAM's
    master length misses cuts."""
    def cuts(pitch_ms: int, marks: int) -> int:
        d, _ = master_drive(1000)
        d.APCCamInitialise1([20_000], [5_000])
        d.APCSetCAMSize(1)
        d.APCEnableCAMSingleShot()
        d.APCEnableCAMFreezeRearm()
        d.APCSelectActionOnFreeze(2)
        t0 = d.time_ns / 1000
        for m in range(marks):
            d.schedule("reference", "freeze", t0 + 1000 * pitch_ms * m + 100)
        done, was = 0, 0
        for _ in range(pitch_ms * marks + 50):
            d.tick()
            now = d.read(87)
            done += now and not was
            was = now
        return done
    assert cuts(30, 5) == 5                 # 30 000 counts between marks > 20 000 of CAM master length
    assert cuts(15, 6) < 6                  # shorter pitch: cuts are missed


def test_marker_reset_zeroes_within_the_turn_by_the_180_degree_rule():
    """L1096-1104 "If the motor has to turn less than 180° before the marker is found, then the position counters
    will jump down to zero … more than 180° … jump up to zero i.e. zero position, turn 1. The turns count is not
    reset"; the integrated position does not jump (decision A14)."""
    for travel, expected in ((10_000, 0), (50_000, 65536)):
        d = enabled_drive()
        vm = VirtualMaster(d, 0)
        d.APCEnableReferenceMarker()
        d.APCEnableRefSourceMarker()
        d.APCResetRefSourceMarkerFlag()
        vm.per_sample = travel
        d.tick()
        vm.per_sample = 0
        integrated = d.read(28)
        d.schedule("reference", "marker", d.time_ns / 1000 + 1000)
        d.tick()
        assert d.read(24) == 1 and d.read(25) == 1
        assert d.read(20) == expected and d.read(28) == integrated


def test_marker_capture_latches_source_and_integrated_positions():
    """L1026-1046 the marker pair [23]/[30] latches like the freeze pair; capture only without marker reset
    (L1129-1135)."""
    d = enabled_drive()
    VirtualMaster(d, 100)
    d.APCEnableReferenceMarker()
    d.APCResetRefSourceMarkerFlag()
    d.run_ms(3)
    d.schedule("reference", "marker", d.time_ns / 1000 + 500)
    d.tick()
    assert d.read(24) == 1 and d.read(23) == 350 and d.read(30) == d.read(28) - 50


def test_feedback_encoder_marker_from_the_plant():
    """The drive encoder's marker once per turn (decision A44): a feedback marker capture while the motor turns
    lands at the marker angle."""
    from motiontool.apc import ApcDrive, PlantConfig
    d = ApcDrive(PlantConfig(marker_angle=0.25))
    d.APCSetupOutputChannel(2, 0, 0)
    d.APCEnableOutputChannel()
    d.APCSetRunMode(2)
    d.APCEnableFeedbackMarker()
    d.APCResetFbckSourceMarkerFlag()
    d.APCSetSpeedSetPoint(17895 * 300)
    d.APCSelectReference(2)
    d.run_ms(300)
    assert d.read(44) == 1
    assert abs(d.read(43) % 65536 - 16384) <= 40


def test_events_must_come_after_the_last_sample():
    d, _ = master_drive()
    with pytest.raises(ValueError, match="last sample was at"):
        d.schedule("reference", "freeze", d.time_ns / 1000)
    with pytest.raises(ValueError, match="reference or feedback"):
        d.schedule("master", "freeze", d.time_ns / 1000 + 10)
    with pytest.raises(ValueError, match="freeze or marker"):
        d.schedule("reference", "index", d.time_ns / 1000 + 10)
