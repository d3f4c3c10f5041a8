"""Configuration files (.zbc/.cnf): round trips, refusals with line numbers, parameters."""

from __future__ import annotations

import contextlib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from motiontool.camcurve import Curve, CurveError, FixPoint, element_count
from motiontool.formats.zbc import ArrayEntry, ConfigError, ConfigFile, config_text, read_config, write_config
from tests.camcurve.conftest import marker_curve, slavesync_curve, stamping_curve
from tests.camcurve.strategies import curves


def sample_config() -> ConfigFile:
    config = ConfigFile({"32-60": 30, "19-00": -5, "33-80": 0, "32-06": 262.5})
    config.arrays.append(ArrayEntry("table", [1, 2, 3]))
    for curve in (stamping_curve(), marker_curve(), slavesync_curve()):
        config.add_curve(curve)
    return config


def lines_of(text: str) -> list[str]:
    return text.split("\n")


def line_number(text: str, startswith: str) -> int:
    return next(i for i, line in enumerate(lines_of(text), 1) if line.startswith(startswith))


def test_manual_element_counts():
    config = sample_config()
    assert [len(a.values) for a in config.arrays] == [3, 92, 112, 108]
    assert [a.curve for a in config.arrays] == [None, "stamping", "marker", "slavesync"]


def test_round_trip_byte_identical(tmp_path):
    config = sample_config()
    path = tmp_path / "stamping.zbc"
    write_config(path, config)
    first = path.read_bytes()
    again = read_config(path)
    assert again == config
    write_config(path, again)
    assert path.read_bytes() == first
    assert first.decode().startswith("# motiontool configuration file, format 1\n")


def test_sections_and_keys():
    text = config_text(sample_config())
    assert "[global]\n33-80 PRGPAR = 0\n" in text
    assert "32-60 KPROP = 30" in text and "32-06 ENCODERFREQ = 262.500" in text
    assert "[user]\n19-00 = -5\n" in text
    assert "[array stamping]\nsize = 92\ncurve = stamping\nvalues = " in text
    assert "point = 1500, 1200, T" in text and "pair = 1000, 1500" in text
    assert text.endswith("[end]\n")
    values_line = lines_of(text)[line_number(text, "[array stamping]") + 2]
    assert len(values_line.split()) == 2 + 16


def test_cnf_accepted(tmp_path):
    path = tmp_path / "old.cnf"
    write_config(path, sample_config())
    assert read_config(path).curve("marker") == marker_curve()
    assert read_config(str(path)) == read_config(path.read_text())


def test_add_curve_replaces_in_place():
    config = sample_config()
    shorter = Curve("stamping", 4000, stamping_curve().fix_points, intervals=20)
    config.add_curve(shorter)
    assert [a.name for a in config.arrays] == ["table", "stamping", "marker", "slavesync"]
    assert len(config.arrays[1].values) == element_count(shorter) == 72
    assert config.curve("stamping").intervals == 20
    read_config(config_text(config))
    config.remove_curve("stamping")
    assert config.curve("stamping") is None and config.array("stamping") is None


def test_add_curve_refuses_unencodable():
    with pytest.raises(CurveError, match="fix_points"):
        ConfigFile().add_curve(Curve("two", 100, (FixPoint(0, 0), FixPoint(100, 10)), intervals=10))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(curves(integral=True, min_points=4), max_size=3),
       st.dictionaries(st.sampled_from(["32-60", "32-61", "19-05", "19-89", "33-80"]), st.integers(0, 20)))
def test_round_trip_random(curve_list, params):
    config = ConfigFile(dict(params))
    for k, curve in enumerate(curve_list):
        with contextlib.suppress(CurveError):
            config.add_curve(Curve(**{**curve.__dict__, "name": f"c{k}"}))
    text = config_text(config)
    again = read_config(text)
    assert config_text(again) == text
    assert again.curves == config.curves
    assert again.parameters == config.parameters


# -- refusals --------------------------------------------------------------------------------------------------
GOOD = config_text(sample_config())


def refuse(text: str) -> ConfigError:
    with pytest.raises(ConfigError) as info:
        read_config(text)
    return info.value


def replace_line(text: str, startswith: str, new: str) -> tuple[str, int]:
    number = line_number(text, startswith)
    lines = lines_of(text)
    lines[number - 1] = new
    return "\n".join(lines), number


def test_missing_format_line():
    err = refuse(GOOD.split("\n", 1)[1])
    assert err.line == 1 and "first line" in err.message


def test_newer_format_refused():
    err = refuse(GOOD.replace("format 1\n", "format 4\n", 1))  # 2 (motion laws, C12) and 3 ([fc300], C19) are read
    assert err.line == 1 and "newer" in err.message


def test_truncated_file():
    lines = lines_of(GOOD)
    cut = line_number(GOOD, "[curve marker]") + 3
    err = refuse("\n".join(lines[:cut]) + "\n")
    assert err.line == cut and "truncated" in err.message


def test_truncated_array_names_size_line():
    start = line_number(GOOD, "[array marker]")
    lines = lines_of(GOOD)
    values_end = start + 2 + 7  # 112 values = 7 lines of 16
    text = "\n".join(lines[:values_end - 1] + lines[values_end:])
    err = refuse(text)
    assert err.line == start + 1 and "size = 112 but 96 values" in err.message


