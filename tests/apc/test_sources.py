"""Sources, integrators, turns bits, inversion, filter insertion, resets per reference, user units
(seed 004 §4.3, §4.12, §5.2.2)."""

import pytest

from motiontool.apc import ApcDrive, SlotEncoder
from motiontool.apc.units import rpm_to_speed

from .helpers import VirtualMaster, enabled_drive


def test_turns_bits_move_the_window_over_the_48_bit_word():
    """L2803-2835 "If the number of turns bits is set to 10, then the 32 bit position window … 1024 turns counts
    … and 4194304 position counts / revolution"."""
    d = ApcDrive()
    d.slots[1] = SlotEncoder(word=(5 << 32) | (0x4000 << 16) | 0x8000)     # 5¼ turns + half a coarse count
    d.APCSetReferenceSource(1)
    d.APCSetRunMode(1)
    d.tick()
    assert d.read(20) == 5 * 65536 + 0x4000
    d.APCSetNumOfTurnsBits(10)
    d.tick()
    assert d.read(20) == 5 * 4194304 + 0x4000 * 64 + 0x8000 // 1024 and d.read(14) == 10


def test_invert_acts_between_source_and_integrator():
    """L3042-3047 "inverts the reference source position, after the source counter [20], but before the integrated
    counter [28]"."""
    d = ApcDrive()
    VirtualMaster(d, 100)
    d.APCInvertRefSource()
    d.APCDoNotResetSourcesOnDisable()
    d.APCSetRunMode(1)
    d.run_ms(10)
    assert d.read(20) == 1000 and d.read(31) == -1000 and d.read(28) == -1000 and d.read(27) == 1


