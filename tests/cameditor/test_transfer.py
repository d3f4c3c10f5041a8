"""Configuration files to and from a controller, through the embedded link (the real kernel behind it)."""

import subprocess
import sys

import pytest

from motiontool.camcurve.layout import encode
from motiontool.cameditor.transfer import download_config, upload_config
from motiontool.controller.embedded import EmbeddedLink
from motiontool.formats.zbc import ArrayEntry, ConfigError, ConfigFile, write_config
from tests.camcurve.conftest import stamping_curve


def _config() -> ConfigFile:
    config = ConfigFile(parameters={"32-60": 55, "32-81": 2.5})  # KPROP, RAMPMIN (scaled, 3 decimals)
    config.arrays.append(ArrayEntry("speeds", [10, 20, 30]))
    config.add_curve(stamping_curve())
    return config


def test_download_then_upload_gives_back_parameters_arrays_and_the_curve():
    """DG 2886-2900: Restore from file writes parameters and arrays; Save to file reads them back."""
    link = EmbeddedLink()
    download_config(link, _config())
    assert link.read_parameter("KPROP") == 55
    assert link.read_parameter("32-81") == 2500  # raw, ms
    assert [a["name"] for a in link.call("list_arrays")] == ["speeds", "stamping"]
    assert link.read_array(1) == encode(stamping_curve())
    back = upload_config(link)
    assert back.parameters["32-60"] == 55 and back.parameters["32-81"] == 2.5
    assert back.array("speeds").values == [10, 20, 30]
    assert back.curve("stamping") == stamping_curve()
    assert back.array("stamping").curve == "stamping"


def test_a_refused_parameter_names_it():
    link = EmbeddedLink()
    config = ConfigFile(parameters={"32-60": 200000})  # above 100000: the controller refuses a link write
    with pytest.raises(ConfigError, match="32-60 KPROP"):
        download_config(link, config)


def test_run_config_loads_parameters_and_arrays_before_the_program(tmp_path):
    """Issue 5: `motiontool run --config CONF.zbc` loads parameters and arrays before the program runs; the
    program's DIM finds the arrays by position (C:1024-1041)."""
    conf = tmp_path / "conf.zbc"
    write_config(conf, _config())
    program = tmp_path / "p.m"
    program.write_text("DIM speeds[3], cam[92]\nPRINT GET KPROP, \" \", speeds[2], \" \", cam[1]\n")
    proc = subprocess.run([sys.executable, "-m", "motiontool", "run", str(program), "--config", str(conf)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == f"55 20 {encode(stamping_curve())[0]}\n"


def test_run_config_refuses_a_broken_file_with_its_line(tmp_path):
    conf = tmp_path / "conf.zbc"
    write_config(conf, _config())
    conf.write_text(conf.read_text().replace("32-60 KPROP = 55", "32-60 KPROP = fast"))
    program = tmp_path / "p.m"
    program.write_text('PRINT "never"\n')
    proc = subprocess.run([sys.executable, "-m", "motiontool", "run", str(program), "--config", str(conf)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1
    assert proc.stdout == ""
    line = conf.read_text().splitlines().index("32-60 KPROP = fast") + 1
    assert proc.stderr.startswith(f"{conf}:{line}: ") and "fast" in proc.stderr
