"""apc/fused.py's steady tick against KernelCore.tick's general steps on states the golden runs do not vary
(issue 30 item 1): the same rows (tests/apc/trace_identity.py's row: every read parameter and the internals), every
sample, with the fused tick and with it switched off, and the fused tick must have run most samples."""

from __future__ import annotations

import pytest

from motiontool.apc import ApcDrive, CTSyncLine, fused
from tests.apc.helpers import VirtualMaster
from tests.apc.trace_identity import IN, OUT1, ctsync_cam_line, row


def cam_drive(per_sample: int = 1500, *, pos_rate: int | None = None, start: int = 0, codes=(2, 0, 3),
              out2=None) -> tuple[ApcDrive, VirtualMaster]:
    """A drive following a user-program virtual master with the benchmark's CAM (or `codes`, a linear Out2)."""
    d = ApcDrive(pos_rate=pos_rate)
    d.APCSetupOutputChannel(2, 0, 0)
    d.APCEnableOutputChannel()
    d.APCSetRunMode(2)
    vm = VirtualMaster(d, per_sample)
    vm.counter = start
    if out2 is None:
        d.APCCamInitialise2(IN, OUT1, list(codes))
    else:
        d.APCCamInitialise(IN, OUT1, out2, list(codes))
    d.APCSetCAMInterpolationMode(-1)
    d.APCSetCAMSize(3)
    d.run_ms(10)
    d.APCSelectReference(3)
    return d, vm


def scripted(setup):
    """setup() → (tick, drives, {sample: action}); the rows of 2000 samples."""
    def rows() -> list:
        tick, drives, at = setup()
        out = []
        for k in range(2000):
            if k in at:
                at[k]()
            tick()
            out.append([row(d) for d in drives])
        return out
    return rows


def single(actions: dict | None = None, **kw):
    """One drive (cam_drive(**kw)); actions: {sample: f(drive, virtual master)}."""
    def setup():
        d, vm = cam_drive(**kw)
        return d.tick, [d], {k: (lambda f=f: f(d, vm)) for k, f in (actions or {}).items()}
    return scripted(setup)


def line_with_faults():
    line = ctsync_cam_line(3)
    line.inject(300, "checksum")
    line.inject(301, "missing")
    return line.tick, line.drives, {10: lambda: [d.APCSelectReference(3) for d in line.drives]}


