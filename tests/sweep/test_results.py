"""Reading a finished sweep back (the IDE's sweep view, issue 30 item 2): the CSV of docs/sweep.md "The CSV"."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.sweep.results import ResultsError, parse_results, read_results

DOC = """point,32-60,32-61,max(abs(TRACKERR)),"settle_time(APOS, 204800, 10)",error
1,20,0,2509,nan,
2,20,50,2637,4999,
4,80,50,,,KPROP=80: error 183: Invalid argument
5,80,200,717,4999,
"""


def test_the_documented_csv_with_a_failed_point_and_a_gap():
    r = parse_results(DOC)
    assert r.keys == ["32-60", "32-61"]
    assert r.measures == ["max(abs(TRACKERR))", "settle_time(APOS, 204800, 10)"]
    assert r.numbers == [1, 2, 4, 5] and r.failed == 1
    assert r.points.tolist() == [[20, 0], [20, 50], [80, 50], [80, 200]]
    assert r.values[0, 0] == 2509 and math.isnan(r.values[0, 1]) and np.isnan(r.values[2]).all()
    xs, ys, grid = r.grid(0)
    assert xs.tolist() == [20, 80] and ys.tolist() == [0, 50, 200]
    assert grid[0, 0] == 2509 and grid[0, 1] == 2637 and math.isnan(grid[0, 2]) and grid[1, 2] == 717
    assert math.isnan(grid[1, 1])               # the failed point
    assert r.row_of(4) == 2


def test_a_line_over_one_parameter_is_sorted_by_it():
    r = parse_results("point,KPROP,max(APOS),error\n1,30,5,\n2,10,7,\n3,20,6,\n")
    x, y = r.line(0)
    assert x.tolist() == [10, 20, 30] and y.tolist() == [7, 6, 5]


@pytest.mark.parametrize(("text", "message"), [
    ("", "line 1: not a sweep's CSV"),
    ("a,b\n", "line 1: not a sweep's CSV"),
    ("point,max(APOS),error\n", "line 1: expected the parameters, then the measures"),
    ("point,KPROP,error\n", "line 1: expected the parameters, then the measures"),
    ("point,KPROP,max(APOS),error\n1,10,5\n", "line 2: 3 columns, the header has 4"),
    ("point,KPROP,max(APOS),error\n1,ten,5,\n", "line 2, column 2: 'ten' is not a whole number"),
    ("point,KPROP,max(APOS),error\n1,10,5,\n\n1,20,6,\n", "point 1 appears twice"),
    ("point,KPROP,max(APOS),error\n1,10,five,\n", "line 2, column 3: 'five' is not a number"),
])
def test_a_file_that_is_no_sweep_is_refused_naming_the_place(text, message):
    with pytest.raises(ResultsError, match="^sweep.csv") as info:
        parse_results(text)
    assert message in str(info.value)


def test_a_file_is_read_bounded_and_binary_is_refused(tmp_path):
    path = tmp_path / "s.csv"
    path.write_bytes(b"point,KPROP,max(APOS),error\n1,10,\xff,\n")
    with pytest.raises(ResultsError, match=r"s.csv: not UTF-8 text \(byte 33\)"):
        read_results(path)


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet="point,KPROP()max\"error0123456789.-n\n a", max_size=200))
def test_any_text_is_read_or_refused_with_a_results_error(text):
    try:
        r = parse_results(text)
    except ResultsError:
        return
    assert r.points.shape == (len(r.numbers), len(r.keys)) and r.values.shape == (len(r.numbers), len(r.measures))