def test_parameter_out_of_range_names_parameter():
    text, number = replace_line(GOOD, "32-60 KPROP", "32-60 KPROP = 100001")
    err = refuse(text)
    assert err.line == number and "KPROP" in err.message and "outside" in err.message


def test_unknown_parameter():
    text, number = replace_line(GOOD, "32-60 KPROP", "32-99 = 1")
    err = refuse(text)
    assert err.line == number and "unknown parameter 32-99" in err.message


def test_parameter_in_wrong_section_or_wrong_name():
    text, number = replace_line(GOOD, "33-80 PRGPAR", "32-61 = 1")
    err = refuse(text)
    assert err.line == number and "belongs in [axis]" in err.message
    text, number = replace_line(GOOD, "32-60 KPROP", "32-60 KDER = 1")
    err = refuse(text)
    assert err.line == number and "KPROP" in err.message


def test_bad_value_word():
    number = line_number(GOOD, "[array stamping]") + 3
    lines = lines_of(GOOD)
    lines[number - 1] = lines[number - 1].replace("4000", "4x00", 1)
    err = refuse("\n".join(lines))
    assert err.line == number and "'4x00' is not an integer" in err.message


def test_bad_curve_field_names_line():
    start = line_number(GOOD, "[curve stamping]")
    text = GOOD.replace("point = 2500, 2400, T\npoint = 4000, 3600, C\npair = 0, 0\n\n[curve marker]",
                        "point = 2500, 2400, T\npoint = 2000, 3600, C\npair = 0, 0\n\n[curve marker]", 1)
    err = refuse(text)
    assert err.line == line_number(text, "point = 2000") and "fix_points" in err.message
    lines = lines_of(GOOD)
    lines[start] = "master_length = lots"
    err = refuse("\n".join(lines))
    assert err.line == start + 1 and "master_length" in err.message
    lines = lines_of(GOOD)
    lines[start + 3] = "curve_type = WOBBLY"
    err = refuse("\n".join(lines))
    assert err.line == start + 4 and "curve_type" in err.message


def test_curve_and_array_must_agree():
    start = line_number(GOOD, "[curve stamping]")
    text = GOOD.replace("[curve stamping]\nmaster_length = 4000\nintervals = 40\ninterpolation = yes\n"
                        "curve_type = AVERAGE_GRADIENTS\nslave_stop_position = 0",
                        "[curve stamping]\nmaster_length = 4000\nintervals = 40\ninterpolation = yes\n"
                        "curve_type = AVERAGE_GRADIENTS\nslave_stop_position = 7", 1)
    err = refuse(text)
    assert err.line == start and "differ: slave_stop_position" in err.message


def test_corrupt_curve_array_names_values_line():
    number = line_number(GOOD, "[array stamping]") + 3
    lines = lines_of(GOOD)
    lines[number - 1] = "values = 1 " + lines[number - 1].split(" ", 3)[3]
    err = refuse("\n".join(lines))
    assert err.line == number and "not a valid curve array" in err.message


def test_missing_key_duplicate_and_garbage():
    start = line_number(GOOD, "[curve marker]")
    lines = lines_of(GOOD)
    del lines[start]  # master_length
    err = refuse("\n".join(lines))
    assert err.line == start and "missing key master_length" in err.message
    err = refuse(GOOD.replace("[user]\n", "[user]\nnonsense here\n", 1))
    assert err.line == line_number(GOOD, "[user]") + 1
    err = refuse(GOOD.replace("[user]\n", "[user]\n[global]\n", 1))
    assert err.line == line_number(GOOD, "[user]") + 1 and "twice" in err.message
    err = refuse(GOOD + "[global]\n")
    assert "after the [end]" in err.message


def test_curve_without_array_refused():
    text = GOOD.replace("curve = stamping\n", "", 1)
    err = refuse(text)
    assert err.line == line_number(text, "[curve stamping]") and "no array" in err.message


def test_file_errors(tmp_path):
    path = tmp_path / "bin.zbc"
    path.write_bytes(b"# motiontool configuration file, format 1\n\xff\n")
    with pytest.raises(ConfigError) as info:
        read_config(path)
    assert info.value.line == 2 and str(path) in str(info.value)
    with pytest.raises(ConfigError, match="cannot read"):
        read_config(tmp_path / "missing.zbc")


def test_write_refuses_bad_parameter():
    with pytest.raises(ConfigError, match="KPROP"):
        config_text(ConfigFile({"32-60": -1}))
    with pytest.raises(ConfigError, match="read-only"):
        config_text(ConfigFile({"34-50": 0}))


def test_doc_example_is_current():
    from pathlib import Path

    doc = (Path(__file__).resolve().parents[2] / "docs" / "formats" / "zbc.md").read_text()
    example = doc.split("# motiontool configuration file, format 1\n# see", 2)[1].split("```", 1)[0]
    config = ConfigFile({"32-60": 30, "33-80": 0, "19-00": 5})
    config.add_curve(stamping_curve())
    assert "# motiontool configuration file, format 1\n# see" + example == config_text(config)
    assert read_config(config_text(config)).array("stamping").values.__len__() == 92
