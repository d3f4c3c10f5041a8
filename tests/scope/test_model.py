"""The oscilloscope's Qt-free model: sample FIFO, decimation, curves, derived curves, cursors, triggers."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.scope.buffer import MinMaxPyramid, RingBuffer, decimate_minmax
from motiontool.scope.curves import AxisSettings, Curve, Group, Scaling, Scope, signal_label, smooth
from motiontool.scope.derived import DerivedError, DerivedSpec, compute, parse_expression
from motiontool.scope.measure import CursorReadout, curve_value_at
from motiontool.scope.trigger import Capture, Trigger


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 50), st.lists(st.lists(st.floats(-1e6, 1e6), max_size=70), max_size=8))
def test_ring_buffer_keeps_the_newest_samples_in_order(capacity, blocks):
    """DG 5995-6001 (ide-spec 6.32): "The sample limit works as a FIFO: the oldest points are dropped"."""
    buf = RingBuffer(capacity)
    everything = []
    for block in blocks:
        t = np.arange(len(everything), len(everything) + len(block), dtype=float)
        buf.extend(t, block)
        everything += block
    t, y = buf.arrays()
    assert list(y) == everything[-capacity:] if everything else y.size == 0
    assert list(t) == list(range(len(everything)))[-capacity:]


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(-1e9, 1e9), min_size=1, max_size=3000), st.integers(1, 300))
def test_min_max_decimation_never_loses_a_peak(values, bins):
    y = np.array(values)
    t = np.arange(y.size, dtype=float)
    tt, yy = decimate_minmax(t, y, bins)
    assert yy.size <= max(2 * bins + 2, y.size)
    assert yy.min() == y.min() and yy.max() == y.max()
    assert np.all(np.diff(tt) >= 0)


def test_pyramid_window_keeps_the_envelope_of_ten_million_samples():
    t = np.arange(10_000_000, dtype=float)
    y = np.sin(t / 1e5)
    y[4_321_987] = 7.0  # one spike in the middle
    p = MinMaxPyramid(t, y)
    tt, yy = p.window(0, 1e7, 1000)
    assert yy.size <= 4000 and yy.max() == 7.0 and yy.min() == pytest.approx(-1.0, abs=1e-6)
    tt, yy = p.window(4_000_000, 4_100_000, 1000)
    assert tt[0] <= 4_000_000 and tt[-1] >= 4_099_000 - 200


def test_curve_names_follow_the_manual():
    """DG 5343-5345: names "have the format "Axis: Name [Index]"" (the index from the command)."""
    assert signal_label("4097") == "1: REG_ACTPOS [4097]"
    assert signal_label("0x01250006") == "1: REG_TRACKERR [0x01250006]"
    assert signal_label("apos") == "1: APOS"


def test_scaling_range_and_smoothing_change_the_view_not_the_data():
    """DG 5125-5129: "(y-offset)*scale", mm → cm with offset 0 and scale 0.1; DG 5143-5161: smoothing width
    2 averages 5 points, display only."""
    c = Curve("x")
    c.buffer.extend(np.arange(10.0), [0, 0, 0, 0, 50, 0, 0, 0, 0, 4950])
    c.scaling = Scaling(0.0, 0.1)
    assert c.stats() == (495.0, 0.0, 495.0)
    c.range_high = 400
    assert c.out_of_range(495.0) and not c.out_of_range(5.0)
    c.smoothing = 2
    assert c.display()[1][4] == pytest.approx(1.0)   # (0+0+5+0+0)/5
    assert c.raw()[1][4] == 50                        # stored data unchanged
    assert list(smooth(np.array([1.0, 2, 3]), 5)) == [2, 2, 2]


def test_axis_range_min_height_and_centre_zero():
    """DG 5180-5203: automatic range padded, at least Min Height; "Center zero when reset"."""
    c = Curve("flat", axis=AxisSettings(min_height=10))
    c.buffer.extend([0, 1], [5, 5])
    assert c.y_range() == (0.0, 10.0)
    c.buffer.extend([2], [-1])
    c.axis.center_zero = True
    lo, hi = c.y_range()
    assert lo == -hi and hi >= 5


def test_shares_chain_and_single_shot_groups_exclude_each_other():
    """DG 5207-5225: shares chain (C→B→A); DG 5865: a second group on the same controller deselects the
    first."""
    s = Scope("single_shot")
    for n in "ABC":
        s.add_curve(Curve(n))
    s.curve("C").axis.share = "B"
    s.curve("B").axis.share = "A"
    assert s.shared_root("C") == "A"
    s.remove_curve("B")
    assert s.curve("C").axis.share is None
    s.add_group(Group("g1", method="single_shot"))
    s.add_group(Group("g2", method="single_shot"))
    s.set_group_active("g2", True)
    assert not s.group("g1").active and s.group("g2").active
    with pytest.raises(ValueError, match="exists already"):
        s.add_group(Group("g1"))


def _lookup(curves):
    return lambda name: curves[name]


def test_derived_curves():
    """DG 5630-5674: derivative, delta, difference, bit mask; plus sum, product, scaled, integral."""
    t = np.arange(0.0, 1001.0, 1.0)       # ms
    pos = 0.5 * t                          # 500 UU/s
    other = np.full_like(t, 2.0)
    curves = _lookup({"p": (t, pos), "o": (t, other)})
    assert np.allclose(compute(DerivedSpec("derivative", "p"), curves)[1], 500.0)
    assert np.allclose(compute(DerivedSpec("delta", "p"), curves)[1][1:], 0.5)
    assert np.allclose(compute(DerivedSpec("difference", "p", "o"), curves)[1], pos - 2)
    assert np.allclose(compute(DerivedSpec("sum", "p", "o"), curves)[1], pos + 2)
    assert np.allclose(compute(DerivedSpec("product", "p", "o"), curves)[1], pos * 2)
    assert np.allclose(compute(DerivedSpec("scaled", "p", factor=2, offset=1), curves)[1], pos * 2 + 1)
    assert compute(DerivedSpec("integral", "o"), curves)[1][-1] == pytest.approx(2.0)  # 2 × 1 s
    words = _lookup({"w": (np.array([0.0]), np.array([0x12345678]))})
    assert compute(DerivedSpec("bit_mask", "w", mask=0x0000FF00), words)[1][0] == 0x56
    assert compute(DerivedSpec("bit_mask", "w", mask=0xFF00, signed=True),
                   _lookup({"w": (np.array([0.0]), np.array([0x8000]))}))[1][0] == -128


def test_difference_of_two_runs_resamples_the_second_curve():
    curves = _lookup({"a": (np.array([0.0, 10, 20]), np.array([0.0, 10, 20])),
                      "b": (np.array([5.0, 15]), np.array([0.0, 10]))})
    y = compute(DerivedSpec("difference", "a", "b"), curves)[1]
    assert np.isnan(y[0]) and y[1] == 5.0 and np.isnan(y[2])


def test_expressions_are_parsed_never_evaluated_by_python():
    t = np.arange(5.0)
    curves = _lookup({"1: APOS": (t, t * 2), "1: CPOS": (t, t * 3)})
    spec = DerivedSpec("expression", expression="abs(c - a) * 2 + (a & 0xF) - pi * 0",
                       variables={"a": "1: APOS", "c": "1: CPOS"})
    assert list(compute(spec, curves)[1]) == [0, 4, 8, 12, 16]
    for bad in ("__import__('os')", "a.real", "a if a else c", "[a]", "lambda: 1", "a @ c", "'x'", "a(1)",
                "open", "a; c", "c ** 1000"):
        with pytest.raises(DerivedError):
            compute(DerivedSpec("expression", expression=bad, variables={"a": "1: APOS", "c": "1: CPOS"}),
                    curves)
    with pytest.raises(DerivedError, match="unknown name 'z' at column 5"):
        parse_expression("a + z", {"a"})


def test_cursor_readout():
    """DG 5030-5038: columns A, B and B−A; Δt and 1/Δt between the cursors."""
    c = Curve("x")
    c.buffer.extend([0, 10, 20], [0, 100, 50])
    r = CursorReadout.of(c, 5, 15)
    assert (r.a, r.b, r.dt_ms, r.d_value, r.frequency_hz) == (50.0, 75.0, 10, 25.0, 100.0)
    c.interpolation = "values"
    assert curve_value_at(c, 15) == 100.0
    assert curve_value_at(c, 25) is None


def test_trigger_with_pre_trigger_captures_the_window_around_the_edge():
    """halscope's PRE_TRIG → TRIG_WAIT → POST_TRIG → DONE with pre-trigger samples (peers.md 2.1)."""
    cap = Capture(Trigger(signal=0, level=10, edge="rising", pre=5, post=10), columns=1)
    y = np.concatenate([np.full(30, 12.0), np.zeros(20), np.arange(50.0)])  # high at the start: no edge yet
    t = np.arange(y.size, dtype=float)
    for i in range(0, y.size, 7):
        cap.feed(t[i:i + 7], y[i:i + 7, None])
    assert cap.done and cap.trigger_time == 60.0  # first rising crossing of 10 at y = 10 (t = 50 + 10)
    tt, vv = cap.result()
    assert list(tt) == list(range(55, 70)) and vv.shape == (15, 1)
    pattern = Capture(Trigger(edge="pattern", mask=0x0F, pattern=0x05, pre=0, post=2), columns=1)
    pattern.feed([0, 1, 2, 3], [[0x10], [0x15], [0x25], [0]])
    assert pattern.done and pattern.trigger_time == 1.0
    with pytest.raises(ValueError):
        Trigger(edge="sideways")


