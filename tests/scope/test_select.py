"""Byte/word/bit selection of stream curves (ide-spec 6.43 "byte selection … bit selection … signed or unsigned"),
written like the APOSS suffixes (aposs-language.md 5.4), through the embedded link and the .zbo file."""

import json
from pathlib import Path

import numpy as np
import pytest

from motiontool.controller.embedded import EmbeddedLink
from motiontool.scope import zbo
from motiontool.scope.acquisition import FreeRun, Polling, SingleShot, default_group, new_curve
from motiontool.scope.curves import Curve, Scope, Source
from motiontool.scope.derived import DerivedSpec
from motiontool.scope.select import apply, canonical, parse_selection, split_signal, with_suffix, without_suffix

DATA = Path(__file__).parent / "data"


def test_suffixes_select_like_aposs():
    """aposs-language 5.4: "`e.b n` byte n (1…4, b1 = least significant), unsigned: 0x027F.b1 = 127, .b2 = 2";
    "`e.w n` word n: 0x0010FFFF.w2 = 16"; "`e.n` bit n of e, 1-based: 7.1 = 1, 7.3 = 1, 7.4 = 0";
    "`e.ub n` / `e.sb n`: 0x1FFFE.ub1 = 254, .sb1 = -2"."""
    assert list(apply("b1", [0x027F])) == [127] and list(apply("b2", [0x027F])) == [2]
    assert list(apply("w2", [0x0010FFFF])) == [16]
    assert list(apply("1", [7, 7, 7])) == [1, 1, 1] and list(apply(".3", [7])) == [1] and list(apply("4", [7])) == [0]
    assert list(apply("b1", [0x1FFFE])) == [254] and list(apply("sb1", [0x1FFFE])) == [-2]
    assert list(apply("sw1", [0xFFFF8000])) == [-32768] and list(apply("w1", [0xFFFF8000])) == [32768]
    assert list(apply("b4", [-1])) == [255] and list(apply("32", [-1])) == [1] and list(apply("32", [1])) == [0]
    assert list(apply("b1", [2.6])) == [3]                       # rounded to the nearest integer first
    y = apply("b1", [np.nan, np.inf, 1e30])
    assert np.isnan(y[0]) and np.isnan(y[1]) and 0 <= y[2] <= 255
    assert list(apply(None, [1.5])) == [1.5]


@pytest.mark.parametrize("text", ["b0", "b5", "w3", "sw0", "0", "33", "x", "b", "sb", ".", "1.5"])
def test_invalid_selections_are_refused(text):
    with pytest.raises(ValueError):
        parse_selection(text)


def test_canonical_forms_and_signal_suffixes():
    assert canonical(".B2") == "b2" and canonical(" SW1 ") == "sw1" and canonical("07") == "7"
    assert canonical("") is None and canonical(None) is None
    assert split_signal("4104.b2") == ("4104", "b2") and split_signal("APOS.3") == ("APOS", "3")
    assert split_signal("0x01250001") == ("0x01250001", None) and split_signal("a[3].sb1") == ("a[3]", "sb1")
    assert split_signal("data.x") == ("data.x", None) and split_signal(".b1") == (".b1", None)
    assert with_suffix("1: REG_STAT [4104]", "b2") == "1: REG_STAT [4104].b2"
    assert without_suffix("1: REG_STAT [4104].b2", "b2") == "1: REG_STAT [4104]"
    assert without_suffix("my name", "b2") == "my name"


def test_curve_name_is_axis_name_index_with_the_suffix():
    """DG 5343-5345 "Axis: Name [Index]", extended by the APOSS suffix of the selection."""
    scope = Scope("free_run")
    group = default_group(scope, "free_run").name
    a = new_curve(scope, "4104.b2", group, "free_run")
    b = new_curve(scope, "APOS", group, "free_run", select="3")
    c = new_curve(scope, "0x01250001", group, "free_run")
    assert (a.name, a.source.signal, a.source.select) == ("1: REG_STAT [4104].b2", "4104", "b2")
    assert (b.name, b.source.signal, b.source.select, b.unit) == ("1: APOS.3", "APOS", "3", "")
    assert (c.name, c.source.select) == ("1: REG_ACTPOS [0x01250001]", None)
    with pytest.raises(ValueError):
        new_curve(scope, "APOS", group, "free_run", select="b9")


