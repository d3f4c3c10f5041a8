"""MDF4 export via asammdf (issue 8: "export curves to txt/CSV (and MDF4 via asammdf if installed)"). asammdf is
not a dependency: without it the export says what to install; with it the file reads back."""

import sys

import numpy as np
import pytest

from motiontool.scope.curves import Curve, Group, Scaling, Scope, Source
from motiontool.scope.mdf4 import Mdf4Unavailable, export_mdf4


def scope() -> Scope:
    s = Scope("free_run")
    s.add_group(Group("Test Group (Free Run)"))
    a = s.add_curve(Curve("1: APOS", Source(signal="APOS", group="Test Group (Free Run)"), unit="UU",
                          scaling=Scaling(0, 0.5)))
    a.buffer.extend([0, 1, 2, 3], [0, 10, 30, 60])
    b = s.add_curve(Curve("KPROP", Source(method="polled", signal="KPROP")))
    b.buffer.extend([0, 100], [30, 40])
    s.add_curve(Curve("empty"))
    return s


def test_without_asammdf_the_message_says_what_to_install(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "asammdf", None)      # import asammdf raises ImportError
    with pytest.raises(Mdf4Unavailable, match="pip install asammdf"):
        export_mdf4(scope(), tmp_path / "x.mf4")
    assert not (tmp_path / "x.mf4").exists()


def test_with_asammdf_the_file_reads_back(tmp_path):
    asammdf = pytest.importorskip("asammdf")
    path = export_mdf4(scope(), tmp_path / "x.mf4")
    mdf = asammdf.MDF(path)
    try:
        apos = mdf.get("1: APOS")
        assert np.allclose(apos.timestamps, [0, 0.001, 0.002, 0.003]) and np.allclose(apos.samples, [0, 5, 15, 30])
        assert apos.unit == "UU"
        assert np.allclose(mdf.get("KPROP").samples, [30, 40])
        assert "empty" not in mdf.channels_db
    finally:
        mdf.close()
