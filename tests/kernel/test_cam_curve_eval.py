"""The kernel's per-tick evaluation of fix-point curves (kernel/cam.py CurveFunction.at): the editor's PPoly, evaluated
for one float with Horner's rule and the piece of the previous call tried first (benchmarks/kernel_rtf.py)."""

from __future__ import annotations

import bisect
import dataclasses

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from motiontool.camcurve import decode, encode, profile
from motiontool.kernel.cam import decode_curve_array
from motiontool.kernel.errors import ControllerError
from tests.camcurve.strategies import curves


def _bisect_horner(fn, x: float) -> float:
    """The evaluation before the piece cache: bisect for the piece (clamped to the pieces), then Horner."""
    j = min(max(bisect.bisect_right(fn.breaks, x) - 1, 0), len(fn.coeffs) - 1)
    dx = x - fn.breaks[j]
    c0, c1, c2, c3, c4, c5 = fn.coeffs[j]
    return ((((c0 * dx + c1) * dx + c2) * dx + c3) * dx + c4) * dx + c5


@settings(max_examples=150, deadline=None)
@given(curves(integral=True, min_points=4), st.lists(st.floats(-0.25, 1.25), min_size=1, max_size=40), st.booleans())
def test_scalar_evaluation_equals_the_ppoly(curve, fractions, walk):
    """For random fix-point curves (all point types) and master positions in any order — a jump to any piece, a
    walk through them, the breakpoints themselves, outside 0..L — the kernel's value is bit for bit the one of a
    fresh bisect, and the editor's PPoly value to 1e-9 relative (CR 3955-3958: fix-point arrays are evaluated from
    the fix points)."""
    values = encode(dataclasses.replace(curve, interpolation=False))
    try:
        fn = decode_curve_array("c", values)
    except ControllerError:  # a curve the editor itself cannot evaluate is error 191, tested elsewhere
        assume(False)
    pp = profile(decode(values).to_curve()).ppoly
    length = float(curve.master_length)
    xs = [f * length for f in fractions] + [float(b) for b in pp.x]
    if walk:
        xs.sort()
    scale = 1.0 + max(abs(float(p.slave)) for p in curve.fix_points)
    for x in xs:
        got = fn.at(x)
        assert got == _bisect_horner(fn, x), x
        assert fn(x) == got
        assert got == pytest.approx(float(pp(x)), rel=1e-9, abs=1e-9 * scale), x


def test_the_cam_step_on_the_curve_commands_the_curve_value_of_every_tick():
    """The CAM step evaluates the curve inline on the piece of the last tick: every tick on the curve the commanded
    position is exactly C + F(M) · k through CurveFunction.periodic (kernel/cam.py module docstring), over several
    master cycles and all pieces of the stamping curve (DG 1435-1494, fix points only as with MCO ≥ 5.00)."""
    from motiontool.aposs.driver import compile_source
    from motiontool.camcurve import Curve, FixPoint
    from motiontool.controller.embedded import EmbeddedLink

    points = (FixPoint(0, 0), FixPoint(1500, 1200, "T"), FixPoint(2500, 2400, "T"), FixPoint(4000, 3600))
    values = encode(Curve("stamping", 4000, points, interpolation=False, intervals=40))
    source = (f"DIM stamping[{len(values)}]\nSETCURVE stamping\nDEFMCPOS 1000\nPOSA CURVEPOS\nPULSACC 100000\n"
              "PULSVEL 37236\nSYNCC 0\nSYNCCSTART 0\nWAITI 8 ON\n")
    link = EmbeddedLink()
    link.call("restore_arrays", arrays=[{"name": "stamping", "values": values}])
    for key, value in {"SYNCFACTM": 2048, "SYNCFACTS": 55, "POSFACT_Z": 25, "POSFACT_N": 9, "ENCODER": 500,
                       "FFVEL": 1000, "DFLTVEL": 100, "DFLTACC": 100}.items():
        link.write_parameter(key, value)
    link.download(compile_source(source, "cam.m").image.to_bytes())
    link.start()
    ctl = link.service.controller
    on_curve = 0
    for _ in range(4000):
        link.advance(1)
        motion = ctl.axis.sync
        if ctl.axis.mode == "cam" and motion.state == "curve" and motion.locked:
            on_curve += 1
            m = motion.cam.master_position()
            assert ctl.axis.profile.position == motion.base + motion.cam.curve.periodic(m) * motion.k
    assert on_curve > 2000 and motion.cycles_done >= 2 and not ctl.error
