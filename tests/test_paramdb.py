"""Tests of the MCO 305 parameter database (resources/parameters/mco305.csv) and its loader.

Seed citations "DG n" are line numbers of the MCO 305 Design Guide OCR text (seed 000_de8489130b22ed63).
"""

import csv
from pathlib import Path

import pytest

from motiontool.paramdb import COLUMNS, Parameter, ParameterDatabase, ParameterError, database

CSV_PATH = Path(__file__).resolve().parents[1] / "resources" / "parameters" / "mco305.csv"


@pytest.fixture(scope="module")
def db() -> ParameterDatabase:
    return ParameterDatabase.load(CSV_PATH)


def test_file_is_plain_csv_with_exact_header():
    with CSV_PATH.open(encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    assert tuple(rows[0]) == COLUMNS
    assert all(len(row) == len(COLUMNS) for row in rows)
    assert len(rows) - 1 >= 262


def test_row_count_and_groups(db):
    assert len(db) >= 262
    assert len(db.group("19")) == 100
    assert {p.number[:2] for p in db} == {"19", "32", "33", "34"}
    numbers = [p.index for p in db]
    assert numbers == sorted(numbers)


def test_default_database_is_cached_and_complete():
    assert database() is database()
    assert len(database()) == len(ParameterDatabase.load(CSV_PATH))


@pytest.mark.parametrize("key", ["32-60", "3260", 3260, "KPROP", "kprop", " Kprop "])
def test_kprop_lookup_by_every_key_form(db, key):
    """DG 11164: '32-60	KPROP	Proportional Factor	30	TRUE	2 set-ups	0	Uint32';
    DG 8645: '0 - 100000 \\* 30'."""
    p = db.get(key)
    assert (p.number, p.index, p.name) == ("32-60", 3260, "KPROP")
    assert (p.default, p.minimum, p.maximum) == (30, 0, 100000)
    assert p.conversion_index == 0 and p.data_type == "Uint32" and p.changes_during_operation
    assert p.label == "32-60 KPROP"
    assert key in db


def test_format_line_exact(db):
    assert db.get("32-60").format_line() == "32-60 KPROP 30 [0..100000] Proportional Factor"
    assert db.get(1900).format_line().startswith("19-00 - 0 [-2147483648..2147483647] ")
    assert db.get("RAMPMIN").format_line() == "32-81 RAMPMIN 1.000 [0.001..3600.000] Shortest Ramp"


@pytest.mark.parametrize(("key", "default", "low", "high"), [
    ("POSERR", 20000, 1, 1073741823),   # DG 8756: '1 - MLONG [qc]'; DG 8758: '\* 20000'
    ("VELMAX", 1500, 1, 100000),        # DG 8945: '1 - 100000 [RPM]'; DG 8947: '\* 1500'
    ("VELRES", 100, 1, 10000),          # DG 11183: '32-83	VELRES	Velocity Resolution	100'
    ("DFLTVEL", 50, 1, 10000),          # DG 11184: '32-84	DFLTVEL	Default Velocity	50'
    ("DFLTACC", 50, 1, 10000),          # DG 11185: '32-85	DFLTACC	Default Acceleration	50'
    ("TESTWIN", 0, 0, 10000),           # DG 10301: '0 – 10000 [qc]'; DG 11245: '...	0 qc'
    ("NEGLIMIT", -500000, -1073741824, 1073741823),  # DG 10145: '* -500000'
    ("PRGPAR", -1, -1, 127),            # DG 10671: '-1 - 1	127	* -1' (OCR for '-1 - 127 * -1')
])
def test_known_defaults_and_ranges(db, key, default, low, high):
    """DG 220: 'An upper or lower limit for many parameters: -MLONG = -1,073,741,824
    MLONG = 1,073,741,823'."""
    p = db.get(key)
    assert (p.default, p.minimum, p.maximum) == (default, low, high)
    assert type(p.default) is int


def test_rampmin_is_scaled_seconds(db):
    """DG 8965: '0.001 - 3600.000 [s]'; DG 8967: '\\* 1.000'."""
    p = db.get("32-81")
    assert (p.default, p.minimum, p.maximum, p.unit) == (1.0, 0.001, 3600.0, "s")
    assert not p.integral and p.conversion_index == -3
    assert p.validate("0.5") == 0.5
    assert p.validate(1.23456) == 1.235


def test_every_default_within_range_and_options(db):
    for p in db:
        assert p.minimum <= p.default <= p.maximum, p.label
        if p.options:
            assert p.default in p.options, p.label
            assert (min(p.options), max(p.options)) == (p.minimum, p.maximum), p.label
        assert p.validate(p.default) == p.default, p.label


def test_options_are_clean(db):
    for p in db:
        for number, text in p.options.items():
            assert isinstance(number, int) and text and "|" not in text and "=" not in text, p.label


def test_iomode_default_is_output(db):
    """DG 10503: '* Output	[1]' beats the list's DG 11257: '33-60	IOMODE	...	[0] Output'."""
    p = db.get("IOMODE")
    assert p.default == 1 and p.options[1].startswith("Output")
    assert not p.changes_during_operation


def test_errcond_options(db):
    """DG 10738: 'Jumps to error routine without automatic MOTOR OFF	[5]' (there is no option 4)."""
    assert sorted(db.get("ERRCOND").options) == [0, 1, 2, 3, 5]


def test_validate_accepts_and_converts(db):
    assert db.validate("KPROP", 100000) == 100000
    assert db.validate("kprop", "250") == 250
    assert type(db.validate(3260, 40.0)) is int
    assert db.validate("33-83", 5) == 5


@pytest.mark.parametrize(("key", "value", "fragment"), [
    ("KPROP", 200000, "32-60 KPROP: 200000 is outside 0..100000"),
    ("KPROP", -1, "32-60 KPROP: -1 is outside 0..100000"),
    ("ERRCOND", 4, "33-83 ERRCOND: 4 is not one of the options"),
    ("33-60", 2, "33-60 IOMODE: 2 is not one of the options"),
    ("KPROP", "abc", "32-60 KPROP: 'abc' is not a number"),
    ("KPROP", None, "32-60 KPROP: None is not a number"),
    ("KPROP", True, "32-60 KPROP: True is not a number"),
    ("KPROP", 1.5, "32-60 KPROP: 1.5 is not an integer"),
    ("RAMPMIN", 0.0001, "32-81 RAMPMIN: 0.0001 is outside 0.001..3600.000"),
    ("32-14", 0, "32-14: 0 is outside 1..127"),
])
def test_validate_refuses_with_number_and_name(db, key, value, fragment):
    with pytest.raises(ParameterError) as info:
        db.validate(key, value)
    assert fragment in str(info.value)
    assert isinstance(info.value, ValueError)


@pytest.mark.parametrize("key", ["XYZ", "32-99", 9999, "", "32-6"])
def test_unknown_parameter(db, key):
    with pytest.raises(ParameterError, match="unknown parameter"):
        db.get(key)
    assert key not in db


def test_unknown_parameter_message(db):
    with pytest.raises(ParameterError) as info:
        db.get("XYZ")
    assert str(info.value) == "unknown parameter 'XYZ'"


def test_find(db):
    assert [p.name for p in db.find("jerk")] == ["JERKMIN", "JERKMIN2", "JERKMIN3", "JERKMIN4"]
    assert db.get("KPROP") in db.find("proportional")
    assert [p.number for p in db.find("kprop")] == ["32-60"]
    assert [p.number for p in db.find("33-8")] == ["33-80", "33-81", "33-82", "33-83", "33-84", "33-85"]
    assert db.find("no such text anywhere") == []


def test_group(db):
    assert [p.name for p in db.group("32-6")][:3] == ["KPROP", "KDER", "KINT"]
    assert [p.number for p in db.group("32-60")] == ["32-60"]
    assert db.group("32-6*") == db.group("32-6")
    assert len(db.group("32")) + len(db.group("33")) + len(db.group("34")) + 100 == len(db)
    assert all(p.read_only for p in db.group("34"))
    assert not db.get("KPROP").read_only and db.get("1990").read_only


def test_names_are_unique_code_names(db):
    names = [p.name for p in db if p.name]
    assert len(names) == len(set(names))
    assert db.get("REGWMAX").number == "32-71"
    assert db.get("ENCODERDATLEN").number == "32-05"
    assert db.get("I_FUNCTION_1").number == "33-50"


def test_parameter_is_frozen(db):
    p = db.get("KPROP")
    with pytest.raises(AttributeError):
        p.default = 1  # type: ignore[misc]
    assert isinstance(p, Parameter)


def _write(tmp_path: Path, lines: list[str]) -> Path:
    path = tmp_path / "bad.csv"
    path.write_text("\n".join([",".join(COLUMNS), *lines]) + "\n", encoding="utf-8")
    return path


GOOD = "32-60,KPROP,Proportional Factor,32-6* PID,30,0,100000,,,0,Uint32,TRUE,DG 8638-8653"


def test_small_valid_file_loads(tmp_path):
    loaded = ParameterDatabase.load(_write(tmp_path, [GOOD]))
    assert len(loaded) == 1 and loaded.get("KPROP").default == 30


@pytest.mark.parametrize(("bad", "reason"), [
    (GOOD.replace(",30,", ",abc,"), "default 'abc' is not a number"),
    (GOOD.replace(",30,", ",200000,"), "200000 is outside 0..100000"),
    (GOOD.replace(",,,0,", ",,0=Off|1=On,0,"), "30 is not one of the options"),
    (GOOD.replace(",,,0,", ",,0 Off,0,"), "option '0 Off' is not like '0=Off'"),
    (GOOD.replace("32-60,", "3260,"), "number '3260' is not like '32-60'"),
    (GOOD.replace(",Uint32,", ",Word,"), "data_type 'Word'"),
    (GOOD.replace(",TRUE,", ",yes,"), "changes_during_operation 'yes'"),
    (GOOD + ",extra", "expected 13 fields"),
])
def test_malformed_csv_names_file_and_line(tmp_path, bad, reason):
    path = _write(tmp_path, [GOOD.replace("32-60,KPROP", "32-61,KDER"), bad])
    with pytest.raises(ParameterError) as info:
        ParameterDatabase.load(path)
    assert f"{path}:3:" in str(info.value)
    assert reason in str(info.value)


def test_duplicate_and_header_errors(tmp_path):
    with pytest.raises(ParameterError, match=r"bad\.csv:3: duplicate parameter 32-60"):
        ParameterDatabase.load(_write(tmp_path, [GOOD, GOOD]))
    path = tmp_path / "header.csv"
    path.write_text("number,name\n32-60,KPROP\n", encoding="utf-8")
    with pytest.raises(ParameterError, match=r"header\.csv:1: header must be"):
        ParameterDatabase.load(path)
    with pytest.raises(ParameterError, match="cannot read"):
        ParameterDatabase.load(tmp_path / "missing.csv")
