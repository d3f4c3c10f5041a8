"""The APC tick core: run modes, resets, the read-parameter store, the DPL binding (seed 004 §4.2-4.3, §5.2.1)."""

import pytest

from motiontool.apc import ALIASES, SIGNATURES, ApcDrive, signature
from motiontool.apc.readpars import READ_PARAMETERS, parameter_number

from .helpers import VirtualMaster, enabled_drive


def test_enable_status_lags_the_request_by_one_sample():
    """L928-930 "the APC will run in disabled for 1 position task sample … read parameter [4] … is set at the end of
    the APC kernel run time"."""
    d = ApcDrive()
    d.APCSetRunMode(1)
    d.tick()
    seen = []
    d.pos1 = lambda: seen.append((d.read(0), d.read(4)))
    d.APCSetRunMode(2)
    d.tick()
    d.tick()
    assert seen == [(1, 0), (1, 1)]


def test_run_mode_0_does_not_call_the_kernel():
    """L779-781 "Off In this mode the APC is never called": the counters do not follow the source."""
    d = ApcDrive()
    vm = VirtualMaster(d, 100)
    d.run_ms(10)
    assert vm.counter == 1000 and d.read(20) == 0 and d.read(28) == 0


def test_disabled_counts_and_resets_the_integrators_per_mode():
    """L2372-2378: in run mode 1 the integrated counters stay at their reset values with ResetSourcesOnDisable
    (Table 4-2: relative 0 + offset, absolute the source + offset) and integrate with DoNotResetSourcesOnDisable."""
    d = ApcDrive()
    VirtualMaster(d, 100)
    d.APCSetRunMode(1)
    d.APCSetRefPosResetOffset(5)
    d.run_ms(10)
    assert d.read(20) == 1000 and d.read(28) == 5
    d.APCSelectAbsoluteMode()
    d.tick()
    assert d.read(28) == d.read(20) + 5 == 1105
    d.APCDoNotResetSourcesOnDisable()
    d.APCSelectRelativeMode()
    d.run_ms(10)
    assert d.read(28) == 1105 + 1000


def test_apc_reset_pulses_status_5_and_resets_with_offsets():
    """L2436-2444 "When [5] = 1 a reset is in progress, and when [5] changes from 1 to 0 the reset is complete";
    the feedback and profile counters take the reset offset (L2592-2606)."""
    d = enabled_drive()
    VirtualMaster(d, 50)
    d.run_ms(5)
    d.APCSetPositionResetOffset(1000)
    trace = []
    d.pos0 = (lambda vm=d.pos0: (vm(), trace.append(d.read(5))))
    assert d.APCReset() == 1
    d.run_ms(4)
    assert trace[:3] == [1, 1, 0]
    assert d.read(28) == 3 * 50          # reset to 0, then 3 samples of 50
    assert d.read(117) == 1000 and d.read(115) == 1000


def test_apc_reset_only_in_run_mode_2():
    """L2436 "This command is only functional when the APC run mode is set to 2"."""
    d = ApcDrive()
    d.APCSetRunMode(1)
    assert d.APCReset() == 0


def test_read_parameters_by_number_alias_and_raw():
    """L7701-7875 read parameters, L8038-8199 aliases, L2203-2205 "+1000 … will be read in APC units"."""
    d = enabled_drive()
    d.APCSetPositionSetPoint(65536 * 3)
    assert d.read("APC_POS_SETPOINT") == d.read(92) == d.read("[92]") == 196608
    assert d.APCReadPar(1092) == (196608, 1)
    assert d.APCReadPar(99) == (0, 0)
    assert parameter_number("apc_fb_pos") == 48
    with pytest.raises(ValueError, match="no APC read parameter"):
        parameter_number("APC_NOTHING")
    assert set(READ_PARAMETERS) >= {0, 4, 5, 28, 48, 91, 117, 135, 186, 189}


def test_user_units_reads_round_and_raw_reads_stay_in_counts():
    """L2197-2209: with a UPR set, position reads are in units (rounded, remainder from APCReadParWithRem);
    [n+1000] and the permanently raw [170] stay in counts."""
    d = enabled_drive()
    assert d.SetUPRNumeratorAndDenominator(4, 1) == 1          # quarter revolutions (§4.12.3)
    assert d.read(96) == 65536 and d.read(97) == 4
    d.APCSetSetPointRem(100)
    d.APCSetPositionSetPoint(3)
    assert d.read(170) == 3 * 16384 + 25                        # (3·65536 + 100)/4
    assert d.APCReadParWithRem(92) == (3, 100, 1)
    assert d.APCReadPar(1092) == (3 * 16384 + 25, 1)


