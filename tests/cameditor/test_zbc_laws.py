"""Configuration file format 2 (decision C12): curves with motion-law fix points (VDI 2143, camcurve.motionlaws)."""

from __future__ import annotations

import pytest

from motiontool.camcurve import Curve, FixPoint
from motiontool.formats.zbc import ConfigError, ConfigFile, config_text, read_config, write_config
from tests.camcurve.conftest import stamping_curve


def law_curve() -> Curve:
    pts = (FixPoint(0, 0), FixPoint(900, 0, "P345"), FixPoint(1800, 1000, "CYCL"), FixPoint(2700, 1000, "HARM"),
           FixPoint(3600, 0, "MTRAP"))
    return Curve("drdr", 3600, pts, intervals=36)


def test_laws_round_trip_in_format_2(tmp_path):
    config = ConfigFile()
    config.add_curve(stamping_curve())
    config.add_curve(law_curve())
    path = tmp_path / "laws.zbc"
    write_config(path, config)
    text = path.read_text()
    assert text.startswith("# motiontool configuration file, format 2\n")
    assert "point = 1800, 1000, CYCL\n" in text
    again = read_config(path)
    assert again == config
    assert config_text(again) == text  # save → open → save byte-identical


def test_files_without_laws_stay_format_1():
    """Older readers keep reading every file that does not use the extension."""
    config = ConfigFile()
    config.add_curve(stamping_curve())
    assert config_text(config).startswith("# motiontool configuration file, format 1\n")


def test_law_in_a_format_1_file_is_refused_with_its_line():
    config = ConfigFile()
    config.add_curve(law_curve())
    text = config_text(config).replace("format 2\n", "format 1\n", 1)
    with pytest.raises(ConfigError) as info:
        read_config(text)
    line = text.split("\n").index("point = 900, 0, P345") + 1
    assert info.value.line == line and "needs format 2" in info.value.message


def test_misplaced_law_is_refused_with_its_line():
    config = ConfigFile()
    config.add_curve(law_curve())
    text = config_text(config).replace("point = 0, 0, C", "point = 0, 0, CYCL")
    with pytest.raises(ConfigError) as info:
        read_config(text)
    assert info.value.line == text.split("\n").index("point = 0, 0, CYCL") + 1
    assert "first point" in info.value.message