def test_derived_curve_is_inserted_after_its_base_and_follows_new_data():
    """ide-spec 6.45 (DG 5630-5674): the new curve is inserted right after its base curve; ide-spec S24."""
    from motiontool.scope.derived import add_derived, refresh

    s = Scope()
    a = s.add_curve(Curve("1: REG_ACTPOS"))
    b = s.add_curve(Curve("1: REG_COMPOS"))
    a.buffer.extend([0, 1, 2], [0, 1, 2])
    b.buffer.extend([0, 1, 2], [0, 2, 4])
    d = add_derived(s, DerivedSpec("difference", "1: REG_ACTPOS", "1: REG_COMPOS"), "diff")
    assert [c.name for c in s.curves] == ["1: REG_ACTPOS", "diff", "1: REG_COMPOS"]
    assert list(d.raw()[1]) == [0, -1, -2]
    a.buffer.extend([3], [3])
    b.buffer.extend([3], [6])
    refresh(s)
    assert list(d.raw()[1]) == [0, -1, -2, -3]
    s.remove_curve("1: REG_COMPOS")
    assert refresh(s) == ["diff"] and "REG_COMPOS" in d.source.info["error"]
    with pytest.raises(KeyError):
        add_derived(s, DerivedSpec("derivative", "nope"), "x")


