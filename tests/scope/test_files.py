"""Oscilloscope files: .zbo (golden file, round trip, fuzz), old Testrun .txt, CSV export."""

import contextlib
import json
import random
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.scope import zbo
from motiontool.scope.curves import Curve, Group, Scaling, Scope, Source
from motiontool.scope.derived import DerivedSpec
from motiontool.scope.export import export_csv, export_csv_text
from motiontool.scope.testrun import BadTestrunFile, NotTestrun, parse_testrun, read_testrun

DATA = Path(__file__).parent / "data"


def example_scope() -> Scope:
    s = Scope("free_run")
    s.add_group(Group("Test Group (Free Run)", interval_ms=2))
    a = s.add_curve(Curve("1: APOS", Source(method="free_run", signal="APOS", group="Test Group (Free Run)"),
                          unit="UU"))
    a.buffer.extend([0, 2, 4, 6], [0, 10, 30, 60])
    b = s.add_curve(Curve("1: CPOS", Source(method="free_run", signal="CPOS", group="Test Group (Free Run)"),
                          unit="UU", scaling=Scaling(0, 0.1)))
    b.buffer.extend([0, 2, 4, 6], [0, 12, 32, 62])
    b.axis.share = "1: APOS"
    b.range_high = 4900.0
    d = s.add_curve(Curve("APOS - CPOS", Source(method="derived", controller=None,
                                                derived=DerivedSpec("difference", "1: APOS", "1: CPOS").to_dict())))
    d.smoothing = 2
    s.cursors = [2.0, 6.0]
    s.pauses = [4.0]
    return s


def test_golden_file_reads_and_writes_byte_identically(tmp_path):
    """ide-spec 7.7: versioned JSON with the configuration and the data (docs/formats/zbo.md)."""
    golden = DATA / "golden.zbo"
    text = golden.read_text(encoding="utf-8")
    assert zbo.dumps(example_scope()) == text
    scope = zbo.load(golden)
    assert [c.name for c in scope.curves] == ["1: APOS", "1: CPOS", "APOS - CPOS"]
    assert list(scope.curve("1: CPOS").raw()[1]) == [0, 12, 32, 62]
    assert scope.curve("1: CPOS").scaling == Scaling(0.0, 0.1) and scope.curve("1: CPOS").axis.share == "1: APOS"
    assert scope.cursors == [2.0, 6.0] and scope.group("Test Group (Free Run)").interval_ms == 2
    zbo.save(scope, tmp_path / "t.zbo")
    assert (tmp_path / "t.zbo").read_text(encoding="utf-8") == text


def test_save_without_data_is_a_template(tmp_path):
    """DG 5353-5355: "Save without Data" keeps all curve definitions and settings but no recorded data."""
    zbo.save(example_scope(), tmp_path / "t.zbo", with_data=False)
    scope = zbo.load(tmp_path / "t.zbo")
    assert len(scope.curves) == 3 and all(len(c.buffer) == 0 for c in scope.curves)


def test_large_regular_data_is_compact(tmp_path):
    s = Scope("single_shot")
    c = s.add_curve(Curve("x"))
    c.buffer.set_capacity(100_000)
    c.buffer.extend(np.arange(100_000.0), np.round(np.sin(np.arange(100_000) / 500) * 1000))
    zbo.save(s, tmp_path / "big.zbo")
    assert (tmp_path / "big.zbo").stat().st_size < 100_000 * 16 * 0.5
    assert np.array_equal(zbo.load(tmp_path / "big.zbo").curve("x").raw()[1], c.raw()[1])


@pytest.mark.parametrize("edit, message", [
    (lambda d: d.update(version=zbo.VERSION + 1), "newer than this motiontool reads"),
    (lambda d: d.update(format="x"), "not an oscilloscope file"),
    (lambda d: d.update(variant="bogus"), "variant: 'bogus'"),
    (lambda d: d["curves"][1]["axis"].update(min_height="big"), r"curves\[1\].axis.min_height: expected float"),
    (lambda d: d["curves"][0]["data"].update(count=5), r"curves\[0\].data.time_ms: 4 values, 'count' says 5"),
    (lambda d: d["curves"][0]["data"].update(values="!!"), r"curves\[0\].data.values: not f8le"),
    (lambda d: d["curves"][2].update(name="1: APOS"), "appears twice"),
    (lambda d: d["curves"][0].update(colr="#fff"), r"curves\[0\].colr: unknown key"),
    (lambda d: d["groups"][0].update(controller=True), r"groups\[0\].controller: expected int"),
])
def test_defects_name_the_place(edit, message):
    doc = json.loads(zbo.dumps(example_scope()))
    edit(doc)
    with pytest.raises(zbo.ZboError, match=message):
        zbo.loads(json.dumps(doc), "t.zbo")
    with pytest.raises(zbo.ZboError, match=r"t.zbo:3:\d+: not JSON"):
        zbo.loads('{\n "format": \n', "t.zbo")


def _mutate(text: str, rng: random.Random) -> str:
    chars = list(text)
    for _ in range(rng.randint(1, 6)):
        i = rng.randrange(len(chars))
        op = rng.random()
        if op < 0.4:
            chars[i] = rng.choice('{}[]",:0123456789aeEnull-+. \n\\')
        elif op < 0.7:
            del chars[i]
        else:
            chars.insert(i, rng.choice('{}[]",:0-9e.truefalsenull'))
    return "".join(chars)


