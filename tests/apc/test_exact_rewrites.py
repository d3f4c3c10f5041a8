"""Round 2 of decision K128 (issue 30 item 1): the cheaper forms the CTSync line's sample now takes, each held to the
general code it replaces, over inputs the benchmark never reaches (negative, wrapping, marker-adjusted, any turns
bits)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.apc import ApcDrive, fused
from motiontool.apc.intmath import INT32_MAX, INT32_MIN, MULDIVRM, div_trunc, wrap32
from motiontool.apc.plant import REV, Plant, PlantConfig
from motiontool.apc.sources import Source, _interp, user_word
from tests.apc.test_fused_tick import cam_drive
from tests.apc.trace_identity import row

INT32 = st.integers(INT32_MIN, INT32_MAX)


@given(a=INT32, b=INT32, c=INT32.filter(bool))
def test_muldivrm_is_div_trunc_wrapped(a: int, b: int, c: int):
    """L6921 '(VMCntsPerSample%, VMRemainder%) = MULDIVRM(RPM%, CountsPerRev%, 60000)': the call without its inner
    calls for a non-negative product and divisor gives what div_trunc and wrap32 give."""
    q, r = div_trunc(a * b, c)
    assert MULDIVRM(a, b, c) == (wrap32(q), wrap32(r))


@given(turns=st.integers(-2**40, 2**40), position=st.integers(-2**40, 2**40), fine=st.integers(-2**40, 2**40))
def test_set_reference_position_is_user_word(turns: int, position: int, fine: int):
    """L3094-3096 'The lower 16-bits of Turns% ... Position% ... PositionFine% will be treated as a signed 16-bit
    value. Bits 16 to 31 ... will be ignored': the call's written-out word equals user_word()."""
    d = ApcDrive()
    d.APCSetReferencePosition(turns, position, fine)
    assert d.ref.user_word == user_word(turns, position, fine)


def _crossings_as_a_list(plant: Plant, before: float, after: float) -> list[float]:
    """Plant.marker_crossings before round 2: every crossing through the list, whatever their number."""
    phase = plant.marker_phase
    assert phase is not None
    if before == after:
        return []
    k0 = math.floor((before - phase) / REV)
    k1 = math.floor((after - phase) / REV)
    if k0 == k1:
        return []
    lo, hi = (k0 + 1, k1) if k1 > k0 else (k1 + 1, k0)
    marks = [k * REV + phase for k in range(lo, hi + 1)]
    return sorted((m - before) / (after - before) for m in marks)


@given(before=st.floats(-3 * REV, 3 * REV), travel=st.floats(-2.5 * REV, 2.5 * REV),
       angle=st.floats(0.0, 0.999))
def test_one_marker_crossing_is_the_lists_only_element(before: float, travel: float, angle: float):
    """The single-crossing shortcut of Plant.marker_crossings gives the general list (the marker flank of L1090-1100
    is passed once per motor turn)."""
    plant = Plant(PlantConfig(marker_angle=angle))
    assert plant.marker_crossings(before, before + travel) == _crossings_as_a_list(plant, before, before + travel)


def _capture_as_before(s: Source, t_start: int, t_end: int, turns_bits: int) -> list[tuple[str, int]]:
    """Source.capture_events before round 2 (without the early return when no latch is armed)."""
    if not s.events:
        return []
    due = [e for e in s.events if e[0] <= t_end]
    s.events = [e for e in s.events if e[0] > t_end]
    made = []
    span = max(t_end - t_start, 1)
    d_src = wrap32(s.position - s.sample_start_position)
    d_int = wrap32(s.integrated - s.sample_start_integrated)
    for when, kind in sorted(due):
        frac_num = min(max(when - t_start, 0), span)
        src = wrap32(s.sample_start_position + _interp(d_src, frac_num, span))
        main = wrap32(s.sample_start_integrated + _interp(d_int, frac_num, span))
        if kind == "freeze":
            if s.freeze_enabled and not s.freeze_flag:
                s.freeze_flag, s.freeze_position, s.freeze_integrated = 1, src, main
                made.append(("freeze", main))
        elif s.marker_enabled and not s.marker_flag:
            s.marker_flag = 1
            if s.marker_reset:
                s._align_to_marker(src, turns_bits)
            else:
                s.marker_position, s.marker_integrated = src, main
                made.append(("marker", main))
    return made


@given(events=st.lists(st.tuples(st.integers(0, 2_000_000), st.sampled_from(["freeze", "marker"])), max_size=4),
       latches=st.tuples(*[st.integers(0, 1)] * 5), positions=st.tuples(*[INT32] * 4))
def test_capture_events_as_before(events, latches, positions):
    """Source.capture_events returns early when neither latch is armed (Table 4-7, L1093-1100: a capture needs its
    flag enabled and reset): the same captures and the same source afterwards as the loop over the due events."""
    sources = []
    for _ in range(2):
        s = Source("feedback")
        s.freeze_enabled, s.freeze_flag, s.marker_enabled, s.marker_flag, s.marker_reset = latches
        s.position, s.integrated, s.sample_start_position, s.sample_start_integrated = positions
        s.events = list(events)
        sources.append(s)
    assert sources[0].capture_events(0, 1_000_000, 16) == _capture_as_before(sources[1], 0, 1_000_000, 16)
    assert vars(sources[0]) == vars(sources[1])


@settings(max_examples=40, deadline=None)
@given(fb_adjust=st.integers(-2**48, 2**48), ref_adjust=st.integers(-2**48, 2**48), turns_bits=st.integers(1, 16),
       start=st.integers(INT32_MIN, INT32_MAX))
def test_the_fused_source_reads_equal_the_general_ones(fb_adjust, ref_adjust, turns_bits, start):
    """The fused tick's source reads (the marker adjustment added only when there is one, the signed 32-bit value
    without the XOR, the int32 tests by one-digit bounds first) against Source.refresh, through whole samples."""
    rows, taken, real = [], [], fused.steady_tick
    for steady in (lambda d: taken.append(real(d)) or taken[-1], lambda d: False):
        with pytest.MonkeyPatch.context() as m:
            m.setattr(fused, "steady_tick", steady)
            d, _ = cam_drive(start=start)
            d.APCSetNumOfTurnsBits(turns_bits)
            d.fb.marker_adjust, d.ref.marker_adjust = fb_adjust, ref_adjust
            out = []
            for _ in range(6):
                d.tick()
                out.append(row(d))
            rows.append(out)
    assert rows[0] == rows[1]
    assert sum(taken) >= 3
