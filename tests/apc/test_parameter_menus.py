"""The APC parameter browser's table and file (decision A75).

Table 11-1, seed 004 L8207-8212: "81.06 RS485 port mode … 0 to 255 | 1", "81.12 POS Task scheduling rate …
0: Disable 1: 0.25ms 2: 0.5ms 3: 1ms 4: 2ms 5: 4ms 6: 8ms | 0", "81.42 Pass digital input 0 through to the freeze
counters … 0: Disable 1: Enable | 0". §11.3 L7913: "90.43 Reference encoder source … 0: Drive encoder input …
5: None | 0"; L7919: "90.49 APC Runtime Error ID" (a readout)."""

from __future__ import annotations

import pytest

from motiontool.apc.parameter_menus import MENUS, PARAMETERS, checked, dump, load, parameter


def test_ranges_and_defaults_are_the_manuals_tables():
    p = PARAMETERS
    assert (p["81.06"].low, p["81.06"].high, p["81.06"].default) == (0, 255, "1")
    assert (p["81.12"].low, p["81.12"].high, p["81.12"].default) == (0, 6, "0")
    assert (p["81.42"].low, p["81.42"].high, p["81.42"].default) == (0, 1, "0")
    assert (p["90.43"].low, p["90.43"].high) == (0, 5) and not p["90.43"].read_only
    assert p["90.49"].read_only and p["90.01"].read_only and p["91.06"].read_only
    assert not p["18.11"].printed_range and p["18.11"].high == 2 ** 31 - 1
    assert [title.split()[1] for title, _ in MENUS] == ["1-6", "18", "19", "20", "81", "90", "91"]
    assert {m.menu for _, params in MENUS for m in params} >= {1, 3, 4, 18, 19, 20, 81, 90, 91}


def test_a_typed_value_is_checked_against_the_printed_range():
    assert checked(PARAMETERS["81.12"], " 4 ") == 4
    with pytest.raises(ValueError, match=r"#81.12 .*: 7 is outside 0 .. 6"):
        checked(PARAMETERS["81.12"], "7")
    with pytest.raises(ValueError, match=r"#90.49 .* is read only"):
        checked(PARAMETERS["90.49"], "0")
    with pytest.raises(ValueError, match=r"'1.5' is not a whole number"):
        checked(PARAMETERS["18.11"], "1.5")
    assert parameter("#18.11") is parameter("18.11") is PARAMETERS["18.11"]
    with pytest.raises(ValueError, match="not a parameter of the APC browser"):
        parameter("18.111")


def test_the_file_round_trips_and_a_bad_file_names_its_line():
    text = dump({"18.11": 50, "81.12": 4, "90.01": 123})
    assert text.splitlines()[0] == "motiontool APC parameters 1" and text.endswith("\nend\n")
    assert "90.01" not in text                                          # readouts are not saved
    assert load(text, "f") == {"18.11": 50, "81.12": 4}
    cases = {
        text.replace("81.12 = 4", "81.12 = 9"): "f:3: #81.12 .*9 is outside 0 .. 6",
        text.replace("\nend\n", "\n"): "f:3: the file ends without 'end'",
        text.replace("81.12 = 4", "18.11 = 7"): "f:3: #18.11 is given twice",
        text + "18.12 = 1\n": "f:5: nothing may follow 'end'",
        text.replace("parameters 1", "parameters 2"): "f:1: .*version 2 is newer",
        "": "f:1: not an APC parameter file",
        text.replace("81.12 = 4", "81.12 4"): "f:3: '81.12 4': write menu.par = value",
    }
    for bad, message in cases.items():
        with pytest.raises(ValueError, match=message):
            load(bad, "f")
