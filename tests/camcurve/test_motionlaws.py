"""VDI 2143 motion laws (issue 6 item 5, decisions C10-C11): the normalised laws, their textbook coefficients, and
law segments in the profile, the controller array and the kernel's evaluation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.camcurve import (
    Curve,
    CurveError,
    CurveType,
    FixPoint,
    curve_info,
    decode,
    encode,
    profile,
    segment_kinds,
)
from motiontool.camcurve.model import LAW_TYPES
from motiontool.camcurve.motionlaws import LAWS, segment

# Textbook peak coefficients Cv = max s', Ca = max |s''| (rise of 1 over a period of 1).  Checked against:
# 3-4-5: s' = 30u²(1-u)² → 30/16 = 1.875, s'' peak 10/√3 = 5.7735 at u = (3-√3)/6;  cycloid: 2 and 2π;
# simple harmonic: π/2 and π²/2;  modified sine: Cv 1.76, Ca 5.53, Cj 69.47 (mechdesigner.support,
# "Modified-Sinusoid Motion-Law");  modified trapezoid: 2 and 4.888 (quarter sine to 1/8, constant to 3/8, half
# cosine to 5/8, constant to 7/8, quarter cosine to 1 — SolidWorks "Defining a Modified Trapezoid Profile").
TEXTBOOK = {"P345": ("1.875", "5.774"), "CYCL": ("2.000", "6.283"), "MSIN": ("1.76", "5.53"),
            "MTRAP": ("2.000", "4.888"), "HARM": ("1.571", "4.935")}
law_codes = st.sampled_from(LAW_TYPES)
unit = st.floats(0.0, 1.0)


def test_every_law_type_has_a_law_and_textbook_values():
    assert tuple(LAWS) == LAW_TYPES
    assert set(TEXTBOOK) == set(LAW_TYPES)


@given(law_codes)
def test_rest_to_rest_boundary_values(code):
    law = LAWS[code]
    assert law(0.0) == pytest.approx(0.0, abs=1e-12)
    assert law(1.0) == pytest.approx(1.0, abs=1e-12)
    assert law(0.0, 1) == pytest.approx(0.0, abs=1e-12)
    assert law(1.0, 1) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("code", LAW_TYPES)
def test_textbook_peak_coefficients(code):
    for computed, text in zip((LAWS[code].cv, LAWS[code].ca), TEXTBOOK[code], strict=True):
        decimals = len(text.partition(".")[2])
        assert computed == pytest.approx(float(text), abs=0.5 * 10 ** -decimals)  # to the textbook's precision
    assert LAWS[code](0.5, 1) == pytest.approx(LAWS[code].cv, rel=1e-9)  # symmetric laws peak at the middle


def test_modified_sine_jerk_coefficient():
    assert float(np.max(np.abs(LAWS["MSIN"](np.linspace(0, 1, 8001), 3)))) == pytest.approx(69.47, abs=0.01)


@given(law_codes, unit)
def test_symmetric_and_monotonic(code, u):
    law = LAWS[code]
    assert law(u) + law(1 - u) == pytest.approx(1.0, abs=1e-12)
    assert law(u, 1) >= -1e-12


@settings(max_examples=60)
@given(law_codes, st.floats(0.01, 0.99), st.integers(0, 2))
def test_derivatives_are_consistent(code, u, nu):
    """s', s'', s''' are the derivatives of s, s', s'' (central differences)."""
    law, d = LAWS[code], 1e-6
    numeric = (law(u + d, nu) - law(u - d, nu)) / (2 * d)
    scale = max(1.0, abs(law(u, nu + 1)))
    assert numeric == pytest.approx(law(u, nu + 1), abs=2e-3 * scale)


def test_vectorised():
    u = np.linspace(0, 1, 11)
    for law in LAWS.values():
        assert law(u).shape == (11,)
        assert isinstance(law(0.3), float)


# -- law segments in a curve ------------------------------------------------------------------------------------------
def dwell_rise_dwell_return(rise="CYCL", ret="MSIN", interpolation=True) -> Curve:
    pts = (FixPoint(0, 0), FixPoint(900, 0, "P345"), FixPoint(1800, 1000, rise), FixPoint(2700, 1000, "P345"),
           FixPoint(3600, 0, ret))
    return Curve("drdr", 3600, pts, interpolation=interpolation, intervals=36)


def test_law_point_shapes_the_segment_ending_there():
    assert segment_kinds(["C", "C", "CYCL", "C"]) == ["spline", "law", "spline"]
    assert segment_kinds(["C", "P345", "HARM"]) == ["law", "law"]
    assert segment_kinds(["T", "T", "MTRAP", "C"]) == ["line", "law", "spline"]


@pytest.mark.parametrize("types, words", [(["CYCL", "C"], "first point"), (["T", "CYCL", "C"], "tangent"),
                                          (["T", "CZ", "CYCL", "T", "T"], "trapezoid")])
def test_law_point_misplaced(types, words):
    with pytest.raises(CurveError, match=words):
        segment_kinds(types)


