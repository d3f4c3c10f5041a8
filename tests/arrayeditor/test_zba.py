"""Array definition files (.zba): the manual's example, strict writer, lenient reader, errors with lines."""

import contextlib
import random

import pytest
from hypothesis import given
from hypothesis import strategies as st

from motiontool.formats.zba import Record, ZbaError, ZbaFile, parse_zba, zba_text

MANUAL_EXAMPLE = """Date,2009:07:27 10:52
Widths, 150, 40, 40, 40, 70, 70, 70, 70, 70, 365
This is a comment line.
User,,130,Height,50,100,10,1000,"Maximum height of any unit",1
User,,131,Width,10,20,5,200,"Maximum width of any unit",1
User, 132, Weight, 5, , 1, 20, "Maximum weight of any unit", 1
User,,135, "Number of units", 3000,,,, "Number of units to process",1
***** Another comment line *****
Group, 0, 0, "Quantity by Country", , , , 0
Array,0,1,Switzerland,5,10,0,5000,"This is the first value in array 0",1
Array,0,2,Germany,5,100,0,5000,"This is the second value in array 0",0
Array,0,3,France,5,50,0,5000,"This is the third value in array 0",0
Array,0,4,Canada,5,1,0,5000,"This is the fourth value in array 0",1
Group, -1, 0, "Other Important Values", , , , , 0
Array,0,8,Extra,123,4,-10000,10000,"This is an extra value in array 0",1
Array, 1, 99, Total, 250, 300, 200, 500, "This is the total", 1
Array, 3, 5, "Test Value", 1, 0, 0, 1, "Test: 0 - No, 1 - Yes", 1
"""


def test_the_manuals_example_reads():
    """DG L4574-4590: the example file, irregular lines included (ide-spec 5.36: the User line without its
    empty Array field, Group lines with fewer trailing fields); comment lines are ignored (DG L4540)."""
    zba = parse_zba(MANUAL_EXAMPLE)
    assert zba.date == "2009:07:27 10:52"
    assert zba.widths == [150, 40, 40, 40, 70, 70, 70, 70, 70, 365]
    assert len(zba.records) == 13
    weight = zba.records[2]
    assert (weight.kind, weight.array, weight.index, weight.name, weight.value, weight.default) == \
        ("User", None, 132, "Weight", 5, None)
    group = zba.records[4]
    assert (group.kind, group.array, group.index, group.name, group.rw) == ("Group", 0, 0, "Quantity by Country",
                                                                          False)
    germany = zba.records[6]
    assert germany.rw is False and germany.maximum == 5000
    assert zba.records[-1].description == "Test: 0 - No, 1 - Yes"


def test_writer_is_strict_and_round_trips():
    """ide-spec 5.36: the writer puts the type and all nine fields on every line, quoting when needed."""
    text = zba_text(parse_zba(MANUAL_EXAMPLE))
    lines = text.splitlines()
    assert lines[2] == 'User,,130,Height,50,100,10,1000,"Maximum height of any unit",1'
    assert lines[4] == 'User,,132,Weight,5,,1,20,"Maximum weight of any unit",1'
    assert lines[6] == 'Group,0,0,"Quantity by Country",,,,,,0'
    assert all(len(line.split(",")) >= 10 for line in lines[2:] if '"' not in line.split(",", 3)[3][:1])
    assert zba_text(parse_zba(text)) == text


@pytest.mark.parametrize(("line", "message"), [
    ("Array,0,x,Name,1,,,,,1", "Index"),
    ("Array,,1,Name,1,,,,,1", "Array"),
    ("Axis,1,3260,KPROP,1,,,,,2", "RW must be 0 or 1"),
    ("User,1,5,Name,1,,,,,1", "must be empty"),
    ("Array,0,1,Name,abc,,,,,1", "Value"),
    ('Array,0,1,"Name,1,,,,,1', "quotes"),
    ("Array,0,1,Name,1,1", "needs 9 fields"),
    ("Date,27.07.2009", "YYYY:MM:DD"),
])
def test_bad_lines_name_their_line(line, message):
    with pytest.raises(ZbaError) as info:
        parse_zba("Date,2009:07:27 10:52\n" + line + "\n")
    assert info.value.line == 2 and message in info.value.message


def test_a_duplicate_item_is_refused():
    with pytest.raises(ZbaError, match="already defined on line 1"):
        parse_zba("Array,0,1,a,1,,,,,1\nArray,0,1,b,2,,,,,1\n")


names = st.text(alphabet=st.characters(blacklist_characters='"\r\n\x85\u2028\u2029\x1c\x1d\x1e\x0b\x0c',
                                       blacklist_categories=("Cs",)), max_size=12).map(str.strip)
numbers = st.none() | st.integers(-2**31, 2**31 - 1)


@given(st.lists(st.builds(Record, st.just("Array"), st.integers(0, 9), st.integers(1, 500), names, numbers,
                          numbers, numbers, numbers, names, st.booleans()), max_size=8, unique_by=lambda r: r.key))
def test_round_trip_property(records):
    zba = ZbaFile("2026:11:22 08:30", [100, 40], records)
    assert parse_zba(zba_text(zba)) == zba


def test_fuzzed_files_never_crash():
    rng = random.Random(305)
    for _ in range(2000):
        chars = list(MANUAL_EXAMPLE)
        for _ in range(rng.randint(1, 8)):
            i = rng.randrange(len(chars))
            chars[i] = rng.choice(',;"\n 0123456789-xAG')
        with contextlib.suppress(ZbaError):  # refused with a line is fine; anything else fails the test
            parse_zba("".join(chars))
