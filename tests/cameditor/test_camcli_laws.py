"""`motiontool cam build --point M,S,TYPE` with the VDI 2143 motion laws (decision C10)."""

from __future__ import annotations

from motiontool.cameditor import editing
from motiontool.formats.zbc import read_config
from tests.cameditor.test_camcli import run

LAW_POINTS = ["--point", "0,0", "--point", "900,0,p345", "--point", "1800,1000,CYCL", "--point", "2700,1000,HARM",
              "--point", "3600,0,MTRAP"]


def test_build_with_laws(tmp_path, capsys):
    out = tmp_path / "laws.zbc"
    assert run(["cam", "build", "--name", "drdr", "--intervals", "36", *LAW_POINTS, "-o", str(out)]) == 0
    assert capsys.readouterr() == ("", "")
    curve = read_config(out).curve("drdr")
    assert [p.type for p in curve.fix_points] == ["C", "P345", "CYCL", "HARM", "MTRAP"]
    assert out.read_text().startswith("# motiontool configuration file, format 2\n")
    assert run(["cam", "info", str(out)]) == 0
    assert capsys.readouterr().out == "drdr: 91 elements, master 3600, slave 0, 36 intervals\n"


def test_build_refuses_a_misplaced_law(tmp_path, capsys):
    out = tmp_path / "bad.zbc"
    assert run(["cam", "build", "--name", "bad", "--point", "0,0,CYCL", "--point", "100,50", "-o", str(out)]) != 0
    err = capsys.readouterr().err
    assert "CYCL" in err and "first point" in err
    assert not out.exists()


def test_type_names_offer_the_laws():
    assert list(editing.TYPE_NAMES)[4:] == ["P345", "MSIN", "CYCL", "MTRAP", "HARM"]
    assert editing.TYPE_NAMES["CYCL"] == "Cycloid"


def test_dat_export_import_keeps_the_laws(tmp_path):
    """.dat holds the controller array; the law type codes 4..8 survive export → import (decision C13)."""
    from motiontool.formats.dat import read_dat, write_dat
    from tests.cameditor.law_trace import law_curve

    for interpolation in (True, False):
        curve = law_curve(interpolation)
        write_dat(tmp_path / "c.dat", curve)
        assert read_dat(tmp_path / "c.dat").to_curve() == curve