def test_free_run_streams_bits_and_bytes_of_the_inputs_word():
    """Digital inputs as bits, bit 0 = input 1 (34-40): INPUTS.3 is input 3, INPUTS.b2 is inputs 9-16."""
    link = EmbeddedLink()
    scope = Scope("free_run")
    group = default_group(scope, "free_run").name
    for signal in ("INPUTS", "INPUTS.3", "INPUTS.b2", "INPUTS.sb2"):
        new_curve(scope, signal, group, "free_run")
    run = FreeRun(scope, link, group, subscribe=True)
    run.start()
    link.advance(100)
    link.call("set_input", number=3, value=1)
    link.call("set_input", number=10, value=1)
    link.call("set_input", number=16, value=1)
    link.advance(100)
    run.stop()
    whole = scope.curve("1: INPUTS").raw()[1]
    bit3 = scope.curve("1: INPUTS.3").raw()[1]
    b2 = scope.curve("1: INPUTS.b2").raw()[1]
    sb2 = scope.curve("1: INPUTS.sb2").raw()[1]
    assert whole.size == bit3.size == b2.size > 150 and run.dropped == 0
    assert set(bit3[:50]) == {0} and set(bit3[-50:]) == {1}
    assert b2[-1] == 0b10000010 == (int(whole[-1]) >> 8) & 0xFF and sb2[-1] == 0b10000010 - 256
    assert np.array_equal(bit3, (whole.astype(int) >> 2) & 1)


def test_the_trigger_sees_the_selected_bit():
    """A trigger on a bit curve fires on the bit's edge (level 0.5), not on the whole word."""
    from motiontool.scope.trigger import Trigger

    link = EmbeddedLink()
    scope = Scope("free_run")
    group = default_group(scope, "free_run").name
    new_curve(scope, "INPUTS.2", group, "free_run")
    run = FreeRun(scope, link, group, subscribe=True)
    run.trigger = ("1: INPUTS.2", Trigger(level=0.5, pre=10, post=40))
    link.call("set_input", number=1, value=1)   # the word changes, bit 2 does not: no trigger
    run.start()
    link.advance(200)
    assert run.running and run.captures == 0
    link.call("set_input", number=2, value=1)
    link.advance(200)
    assert not run.running and run.captures == 1
    y = scope.curve("1: INPUTS.2").raw()[1]
    assert y.size == 50 and set(y[:10]) == {0} and set(y[10:]) == {1}


def test_a_selection_changed_while_free_run_records_applies_to_the_next_packets():
    """ide-spec 6.43: the byte/bit selection is a curve property; changed in Properties while Free Run runs, the
    samples recorded from then on hold the new field (as Polling, which reads it per poll)."""
    link = EmbeddedLink()
    scope = Scope("free_run")
    group = default_group(scope, "free_run").name
    curve = new_curve(scope, "INPUTS", group, "free_run")
    run = FreeRun(scope, link, group, subscribe=True)
    link.call("set_input", number=2, value=1)   # INPUTS = 0b10: bit 1 is 0, bit 2 is 1
    run.start()
    link.advance(100)
    assert set(curve.raw()[1]) == {2}
    curve.source.select = "2"
    curve.buffer.clear()
    link.advance(100)
    assert set(curve.raw()[1]) == {1}