@pytest.mark.parametrize("code", LAW_TYPES)
def test_profile_follows_the_law(code):
    curve = dwell_rise_dwell_return(rise=code)
    prof = profile(curve)
    x = np.linspace(900, 1800, 301)[1:-1]  # inside (HARM's acceleration jumps at its ends)
    for nu, tol in ((0, 1e-7), (1, 1e-6), (2, 1e-4)):  # relative to the peak (decision C11)
        expected = segment(code, 900, 1800, 0, 1000, x, nu)
        assert np.max(np.abs(prof._eval(x, nu, False) - expected)) <= tol * np.max(np.abs(expected))
    info = curve_info(curve)
    assert info.max_velocity == pytest.approx(max(LAWS[code].cv, LAWS["MSIN"].cv) * 1000 / 900, rel=1e-6)


def test_dwells_stay_flat_and_joints_are_at_rest():
    prof = profile(dwell_rise_dwell_return())
    assert np.allclose(prof.slave(np.linspace(0, 900, 50)), 0.0, atol=1e-9)
    assert np.allclose(prof.slave(np.linspace(1800, 2700, 50)), 1000.0, atol=1e-9)
    assert np.allclose(prof.velocity([900, 1800, 2700, 3600 - 1e-9]), 0.0, atol=1e-9)


def test_spline_neighbours_meet_a_law_at_rest():
    curve = Curve("mix", 4000, (FixPoint(0, 0), FixPoint(1000, 500), FixPoint(2000, 1500, "HARM"),
                                FixPoint(3000, 1700), FixPoint(4000, 2000)), intervals=40)
    prof = profile(curve)
    for x in (1000, 2000):
        assert prof.velocity(x - 1e-7) == pytest.approx(0.0, abs=1e-5)
        assert prof.velocity(x + 1e-7) == pytest.approx(0.0, abs=1e-5)


@pytest.mark.parametrize("interpolation", [True, False])
def test_array_carries_the_law(interpolation):
    """Fix-point-only arrays store the law as type codes 4..8 (docs/formats/cam-array.md), so the kernel's
    SETCURVE rebuilds the same profile; arrays with interpolation points are sampled from the law profile."""
    curve = dwell_rise_dwell_return(interpolation=interpolation)
    decoded = decode(encode(curve))
    assert [p.type for p in decoded.fix_points] == [p.type for p in curve.fix_points]
    if interpolation:
        x = np.arange(37) * 100.0
        assert list(decoded.interpolation_points) == [int(math.floor(v + 0.5)) for v in profile(curve).slave(x, False)]
    else:
        assert profile(decoded.to_curve()).slave(1350.0) == pytest.approx(500.0, abs=1e-6)


def test_kernel_follows_the_law():
    from motiontool.kernel.cam import decode_curve_array

    curve = dwell_rise_dwell_return(rise="MTRAP", interpolation=False)
    f = decode_curve_array("drdr", encode(curve))
    for x in (1000.0, 1125.0, 1350.0, 1700.0, 3000.0):
        assert f(x) == pytest.approx(profile(curve).slave(x), abs=1e-6)
    assert f(1125.0) == pytest.approx(1000 * LAWS["MTRAP"](0.25), abs=1e-5)


@st.composite
def law_curves(draw) -> Curve:
    """Curves of C and law points (the first point C), integral positions on a 10-MU grid; at least 4 points (the
    controller array's minimum)."""
    n = draw(st.integers(4, 8))
    types = ["C"] + [draw(st.sampled_from(("C", *LAW_TYPES))) for _ in range(n - 1)]
    cells = sorted(draw(st.sets(st.integers(1, 59), min_size=n - 2, max_size=n - 2)))
    masters = [0] + [10 * c for c in cells] + [600]
    slaves = [draw(st.integers(-500, 500)) for _ in range(n)]
    curve_type = draw(st.sampled_from(list(CurveType)))
    return Curve("laws", 600, tuple(FixPoint(m, s, t) for m, s, t in zip(masters, slaves, types, strict=True)),
                 intervals=60, curve_type=curve_type, interpolation=draw(st.booleans()))


@settings(max_examples=60, deadline=None)
@given(law_curves())
def test_law_curves_pass_their_points_with_continuous_velocity(curve):
    prof = profile(curve)
    xs = np.array([p.master for p in curve.fix_points], dtype=float)
    assert np.allclose(prof.slave(xs, periodic=False), [p.slave for p in curve.fix_points], atol=1e-6)
    kinds = curve.segment_kinds
    for k in range(1, len(xs) - 1):
        left, right = prof.velocity(xs[k] - 1e-7, False), prof.velocity(xs[k] + 1e-7, False)
        assert left == pytest.approx(right, abs=1e-3 * (1 + abs(left)))
        if kinds[k - 1] == "law" or kinds[k] == "law":
            assert left == pytest.approx(0.0, abs=1e-3)
    decoded = decode(encode(curve))
    assert decoded.to_curve(curve.intervals, curve.start_gradient, curve.end_gradient) == curve
