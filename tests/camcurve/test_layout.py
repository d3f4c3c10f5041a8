"""Curve array encode/decode (docs/formats/cam-array.md)."""

from __future__ import annotations

import dataclasses

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.camcurve import CURVE_ARRAY_ID, STRUCTURE_VERSION, CurveArrayError, decode, encode
from motiontool.camcurve.layout import H_CI, H_FIP, H_ID, H_STIP, H_VERSION, encode_name
from tests.camcurve.conftest import marker_curve, slavesync_curve, stamping_curve
from tests.camcurve.strategies import curves


def test_stamping_sections(stamping):
    """cam-array-layout.md: "15 + 14 + 2 (1 pair) + 12 (4 fix points) + 41 + 2 + 2 + 2 + 2 = 92"."""
    v = encode(stamping)
    assert v[:3] == [CURVE_ARRAY_ID, STRUCTURE_VERSION, 0]
    assert v[3:7] == encode_name("stamping")
    assert v[7:15] == [15, 29, 31, 43, 84, 86, 88, 90]
    assert v[15:29] == [4000, 3600, 4, 41, 0, 0, 0, 0, 0, 2, 1, 60, 0, 0]
    assert v[31:43] == [0, 0, 0, 1500, 1200, 1, 2500, 2400, 1, 4000, 3600, 0]
    assert v[88:] == [0, 100000, 100000, 0]


def test_marker_start_stop_sections(marker):
    v = encode(marker)
    d = decode(v)
    assert d.start_stop_indices == (0, 0, 10, 15, 25, 30)
    # velocity at 1500 and 2500 (inside the straight section) is 1.2 UU/MU -> 120000
    assert d.start_stop_velocities[3] == 120000 and d.start_stop_velocities[4] == 120000
    assert d.start_path[0] == 0 and d.start_path[-1] == 100000 and len(d.start_path) == 6


def test_curve_without_interpolation_round_trips():
    """DG L3785: "Controllers containing firmware older than MCO 5.00, require interpolation points ... For newer
    controllers, these are no longer necessary" -> InterpolPointNo = 0."""
    curve = dataclasses.replace(marker_curve(), interpolation=False)
    v = encode(curve)
    assert len(v) == 112 - 41
    d = decode(v)
    assert d.interpolation_points == () and set(d.start_stop_indices) == {-1}
    assert d.to_curve(intervals=40) == curve


@settings(max_examples=100, deadline=None)
@given(curves(integral=True, min_points=4))
def test_round_trip(curve):
    v = encode(curve)
    d = decode(v)
    assert d.values() == v
    assert d.to_curve(intervals=curve.intervals, start_gradient=curve.start_gradient,
                      end_gradient=curve.end_gradient) == curve
    assert encode(d.to_curve(intervals=curve.intervals, start_gradient=curve.start_gradient,
                             end_gradient=curve.end_gradient)) == v


@pytest.mark.parametrize(("index", "value"), [
    (H_ID, 0), (H_VERSION, 2), (2, 9), (H_CI, 16), (H_FIP, 30), (H_STIP, 0),
    (15, 0),  # master length
    (17, 3),  # FixPointNo < 4
    (31, 5),  # first fix point not at 0
    (34, 0),  # second fix point not after the first
    (33, 7),  # bad type code
    (89, 200000),  # start path out of range
])
def test_corruptions_name_the_element(index, value):
    v = encode(stamping_curve())
    v[index] = value
    with pytest.raises(CurveArrayError) as info:
        decode(v)
    assert info.value.index == index


def test_wrong_size_and_non_integers():
    v = encode(slavesync_curve())
    with pytest.raises(CurveArrayError) as info:
        decode(v + [0])
    assert info.value.index == 108
    with pytest.raises(CurveArrayError) as info:
        decode(v[:50])
    assert 0 <= info.value.index < 50
    with pytest.raises(CurveArrayError) as info:
        decode(v[:-1] + [0.5])
    assert info.value.index == 107
    with pytest.raises(CurveArrayError):
        decode([])


def test_tangent_without_partner_rejected():
    v = encode(stamping_curve())
    v[42] = 1  # last point's type -> T (no partner); point 3 closes the 1500-2500 line
    with pytest.raises(CurveArrayError) as info:
        decode(v)
    assert info.value.index == 42


@settings(max_examples=300, deadline=None)
@given(st.sampled_from([stamping_curve, marker_curve, slavesync_curve]), st.data())
def test_single_corruption_only_raises_curve_array_error(make, data):
    """Random single-element corruption: either CurveArrayError naming an element, or an array that decodes
    consistently (re-serialises to exactly the same values)."""
    v = encode(make())
    index = data.draw(st.integers(0, len(v) - 1))
    v[index] = data.draw(st.one_of(st.integers(-(2 ** 31), 2 ** 31 - 1), st.integers(-3, 200),
                                   st.sampled_from([v[index] + 1, v[index] - 1, -v[index], 2 ** 40])))
    try:
        d = decode(v)
    except CurveArrayError as exc:
        assert 0 <= exc.index < len(v)
    else:
        assert d.values() == v


@settings(max_examples=200, deadline=None)
@given(st.lists(st.integers(-5, 200), max_size=120))
def test_garbage_only_raises_curve_array_error(values):
    try:
        decode(values)
    except CurveArrayError as exc:
        assert 0 <= exc.index < max(len(values), 1)