def test_signatures_follow_the_manual():
    """Names and argument orders of §5 (e.g. L3093 APCSetReferencePosition(Turns%, Position%, PositionFine%),
    L4253 APCSetupOutputChannel(Mode%, Menu%, Parameter%), L3273 CTSyncGetSlaveReferences outputs)."""
    assert SIGNATURES["APCSetReferencePosition"].args == ("Turns", "Position", "PositionFine")
    assert SIGNATURES["APCSetupOutputChannel"].args == ("Mode", "Menu", "Parameter")
    assert SIGNATURES["APCReadParWithRem"].outputs == ("Value%", "Remainder%", "Status%")
    assert signature("ctsyncgetslavereferences").outputs == ("Reference1%", "Reference2%", "AuxRef%", "Status%")
    assert signature("CTSYNCSetMasterReferences").name == "CTSyncSetMasterReferences"
    quick = ("APCSetRunMode APCReset APCGetOutputSpeed APCGetOutputSpeedRpmx10 APCSelectAbsoluteMode "
             "APCSelectRelativeMode APCReadPar APCReadParWithRem APCSetPositionResetOffset APCSetRefPosResetOffset "
             "APCResetSourcesOnDisable APCDoNotResetSourcesOnDisable APCSetReferenceSource APCSetFeedbackSource "
             "APCSetNumOfTurnsBits APCEnableRefSourceMarker APCDisableRefSourceMarker APCEnableFbckSourceMarker "
             "APCDisableFbckSourceMarker APCResetRefSourceMarkerFlag APCResetFbckSourceMarkerFlag "
             "APCResetRefSourceFreezeFlag APCResetFbckSourceFreezeFlag APCEnableReferenceMarker "
             "APCDisableReferenceMarker APCEnableFeedbackMarker APCDisableFeedbackMarker APCEnableReferenceFreeze "
             "APCDisableReferenceFreeze APCEnableFeedbackFreeze APCDisableFeedbackFreeze APCInvertRefSource "
             "APCDoNotInvertRefSource APCInvertFbckSource APCDoNotInvertFbckSource APCSetReferencePosition "
             "APCSetFeedbackPosition APCGetReferenceStatus APCGetFeedbackStatus APCEnableRefInput APCDisableRefInput "
             "APCEnableFbckInput APCDisableFbckInput APCSetRefInput APCSetFbckInput APCSelectReference "
             "APCSelectActionOnFreeze APCSetStopMode APCTransferStopPosToPosSetPoint APCSetPositionSetPoint "
             "APCSetSetPointRem APCSetSpeedSetPoint APCCamInitialise APCCamInitialise1 APCCamInitialise2 "
             "APCCamInitialise3 APCSetCAMStartIndex APCSetCAMSize APCSetCAMDeltaSegLimit APCSetCAMInterpolationMode "
             "APCSetCAMOutRatioNumerator APCSetCAMOutRatioDenominator APCSelectCAMAbsoluteReset "
             "APCSelectCAMZeroReset APCSetCAMAbsResetIndex APCSetCAMAbsResetPositionInSeg APCEnableCAMSingleShot "
             "APCDisableCAMSingleShot APCEnableCAMFreezeRearm APCDisableCAMFreezeRearm APCSetDigLockMode "
             "APCSetDigLockRatioNumerator APCSetDigLockRatioDenominator APCSetDigLockLockingSpeed "
             "APCSetDigLockLockingPosition APCEnableRigidLock APCDisableRigidLock APCEnableProfile APCDisableProfile "
             "APCSetProfileAccelRate APCSetProfileDecelRate APCSetProfileJerk APCSetProfileMaxSpeedClamp "
             "APCSetSpeedOffset APCSetPositionOffset APCSetOffsetRem APCSelectOffset APCEnableOffsetProfile "
             "APCDisableOffsetProfile APCSetOffProfileAccelRate APCSetOffProfileDecelRate APCSetOffProfileJerk "
             "APCSetOffProfileMaxSpeedClamp APCSetPGain APCSetPGainSpeedClamp APCEnableExternalRefSpeed "
             "APCDisableExternalRefSpeed APCSetExternalRefSpeed APCEnableExternalRefPosition "
             "APCDisableExternalRefPosition APCSetExternalRefPosition APCSetSpeedFFwdGain APCSetOutputRatioNumerator "
             "APCSetOutputRatioDenominator APCSetOutputSpeedClamp APCSetupOutputChannel APCEnableOutputChannel "
             "APCDisableOutputChannel APCWriteOutputChannel UnsignedTopWord SignedTopWord UnsignedBottomWord "
             "SignedBottomWord PutTopWord PutBottomWord SetUPRNumeratorAndDenominator GetUPRNumeratorAndDenominator "
             "UserToAPCPosition APCToUserPosition UserToAPCVelocity APCToUserVelocity UserToAPCAcceleration "
             "APCToUserAcceleration SetConverterNumerator SetConverterDenominator ConvertForwards ConvertBackwards "
             "CTSyncSetMasterReferences CTSyncGetSlaveReferences MULDIV MULDIVRM")
    missing = [name for name in quick.split() if name not in SIGNATURES]
    assert not missing


def test_call_dpl_pads_the_quick_reference_status():
    """L7509 "(Speed%, Status%) = APCGetOutputSpeed ()" vs L2447 "Speed% = APCGetOutputSpeed()": both forms run."""
    d = enabled_drive()
    assert d.call_dpl("APCGetOutputSpeed", (), 1) == (0,)
    assert d.call_dpl("apcgetoutputspeed", (), 2) == (0, 1)
    assert d.call_dpl("APCReadPar", (4,), 1) == (1,)
    assert d.call_dpl("MULDIVRM", (100, 65536, 60000), 2) == (109, 13600)
    assert d.call_dpl("APCSetRunMode", (2,), 0) == ()
    with pytest.raises(TypeError, match="takes 1 argument"):
        d.call_dpl("APCSetRunMode", (), 1)


def test_aliases():
    """L7946-8199: a program may use the number or the alias."""
    assert ALIASES["APC_ENABLE"] == 2 and ALIASES["APC_DIG_LOCK_REF"] == 4 and ALIASES["APC_CAM_ON_FRZ"] == 2
    assert ALIASES["APC_FB_POS"] == 48 and ALIASES["APC_OFF_ACCEL"] == 150
    assert ALIASES["APC_INVALID_ARGU"] == -4


def test_invalid_arguments_answer_apc_invalid_argu():
    """L8005-8013 APC_INVALID_ARGU -4 (decision A6)."""
    d = ApcDrive()
    assert d.APCSetRunMode(3) == -4
    assert d.APCSetNumOfTurnsBits(17) == -4
    assert d.APCSetCAMStartIndex(-5) == 1 and d.read(74) == 0       # clamped, L3500-3503