def test_filter_insertion_through_the_disabled_input():
    """L1153-1166 "The Reference or Feedback must be disabled … The current source position must be acquired from
    read parameter [20] … inserted back … using APCSetRefInput"; "Any values written in POS0 … are used in the same
    POS task cycle"."""
    d = ApcDrive()
    d.slots[1] = SlotEncoder(speed=1000 * 65536 // 4)      # 1000 counts per 1 ms sample
    d.APCSetReferenceSource(1)
    d.APCDisableRefInput()
    d.APCDoNotResetSourcesOnDisable()
    d.pos0 = lambda: d.APCSetRefInput(d.read(20) // 2)     # a "filter": half the source
    d.APCSetRunMode(1)
    d.run_ms(20)
    assert d.read(32) == 1 and d.read(31) == d.read(20) // 2 and d.read(28) == 10000


def test_reset_table_per_reference():
    """Table 4-2 (L975-996): the profile generator output is set from the feedback integrator; its input too,
    except in digital lock where it is the reference integrator."""
    for reference, expect_input in ((1, "feedback"), (4, "reference")):
        d = enabled_drive()
        VirtualMaster(d, 300)
        d.APCEnableRigidLock()
        d.APCSetPositionSetPoint(0)
        d.APCSelectReference(reference)
        d.run_ms(50)
        d.APCSetPositionResetOffset(777)
        d.APCReset()
        d.tick()
        d.tick()
        assert d.read(117) in range(777 - 2000, 777 + 2000)
        if expect_input == "reference":
            assert d.dl.target == d.read(28)          # ratio 1000/1000 · reference integrator
        else:
            assert d.read(48) == 777 + (d.read(48) - 777)


def test_rigid_lock_shows_a_reset_offset_as_following_error():
    """L2602-2606 "if the Digital Lock reference is selected by APCSelectReference(4), with APCEnableRigidLock()
    active, the resultant following error will equal the reset offset position value"."""
    d = enabled_drive()
    VirtualMaster(d, 0)
    d.APCEnableRigidLock()
    d.APCSelectReference(4)
    d.run_ms(20)
    d.APCSetPositionResetOffset(5000)
    d.APCReset()
    d.tick()
    d.tick()
    assert d.read(48) in range(4990, 5010) and d.dl.target == 0
    d.run_ms(1000)
    assert abs(d.read(48)) <= 2            # the lock pulls the axis back onto ratio · reference


def test_rigid_lock_selected_when_the_apc_is_enabled_shows_the_reset_offsets():
    """L2381 "When mode 2 is selected, the internal integrated position counters are set as shown in Table 4-2"
    (Digital Lock: profile generator input = reference integrator); L2597/L2616 "if the Digital Lock reference is
    selected by APCSelectReference(4), with APCEnableRigidLock() active, the resultant following error will equal
    the reset offset position value, and will therefore cause a corresponding speed reference to be generated".
    Both offsets: feedback [2] and reference [6], the lock selected along with run mode 2 (§7.5's POS0 does both
    in one pass). The lock aims at the reset reference integrator while the slave starts at the reset feedback
    integrator; the error between them is pulled out within the profile limits (decisions A40, A42)."""
    for fb_offset, ref_offset, rest in ((5000, 0, 0), (0, 3000, 3000), (5000, 3000, 3000)):
        d = ApcDrive()
        d.APCSetupOutputChannel(2, 0, 0)
        d.APCEnableOutputChannel()
        VirtualMaster(d, 0)
        d.APCSetPositionResetOffset(fb_offset)
        d.APCSetRefPosResetOffset(ref_offset)
        d.APCEnableRigidLock()
        d.APCSelectReference(4)
        d.APCSetRunMode(2)
        d.tick()                                  # the disabled sample: integrators at their reset values
        d.tick()
        assert (d.read(48), d.read(28), d.dl.target) == (fb_offset, ref_offset, ref_offset)
        d.run_ms(1000)
        assert abs(d.read(48) - rest) <= 2     # the speed reference moved the motor onto ratio · reference


def test_lock_selected_at_enable_without_reset_offset_does_not_move():
    """L2597 "Where an offset is applied, there will be no resultant following error" — nor without one: a rigid
    lock enabled on a still master with both offsets 0 keeps the axis where it is; a non-rigid lock with an
    offset engages at the slave (the rigid-lock clause only)."""
    for rigid, offset in ((True, 0), (False, 5000)):
        d = ApcDrive()
        d.APCSetupOutputChannel(2, 0, 0)
        d.APCEnableOutputChannel()
        VirtualMaster(d, 0)
        d.APCSetPositionResetOffset(offset)
        if rigid:
            d.APCEnableRigidLock()
        d.APCSelectReference(4)
        d.APCSetRunMode(2)
        d.run_ms(500)
        assert d.read(48) == offset and d.read(130) == 0


def test_stop_to_position_transfer_with_and_without_remainder():
    """L2211-2230, Fig 4-47: N/D = 4/1, running at 2 units/s, Stop with decel 1 unit/s² ends 2 units later; setting
    only the whole units moves the axis to the nearest whole unit, APCTransferStopPosToPosSetPoint keeps it still."""
    d = enabled_drive()
    d.SetUPRNumeratorAndDenominator(4, 1)
    d.APCSetProfileAccelRate(1)
    d.APCSetProfileDecelRate(1)
    d.APCSetSpeedSetPoint(2)
    d.APCSelectReference(2)
    d.run_ms(2500)
    d.APCSetPositionSetPoint(0)
    d.APCSelectReference(0)
    d.run_ms(3000)
    rest = d.read(1117)
    value, rem, _ = d.APCReadParWithRem(91)
    assert rem != 0 and value * 16384 + rem // 4 == rest
    d.APCSetSetPointRem(0)
    d.APCSetPositionSetPoint(value)
    d.APCSelectReference(1)
    d.run_ms(500)
    assert d.read(1117) == value * 16384 != rest           # crept to the whole unit
    d.APCSelectReference(0)
    d.run_ms(100)
    here = d.read(1117)
    d.APCTransferStopPosToPosSetPoint()
    d.APCSelectReference(1)
    d.run_ms(500)
    assert d.read(1117) == here                            # no motion


def test_slot_without_module_trips_tr81():
    """L2326-2327 "The slot selected as the reference or feedback does not contain a position option module"."""
    d = ApcDrive()
    assert d.APCSetFeedbackSource(2) == 0 and d.trip == "Tr81"


def test_source_changed_from_two_tasks_trips_tr81():
    """L2328-2331 "An attempt to change the Reference source or the Feedback source in more than one task"."""
    d = ApcDrive()
    d.task = "initial"
    d.APCSetReferenceSource(4)
    d.task = "background"
    d.APCSetReferenceSource(0)
    assert d.trip == "Tr81"


def test_source_speed_in_apc_units():
    """L7719 [26] reference source speed in 2^32 counts/rev per 250 µs: a slot encoder at 1000 rpm reads so."""
    d = ApcDrive()
    d.slots[2] = SlotEncoder(speed=rpm_to_speed(1000))
    d.APCSetReferenceSource(2)
    d.APCSetRunMode(1)
    d.run_ms(5)
    assert abs(d.read(26) - rpm_to_speed(1000)) < 65536 // 4


def test_encoder_lines_per_revolution_set_the_counter_steps():
    """L463-467 "for 1024ppr encoder the counts per rev will be 4096. For one count the counter will go up in steps
    of 16 (65536/4096)": with #3.34 = 1024 every feedback position [40] is a multiple of 16 and moves in steps of 16;
    the default 16384 lines count in steps of 1 (L1004: 4096 ppr → 16384 counts → steps of 4)."""
    def positions(lines):
        d = enabled_drive()
        if lines is not None:
            d.params["3.34"] = lines
        d.APCSetSpeedSetPoint(rpm_to_speed(7))
        d.APCSelectReference(2)
        seen = []
        for _ in range(300):
            d.tick()
            seen.append(d.read(40))
        return d, seen
    d, seen = positions(1024)
    assert d.params["3.34"] == 1024 and seen[-1] > 1000
    assert {p % 16 for p in seen} == {0} and {(b - a) % 16 for a, b in zip(seen, seen[1:], strict=False)} == {0}
    _, seen = positions(4096)
    assert {p % 4 for p in seen} == {0} and any(p % 16 for p in seen)
    d, seen = positions(None)
    assert d.params["3.34"] == 16384 and any(p % 4 for p in seen)
    _, seen = positions(1000)                      # 4000 counts: count c is at ⌊c·65536/4000⌋, a turn stays 65536
    assert all(-(-p * 4000 // 65536) * 65536 // 4000 == p for p in seen) and len(set(seen)) > 20
    with pytest.raises(ValueError, match="#3.34 = 0: drive encoder lines per revolution, 1 to 50000"):
        d.params["3.34"] = 0