def test_tune_measurements_on_a_known_response():
    """ide-spec 6.60 DECISION: overshoot past the target, settling time from the profile's end into ±band
    (held to the end), peak |tracking error|."""
    from motiontool.scope.tune import measure

    t = np.arange(0.0, 1000.0)
    cpos = np.minimum(t, 500.0) * 2          # reaches 1000 at t = 500
    apos = cpos.copy()
    apos[500:] = 1000 + 30 * np.exp(-(t[500:] - 500) / 50)   # overshoot 30, decays
    te = cpos - apos
    overshoot, settling, peak = measure(t, cpos, apos, te, 1000.0, 1.0, band=3.0)
    assert overshoot == pytest.approx(30.0)
    assert settling == pytest.approx(np.ceil(50 * np.log(10)), abs=1)   # 30·e^(-x/50) ≤ 3
    assert peak == pytest.approx(30.0)
    ringing = apos.copy()
    ringing[-50:] += 10 * np.sin(t[-50:])
    assert measure(t, cpos, ringing, te, 1000.0, 1.0, band=3.0)[1] is None


def test_fft_finds_the_frequency_and_amplitude_of_a_sine():
    from motiontool.scope.spectrum import amplitude_spectrum

    t = np.arange(0.0, 4000.0, 2.0)                     # 2 ms samples for 4 s
    y = 100 + 25 * np.sin(2 * np.pi * 12.5 * t / 1000)  # 12.5 Hz, amplitude 25, offset 100
    f, a = amplitude_spectrum(t, y)
    assert f[np.argmax(a)] == pytest.approx(12.5, abs=0.25)
    assert a.max() == pytest.approx(25, rel=0.05)
    f2, _ = amplitude_spectrum(t, y, 1000, 2000)
    assert f2[-1] == pytest.approx(250.0, abs=1)          # Nyquist of 2 ms
    with pytest.raises(ValueError, match="at least 8"):
        amplitude_spectrum(t, y, 0, 5)
