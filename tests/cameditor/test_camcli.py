"""`motiontool cam` through a parser built with cli.cam.add_parser; .dat export/import."""

from __future__ import annotations

import argparse

import pytest

from motiontool.camcurve.layout import encode
from motiontool.cli import cam
from motiontool.formats.dat import DatError, dat_text, parse_dat, read_dat, write_dat
from motiontool.formats.zbc import read_config
from tests.camcurve.conftest import stamping_curve

STAMPING = ["--name", "stamping", "--master-length", "4000", "--intervals", "40", "--point", "0,0,C",
            "--point", "1500,1200,T", "--point", "2500,2400,T", "--point", "4000,3600,C", "--cycles-per-min", "60"]


def run(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="motiontool")
    cam.add_parser(parser.add_subparsers(dest="command"))
    args = parser.parse_args(argv)
    return cam.run(args)


def test_build_and_info_stamping(tmp_path, capsys):
    out = tmp_path / "stamping.zbc"
    assert run(["cam", "build", *STAMPING, "-o", str(out)]) == 0
    assert capsys.readouterr() == ("", "")
    config = read_config(out)
    assert len(config.array("stamping").values) == 92
    assert config.curve("stamping") == stamping_curve()
    assert run(["cam", "info", str(out)]) == 0
    assert capsys.readouterr().out == "stamping: 92 elements, master 4000, slave 3600, 40 intervals\n"


def test_build_adds_and_replaces(tmp_path, capsys):
    out = tmp_path / "two.cnf"
    assert run(["cam", "build", *STAMPING, "-o", str(out)]) == 0
    marker = ["--name", "marker", *STAMPING[2:], "--pair", "1000,1500", "--pair", "2500,3000",
              "--correction", "3000,1000", "--marker", "1000,0", "--slave-stop", "0"]
    assert run(["cam", "build", *marker, "-o", str(out)]) == 0
    assert run(["cam", "build", *STAMPING[:4], "--intervals", "20", *STAMPING[6:], "-o", str(out)]) == 0
    capsys.readouterr()
    assert run(["cam", "info", str(out)]) == 0
    assert capsys.readouterr().out.splitlines() == [
        "stamping: 72 elements, master 4000, slave 3600, 20 intervals",
        "marker: 112 elements, master 4000, slave 3600, 40 intervals"]


@pytest.mark.parametrize(("extra", "message"), [
    (["--point", "3000,100"], "fix_points"),
    (["--slave-stop", "abc"], "--slave-stop"),
    (["--correction", "5000,0"], "correction_start"),
    (["--pair", "1000"], "--pair"),
    (["--pair", "1050,1500"], "start_stop_pairs"),
    (["--intervals", "0"], "intervals"),
])
def test_build_bad_input(tmp_path, capsys, extra, message):
    out = tmp_path / "bad.zbc"
    assert run(["cam", "build", *STAMPING, *extra, "-o", str(out)]) == 1
    err = capsys.readouterr().err
    assert err.startswith("motiontool cam build: error: ") and message in err
    assert not out.exists()


def test_build_bad_name_and_length(tmp_path, capsys):
    out = tmp_path / "bad.zbc"
    args = ["cam", "build", *STAMPING, "-o", str(out)]
    args[3] = "x" * 17
    assert run(args) == 1
    assert "name: at most 16" in capsys.readouterr().err
    args = ["cam", "build", *STAMPING, "-o", str(out)]
    args[5] = "4100"
    assert run(args) == 1
    assert "master_length" in capsys.readouterr().err


def test_build_into_corrupt_file_refused(tmp_path, capsys):
    out = tmp_path / "corrupt.zbc"
    out.write_text("hello\n")
    assert run(["cam", "build", *STAMPING, "-o", str(out)]) == 1
    assert "first line" in capsys.readouterr().err
    assert out.read_text() == "hello\n"
    assert run(["cam", "info", str(out)]) == 1


def test_dat_is_the_curve_array_and_import_gives_the_exported_curve(tmp_path):
    """DG L3581: Export writes "the curve data … to an ASCII text file with the extension .dat … the exact
    format of the array"; DG L3580: Import replaces the curve and needs exactly an export file (S: export,
    import → identical curve)."""
    curve = stamping_curve()
    path = tmp_path / "stamping.dat"
    write_dat(path, curve)
    text = path.read_text()
    lines = text.splitlines()
    assert lines[:6] == ["# motiontool cam export, format 1", "name = stamping", "intervals = 40",
                         "start_gradient = 0", "end_gradient = 0", "elements = 92"]
    assert [int(v) for v in lines[6:]] == encode(curve)
    data = read_dat(path)
    assert data.to_curve() == curve
    assert dat_text(data) == text


def test_dat_cli_round_trip(tmp_path):
    zbc, dat, other = tmp_path / "a.zbc", tmp_path / "a.dat", tmp_path / "b.zbc"
    assert run(["cam", "build", *STAMPING, "-o", str(zbc)]) == 0
    assert run(["cam", "export", str(zbc), "--curve", "stamping", "-o", str(dat)]) == 0
    assert run(["cam", "import", str(dat), "-o", str(other)]) == 0
    assert read_config(other).curve("stamping") == read_config(zbc).curve("stamping")


def test_import_errors_name_the_file(tmp_path, capsys):
    """Bad input gets a clear error naming the place, and nothing the user had is lost (DEVELOPERS.md): import
    and build add to a .zbc the same way."""
    zbc, dat, broken = tmp_path / "a.zbc", tmp_path / "a.dat", tmp_path / "broken.zbc"
    assert run(["cam", "build", *STAMPING, "-o", str(zbc)]) == 0
    assert run(["cam", "export", str(zbc), "-o", str(dat)]) == 0
    broken.write_text("not a configuration file\n")
    capsys.readouterr()
    assert run(["cam", "import", str(dat), "-o", str(broken)]) == 1
    assert f"cannot add to {broken}" in capsys.readouterr().err
    assert broken.read_text() == "not a configuration file\n"
    assert run(["cam", "import", str(tmp_path / "missing.dat"), "-o", str(zbc)]) == 1
    assert f"cannot read {tmp_path / 'missing.dat'}" in capsys.readouterr().err


@pytest.mark.parametrize(("mutate", "line", "message"), [
    (lambda t: t.replace("format 1", "format 9"), 1, "unsupported"),
    (lambda t: t.replace("name = ", "nom = "), 2, "name"),
    (lambda t: t.replace("intervals = 40", "intervals = 0"), 3, "intervals"),
    (lambda t: t.replace("end_gradient = 0", "end_gradient = x"), 5, "end_gradient"),
    (lambda t: t.replace("elements = 92", "elements = 93"), 98, "truncated"),
    (lambda t: t.replace("elements = 92", "elements = 91"), 98, "more than"),
    (lambda t: t.replace("\n1128353093\n", "\n1128353093 7\n"), 7, "one integer"),
    (lambda t: t.replace("\n1128353093\n", "\n1\n"), 7, "element 0"),
    (lambda t: t.replace("name = stamping", "name = other"), 2, "named"),
    (lambda t: t.rsplit("\n", 2)[0] + "\n", 97, "truncated"),
])
def test_dat_refusals(mutate, line, message):
    with pytest.raises(DatError) as info:
        parse_dat(mutate(dat_text(stamping_curve())))
    assert info.value.line == line and message in info.value.message