def test_fuzz_the_zbo_reader_only_ever_raises_zbo_error():
    """Readers are fuzzed: any mutation of a valid file either loads or raises ZboError, nothing else."""
    text = zbo.dumps(example_scope())
    rng = random.Random(8)
    loaded = 0
    for _ in range(3000):
        try:
            zbo.loads(_mutate(text, rng), "f.zbo")
            loaded += 1
        except zbo.ZboError:
            pass
    assert loaded < 3000


@settings(max_examples=200, deadline=None)
@given(st.recursive(st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=5),
                    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner,
                                                                                max_size=4), max_leaves=20))
def test_fuzz_arbitrary_json_values(value):
    for doc in (value, {"format": zbo.MAGIC, "version": 1, "variant": "tune", "curves": value},
                {"format": zbo.MAGIC, "version": 1, "variant": "tune", "curves": [value]}):
        with contextlib.suppress(zbo.ZboError):
            zbo.loads(json.dumps(doc))


TESTRUN = """APOSS Testrun
Program: tune.m
Interval: 2 ms

Time\tCPOS\tAPOS
0\t0\t0
2\t10\t8
4\t30\t27
"""


def test_old_testrun_file_opens_in_a_testsetp_scope_without_controller(tmp_path):
    """DG 5357-5376: a recognised file opens in a TESTSETP scope; Status, Controller and Interface are empty;
    the original test parameters appear under Properties → Source."""
    scope = parse_testrun(TESTRUN, "old.txt")
    assert scope.variant == "testsetp"
    assert [c.name for c in scope.curves] == ["CPOS", "APOS"]
    apos = scope.curve("APOS")
    assert list(apos.raw()[0]) == [0, 2, 4] and list(apos.raw()[1]) == [0, 8, 27]
    assert apos.source.controller is None and apos.source.info["Program"] == "tune.m"
    zbo.save(scope, tmp_path / "old.zbo")   # "can then be resaved as a normal Oscilloscope .zbo file"
    assert zbo.load(tmp_path / "old.zbo").curve("APOS").source.info["Interval"] == "2 ms"
    no_time = parse_testrun("testrun\nInterval = 5\nA;B\n1;2\n3;4\n")
    assert list(no_time.curve("B").raw()[0]) == [0, 5]
    (tmp_path / "r.txt").write_text(TESTRUN)
    assert len(read_testrun(tmp_path / "r.txt").curves) == 2


def test_unrecognised_or_broken_testrun_files():
    """DG 5366-5368: "If APOSS does not recognize the file … it will be opened in a normal APOSS Window"."""
    with pytest.raises(NotTestrun):
        parse_testrun("PRINT 1\n")
    with pytest.raises(BadTestrunFile, match="old.txt:9: 2 values, the header .line 5. names 3 columns"):
        parse_testrun(TESTRUN + "6\t1\n", "old.txt")
    with pytest.raises(BadTestrunFile, match="old.txt:7: 'x' is not a number"):
        parse_testrun(TESTRUN.replace("2\t10\t8", "2\tx\t8"), "old.txt")
    with pytest.raises(BadTestrunFile, match="time goes backwards"):
        parse_testrun(TESTRUN + "1\t1\t1\n", "old.txt")


def test_fuzz_the_testrun_reader():
    rng = random.Random(55)
    for _ in range(2000):
        with contextlib.suppress(NotTestrun, BadTestrunFile):
            parse_testrun(_mutate(TESTRUN, rng), "f.txt")


def test_csv_export_layout(tmp_path):
    """DG 5891-5905: row 1 names each followed by an empty cell, row 2 X,Y pairs, group columns empty."""
    s = example_scope()
    text = export_csv_text(s)
    lines = text.splitlines()
    assert lines[0] == "Test Group (Free Run),,1: APOS,,1: CPOS,,Other Curves,,APOS - CPOS,"
    assert lines[1] == "X,Y," * 4 + "X,Y"
    assert lines[3] == ",,2,10,2,1.2000000000000002,,,,"   # scaling applied, derived curve has no data here
    export_csv(s, tmp_path / "t.csv")
    assert (tmp_path / "t.csv").read_text() == text


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.text(min_size=1, max_size=12).filter(str.strip),
                          st.lists(st.floats(allow_nan=False, width=64), max_size=50),
                          st.sampled_from(["lines", "values", "spline"]),
                          st.one_of(st.none(), st.floats(-1e6, 1e6))), max_size=5,
                unique_by=lambda c: c[0]))
def test_zbo_round_trip_is_exact(curves):
    s = Scope("polling")
    for name, values, interpolation, high in curves:
        c = s.add_curve(Curve(name, Source(method="polled", signal="APOS"), interpolation=interpolation))
        c.name = name
        c.range_high = high
        c.buffer.extend(np.arange(len(values), dtype=float) * 0.5, values)
    again = zbo.loads(zbo.dumps(s))
    assert zbo.dumps(again) == zbo.dumps(s)
    for a, b in zip(s.curves, again.curves, strict=True):
        assert a.name == b.name and np.array_equal(a.raw()[1], b.raw()[1])
