"""Measured traces for the CAM editor overlay (decision C14): the `motiontool run --trace` CSV and the
oscilloscope's CSV export, column guesses, errors naming file:line, and the wrap onto the master cycle."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from motiontool.cameditor.trace import TraceError, TraceTable, guess_columns, parse_trace, read_trace, wrap
from motiontool.headless import _write_csv
from motiontool.scope.curves import Curve, Group, Scope, Source
from motiontool.scope.export import export_csv_text


def test_reads_the_file_motiontool_run_writes(tmp_path):
    path = tmp_path / "trace.csv"
    _write_csv(path, ["time_ms", "4230", "APOS", "TRACKERR"], [[0, 0, 0, 0.0], [1, 10, 0.5, 0.1], [2, 20, 2, 0.2]])
    table = read_trace(path)
    assert table.layout == "trace" and table.names == ["4230", "APOS", "TRACKERR"]
    m, s = table.master_slave("4230", "APOS")
    assert m.tolist() == [0, 10, 20] and s.tolist() == [0, 0.5, 2]
    assert guess_columns(table.names) == ("4230", "APOS")


def scope_with(master_times, slave_times) -> Scope:
    s = Scope("free_run")
    s.add_group(Group("Cam", interval_ms=2))
    m = s.add_curve(Curve("1: CMASTERCPOS [4230]", Source(method="free_run", signal="4230", group="Cam")))
    m.buffer.extend(master_times, [10.0 * t for t in master_times])
    a = s.add_curve(Curve("1: APOS", Source(method="free_run", signal="APOS", group="Cam"), unit="UU"))
    a.buffer.extend(slave_times, [t * t for t in slave_times])
    return s


def test_reads_a_scope_export_and_aligns_time_bases():
    text = export_csv_text(scope_with([0, 2, 4, 6, 8], [1, 3, 5]))
    table = parse_trace(text, "scope.csv")
    assert table.layout == "scope" and table.names == ["1: CMASTERCPOS [4230]", "1: APOS"]  # group: heading only
    master, slave = guess_columns(table.names)
    assert (master, slave) == ("1: CMASTERCPOS [4230]", "1: APOS")
    m, s = table.master_slave(master, slave)
    assert m.tolist() == [10, 30, 50] and s.tolist() == [1, 9, 25]  # master interpolated at the slave's times


def test_guess_prefers_the_curve_master_position_and_never_picks_one_column_twice():
    assert guess_columns(["time", "MAPOS", "APOS"]) == ("MAPOS", "APOS")
    assert guess_columns(["APOS - CPOS", "CPOS"]) == (None, "APOS - CPOS")
    assert guess_columns(["X1", "X2"]) == (None, None)


@pytest.mark.parametrize("text, line, words", [
    ("", 1, "empty"),
    ("t,MAPOS,APOS\n1,2,3\n", 1, "time_ms"),
    ("time_ms,APOS\n1,2\n", 1, "two signal columns"),
    ("time_ms,MAPOS,APOS\n0,1,2\n1,2\n", 3, "2 values"),
    ("time_ms,MAPOS,APOS\n0,1,2\n\n1,x,3\n", 4, "'MAPOS': 'x' is not a number"),
    ("time_ms,MAPOS,APOS\n0,1,inf\n", 2, "finite"),
    ("time_ms,MAPOS,MAPOS\n0,1,2\n", 1, "twice"),
    ("time_ms,MAPOS,APOS\n", 1, "no samples"),
    ("A,,B,\nX,Y,X,Y\n0,1,0,\n", 3, "both"),
    ("A,,B,\nX,Y,X,Y\n0,1,,\n", 2, "fewer than two curves"),
])
def test_errors_name_file_and_line(text, line, words):
    with pytest.raises(TraceError) as info:
        parse_trace(text, "m.csv")
    assert info.value.line == line and words in info.value.message
    assert str(info.value).startswith(f"m.csv:{line}: ")


def test_unreadable_files(tmp_path):
    with pytest.raises(TraceError, match="missing.csv"):
        read_trace(tmp_path / "missing.csv")
    path = tmp_path / "bin.csv"
    path.write_bytes(b"time_ms,MAPOS,APOS\n\xff\n")
    with pytest.raises(TraceError) as info:
        read_trace(path)
    assert info.value.line == 2 and "UTF-8" in info.value.message


def test_wrap_takes_the_slave_back_one_slave_cycle_per_master_cycle():
    x, y = wrap([0, 500, 999, 1000, 1500, 2100], [0, 50, 99, 100, 150, 210], 1000, 100)
    gaps = np.isnan(x)
    assert gaps.tolist() == [False, False, False, True, False, False, True, False]
    assert x[~gaps].tolist() == [0, 500, 999, 0, 500, 100]
    assert np.allclose(y[~gaps], [0, 50, 99, 0, 50, 10])


def test_wrap_unwraps_a_master_that_wraps_at_the_cycle():
    """CMASTERCPOS runs 0..L and restarts; the slave of an open curve (slave length 100) keeps counting."""
    x, y = wrap([900, 950, 0, 50, 500, 990, 10], [90, 95, 100, 105, 150, 199, 201], 1000, 100)
    gaps = np.isnan(x)
    assert x[~gaps].tolist() == [900, 950, 0, 50, 500, 990, 10]
    assert np.allclose(y[~gaps], [90, 95, 0, 5, 50, 99, 1])
    assert gaps.sum() == 2


def test_wrap_scales_and_offsets():
    x, y = wrap([0, 10], [0, 4], 100, 0, master_scale=2.0, slave_scale=0.5, slave_offset=1.0)
    assert x.tolist() == [0, 20] and y.tolist() == [-1, 1]


@given(st.lists(st.floats(-1e6, 1e6), min_size=1, max_size=50), st.floats(0.5, 1e4))
def test_wrapped_master_stays_in_the_cycle(masters, length):
    x, _ = wrap(masters, np.zeros(len(masters)), length)
    finite = x[~np.isnan(x)]
    assert len(finite) == len(masters)
    assert ((finite >= 0) & (finite <= length)).all()


def test_the_simulated_controller_follows_a_law_curve(tmp_path):
    """End to end: a fix-point-only array with motion laws (type codes 4..8) runs on the kernel; the recorded
    slave stays within the tracking error of the designed profile (decision C13)."""
    from motiontool.camcurve import profile
    from tests.cameditor.law_trace import law_curve, record_trace

    curve = law_curve()
    record_trace(tmp_path / "t.csv", curve)
    table = read_trace(tmp_path / "t.csv")
    m, s = table.master_slave(*guess_columns(table.names))
    x, y = wrap(m, s, curve.master_length, curve.slave_length)
    ok = ~np.isnan(x)
    assert np.isnan(x).sum() >= 2  # CMASTERCPOS wraps at the cycle: more than two cycles, drawn as strokes
    deviation = np.abs(y[ok] - profile(curve).slave(x[ok]))
    assert np.max(deviation) < 25  # UU, of a 1000 UU rise: the simulated axis' tracking error
    assert np.median(deviation) < 5


def test_a_wrapping_master_on_another_time_base_is_not_interpolated_across_the_wrap():
    """A scope master that counts modulo the cycle (CMASTERCPOS, 3590 -> 10 at the wrap) recorded on other
    times than the slave: with the cycle given it is unwrapped before it is interpolated, so the sample between
    3590 and 10 is 3600 (= 0 of the next cycle), not an invented mid-cycle 1800."""
    table = TraceTable("scope.csv", "scope", {"M": (np.array([0.0, 2.0]), np.array([3590.0, 10.0])),
                                              "S": (np.array([1.0]), np.array([5.0]))})
    assert table.master_slave("M", "S")[0].tolist() == [1800.0]  # without the cycle: plain interpolation
    m, _ = table.master_slave("M", "S", cycle=3600)
    assert m.tolist() == [3600.0]
    x, _ = wrap(m, [5.0], 3600)
    assert x.tolist() == [0.0]