VARIANTS = {
    "trigonometric laws": single(codes=(1, 4, 5)),
    "law codes outside 0-5, linear Out2": single(codes=(7, 0, -3), out2=[1000, -5000, 333]),
    "cosine mode, CAM output ratio": single(actions={500: lambda d, vm: (d.APCSetCAMInterpolationMode(1),
                                                                     d.APCSetCAMOutRatioNumerator(3),
                                                                     d.APCSetCAMOutRatioDenominator(7))}),
    "master reversing and stopping": single(actions={700: lambda d, vm: setattr(vm, "per_sample", -900),
                                                     1400: lambda d, vm: setattr(vm, "per_sample", 0)}),
    "int32 wrap of the reference": single(per_sample=40_000, start=(1 << 31) - 2_000_000),
    "0.25 ms POS period": single(pos_rate=1),
    "8 ms POS period": single(pos_rate=6, per_sample=12_000),
    "1 and 3 turns bits (round, not a shift, of the speed)": single(per_sample=1, actions={
        5: lambda d, vm: d.APCSetNumOfTurnsBits(1), 900: lambda d, vm: d.APCSetNumOfTurnsBits(3)}),
    "loop gains, ratio, clamps, external speed": single(actions={
        300: lambda d, vm: (d.APCSetSpeedFFwdGain(800), d.APCSetOutputRatioNumerator(3),
                            d.APCSetOutputRatioDenominator(2)),
        600: lambda d, vm: (d.APCSetPGainSpeedClamp(2000), d.APCSetOutputSpeedClamp(20_000_000)),
        900: lambda d, vm: (d.APCSetExternalRefSpeed(1_000_000), d.APCEnableExternalRefSpeed()),
        1200: lambda d, vm: (d.APCDisableExternalRefSpeed(), d.APCEnableExternalRefPosition())}),
    "#1.06 lowered, over range trips": single(actions={400: lambda d, vm: d.params.write((1, 6), 100),
                                                        800: lambda d, vm: d.params.write((81, 17), 1)}),
    "drive disabled and enabled, POS1": single(actions={
        300: lambda d, vm: d.params.write((1, 11), 0), 700: lambda d, vm: d.params.write((1, 11), 1),
        800: lambda d, vm: setattr(d, "pos1", lambda: d.APCSetPositionSetPoint(5))}),
    "inverted sources, input disabled": single(actions={
        300: lambda d, vm: d.APCInvertRefSource(), 600: lambda d, vm: d.APCInvertFbckSource(),
        900: lambda d, vm: (d.APCDisableRefInput(), d.APCSetRefInput(123)),
        1200: lambda d, vm: d.APCEnableRefInput()}),
    "freeze and marker events, offsets": single(actions={
        200: lambda d, vm: (d.APCEnableReferenceFreeze(), d.APCResetRefSourceFreezeFlag(),
                            d.schedule("reference", "freeze", d.time_ns / 1000 + 400)),
        500: lambda d, vm: (d.APCEnableFeedbackMarker(), d.APCResetFbckSourceMarkerFlag()),
        900: lambda d, vm: (d.APCSetSpeedOffset(100_000), d.APCSelectOffset(2)),
        1300: lambda d, vm: d.APCSelectOffset(0)}),
    "channel modes 0 and 3, run mode 1, reset": single(actions={
        300: lambda d, vm: d.APCSetupOutputChannel(0, 0, 0), 600: lambda d, vm: d.APCSetupOutputChannel(3, 18, 11),
        900: lambda d, vm: d.APCSetupOutputChannel(2, 0, 0), 1000: lambda d, vm: d.APCSetRunMode(1),
        1100: lambda d, vm: d.APCSetRunMode(2), 1500: lambda d, vm: d.APCReset()}),
    "single shot with freeze re-arm": single(actions={100: lambda d, vm: (d.APCEnableCAMSingleShot(),
                                                                          d.APCEnableCAMFreezeRearm())}),
    "delta-segment limit": single(actions={50: lambda d, vm: d.APCSetCAMDeltaSegLimit(1),
                                           60: lambda d, vm: setattr(vm, "per_sample", 300_000)}),
    "ctsync line with faults": scripted(line_with_faults),
}


@pytest.mark.parametrize("name", sorted(VARIANTS))
def test_the_fused_tick_equals_the_general_one(name: str, monkeypatch):
    steady, fused_tick = [], fused.steady_tick
    with monkeypatch.context() as m:     # counted: the comparison proves nothing if the fused tick never runs
        m.setattr(fused, "steady_tick", lambda d: steady.append(fused_tick(d)) or steady[-1])
        with_fused = VARIANTS[name]()
    with monkeypatch.context() as m:
        m.setattr(fused, "steady_tick", lambda d: False)
        general = VARIANTS[name]()
    assert with_fused == general
    assert sum(steady) > len(steady) // 2


def test_a_line_ticks_its_drives_fused(monkeypatch):
    """CTSyncLine.tick calls the fused tick itself (not through ApcDrive.tick), so switching it off above reaches
    the line's drives too."""
    calls: list[ApcDrive] = []
    line: CTSyncLine = ctsync_cam_line(2)
    real = fused.steady_tick
    monkeypatch.setattr(fused, "steady_tick", lambda d: calls.append(d) or real(d))
    line.tick()
    assert calls == line.drives


@pytest.mark.parametrize("position", [-5e-324, -1e-310, -0.0, 5e-324, -65536.0, -65535.5])
def test_the_fused_encoder_word_of_a_position_next_to_a_count(position: float, monkeypatch):
    """The fused tick quantises with floor(pos / step), Plant.step with int(pos // step): the same count also where
    pos / step underflows to -0.0 (a motor a hair below 0)."""
    words = []
    for steady in (fused.steady_tick, lambda d: False):
        monkeypatch.setattr(fused, "steady_tick", steady)
        d, _ = cam_drive()
        d.params.write((1, 11), 0)                      # not running: the motor coasts, here at rest
        d.plant.position, d.plant.speed = position, 0.0
        d.tick()
        words.append(d.plant.word)
    assert words[0] == words[1]
