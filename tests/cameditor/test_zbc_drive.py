"""The FC 300's own parameters in a configuration file (issue 25 item 2, decision C19, docs/formats/zbc.md format 3):
Save to file keeps those that differ from the default in `[fc300]`, Restore from file writes them back.

DG 2886: "the entire controller configuration … can be uploaded and saved as a file on the PC"; CR 4019-4021:
"The parameter alterations are only stored in RAM. After power down the original parameter values are restored."
(so a file is where a drive setting outlives the power)."""

import pytest

from motiontool.cameditor.transfer import download_config, upload_config
from motiontool.controller.embedded import EmbeddedLink
from motiontool.formats.zbc import ConfigError, ConfigFile, config_text, read_config, write_config

HEADER = "# motiontool configuration file, format {}\n"


def _file(section: str, version: int = 3) -> str:
    return HEADER.format(version) + "[global]\n\n[fc300]\n" + section + "\n[end]\n"


def test_4_13_set_on_one_controller_is_back_on_a_fresh_one(tmp_path):
    first = EmbeddedLink()
    first.write_parameter("4-13", 1800)           # Motor Speed High Limit [RPM], default 1500
    path = tmp_path / "drive.zbc"
    write_config(path, upload_config(first))
    text = path.read_text()
    assert text.startswith(HEADER.format(3))
    assert "\n[fc300]\n4-13 = 1800\n\n" in text   # only what differs from the default
    fresh = EmbeddedLink()
    assert fresh.read_parameter("4-13") == 1500
    download_config(fresh, read_config(path))
    assert fresh.read_parameter("4-13") == 1800


def test_a_drive_at_its_defaults_writes_no_section_and_the_old_format():
    """Files without drive settings stay readable by a reader of format 1 (the lowest format that holds them)."""
    config = upload_config(EmbeddedLink())
    assert config.drive == {}
    text = config_text(config)
    assert text.startswith(HEADER.format(1)) and "[fc300]" not in text


def test_an_old_file_without_the_section_still_reads():
    config = read_config(HEADER.format(1) + "[global]\n33-80 PRGPAR = 0\n\n[end]\n")
    assert config.drive == {} and config.parameters == {"33-80": 0}


def test_the_section_round_trips_sorted_by_number():
    config = ConfigFile(drive={"4-13": 1800, "1-24": 820, "3-03": 60000, "0-25": 7})
    text = config_text(config)
    assert "[fc300]\n0-25 = 7\n1-24 = 820\n3-03 = 60000\n4-13 = 1800\n" in text
    assert read_config(text).drive == config.drive
    assert config_text(read_config(text)) == text


@pytest.mark.parametrize(("line", "reason"), [
    ("4-99 = 1", "unknown FC 300 parameter '4-99'"),
    ("16-13 = 500", "16-13 Frequency: read-only readout"),     # DG 7594: "16-** … are read only"
    ("4-13 = 70000", "4-13 Motor Speed High Limit [RPM]: 70000 is outside 0..60000"),
    ("4-13 = 1.5", "is not an integer"),
    ("4-13 = 1800\n4-13 = 1900", "4-13 given twice (first on line 5)"),
])
def test_a_bad_line_is_refused_with_its_line_number(line, reason):
    text = _file(line)
    with pytest.raises(ConfigError) as info:
        read_config(text)
    assert reason in info.value.message
    assert info.value.line == text.split("\n").index(line.split("\n")[-1]) + 1


def test_the_section_in_an_older_format_is_refused_at_its_header():
    with pytest.raises(ConfigError) as info:
        read_config(_file("4-13 = 1800", version=2))
    assert info.value.line == 4 and "[fc300] needs format 3, the file says format 2" in info.value.message


def test_a_range_that_ends_at_another_parameter_is_restored_in_any_order():
    """4-11 ranges up to 4-13 (PG301, docs/fc300.md): 4-11 = 2000 fits only after 4-13 = 3000 is written."""
    link = EmbeddedLink()
    download_config(link, ConfigFile(drive={"4-11": 2000, "4-13": 3000}))
    assert (link.read_parameter("4-11"), link.read_parameter("4-13")) == (2000, 3000)


def test_settings_no_order_makes_fit_are_refused_naming_the_parameter():
    link = EmbeddedLink()
    with pytest.raises(ConfigError, match=r"FC 300 parameter 4-11: the controller refused 2000"):
        download_config(link, ConfigFile(drive={"4-11": 2000, "4-13": 1000}))


def test_restore_without_the_drive_set_leaves_the_drive():
    link = EmbeddedLink()
    download_config(link, ConfigFile(drive={"4-13": 1800}), sets=("global", "axis", "user", "arrays"))
    assert link.read_parameter("4-13") == 1500


@pytest.mark.wire
def test_the_drive_parameters_go_over_the_fc_protocol_link_as_over_the_embedded_one():
    """The FC protocol's parameter channel carries the drive's own parameters too (4-13 as PNU 413, issue 25 item
    2): Save to file over it holds the [fc300] section, Restore writes it back; a refused one is named."""
    from motiontool.comms.links import open_link
    from tests.comms.drive_process import drive_process

    with drive_process("--node", "1", "--node", "2") as drive:
        first, second = open_link(drive.url + "#1"), open_link(drive.url + "#2")
        try:
            first.write_parameter("4-13", 1800)
            saved = upload_config(first)
            assert saved.drive == {"4-13": 1800}
            download_config(second, saved)
            assert second.read_parameter("4-13") == 1800
            with pytest.raises(ConfigError, match=r"FC 300 parameter 16-13: the controller refused 10"):
                download_config(second, ConfigFile(drive={"16-13": 10}))
        finally:
            first.close()
            second.close()