def test_polled_and_single_shot_curves_store_the_selection():
    link = EmbeddedLink()
    scope = Scope("polling")
    new_curve(scope, "INPUTS.b1", "", "polled")
    poll = Polling(scope, link)
    poll.start()
    link.call("set_input", number=8, value=1)
    link.call("set_input", number=9, value=1)
    link.advance(10)
    poll.poll()
    assert list(scope.curve("1: INPUTS.b1").raw()[1]) == [128]
    shot = Scope("single_shot")
    group = default_group(shot, "single_shot")
    group.count = 20
    new_curve(shot, "INPUTS.w1", group.name, "single_shot")
    new_curve(shot, "INPUTS.9", group.name, "single_shot")
    run = SingleShot(shot, link, group.name)
    run.start()
    link.advance(50)
    assert run.stop() == 20
    assert set(shot.curve("1: INPUTS.w1").raw()[1]) == {384} and set(shot.curve("1: INPUTS.9").raw()[1]) == {1}


def _selected_scope() -> Scope:
    s = Scope("free_run")
    group = default_group(s, "free_run").name
    c = new_curve(s, "4104.sb2", group, "free_run")
    c.buffer.extend([0, 1, 2], [-1, 0, 5])
    new_curve(s, "APOS", group, "free_run")
    return s


def test_zbo_writes_version_2_only_for_selections_and_reads_both(tmp_path):
    """docs/formats/zbo.md: version 2 adds source.select; a file without selections is still written as
    version 1 (byte-identical to before, tests/scope/data/golden.zbo), and version-1 files open."""
    old = zbo.load(DATA / "golden.zbo")
    assert all(c.source.select is None for c in old.curves)
    assert json.loads(zbo.dumps(old))["version"] == 1 and '"select"' not in zbo.dumps(old)
    text = zbo.dumps(_selected_scope())
    doc = json.loads(text)
    assert doc["version"] == 2 and doc["curves"][0]["source"]["select"] == "sb2"
    assert "select" not in doc["curves"][1]["source"]
    zbo.save(_selected_scope(), tmp_path / "s.zbo")
    back = zbo.load(tmp_path / "s.zbo")
    assert back.curve("1: REG_STAT [4104].sb2").source.select == "sb2"
    assert list(back.curve("1: REG_STAT [4104].sb2").raw()[1]) == [-1, 0, 5]
    assert (tmp_path / "s.zbo").read_text(encoding="utf-8") == text


@pytest.mark.parametrize("edit, message", [
    (lambda d: d.update(version=1), r"curves\[0\].source.select: needs format version 2 \(file says 1\)"),
    (lambda d: d["curves"][0]["source"].update(select="b7"), r"curves\[0\].source.select: .b7: a 32-bit"),
    (lambda d: d["curves"][0]["source"].update(select=3), r"curves\[0\].source.select: expected str"),
    (lambda d: d.update(version=3), "format version 3 is newer than this motiontool reads"),
])
def test_zbo_selection_defects_name_the_place(edit, message):
    doc = json.loads(zbo.dumps(_selected_scope()))
    edit(doc)
    with pytest.raises(zbo.ZboError, match=message):
        zbo.loads(json.dumps(doc), "t.zbo")


def test_zbo_select_null_is_read_as_the_whole_value():
    doc = json.loads(zbo.dumps(_selected_scope()))
    doc["curves"][0]["source"]["select"] = None
    assert zbo.loads(json.dumps(doc)).curves[0].source.select is None


def test_rename_follows_shares_and_derived_inputs():
    s = Scope("free_run")
    s.add_curve(Curve("a", Source(signal="INPUTS", select="b1")))
    b = s.add_curve(Curve("b"))
    b.axis.share = "a"
    d = s.add_curve(Curve("d", Source(method="derived", derived=DerivedSpec(
        "expression", "a", "b", expression="x + y", variables={"x": "a", "y": "b"}).to_dict())))
    assert s.rename_curve("a", "b") == "b (2)"
    assert b.axis.share == "b (2)" and d.source.derived["base"] == "b (2)"
    assert d.source.derived["variables"] == {"x": "b (2)", "y": "b"}
    assert s.rename_curve("b", "b") == "b"
