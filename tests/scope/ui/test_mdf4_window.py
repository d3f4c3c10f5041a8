"""The oscilloscope window's Export picks CSV or MDF4 by the file's suffix (issue 8: "export curves to txt/CSV (and
MDF4 via asammdf if installed)"); without asammdf an .mf4 export says what to install."""

import sys

import pytest

from motiontool.scope.mdf4 import Mdf4Unavailable
from tests.scope.test_mdf4 import scope


def test_the_window_exports_csv_or_mdf4_by_suffix(qtbot, monkeypatch, tmp_path):
    from motiontool.scope.ui import ScopeWindow

    w = ScopeWindow(None, "free_run", scope=scope(), ask=False)
    qtbot.addWidget(w)
    w.export_to(tmp_path / "x.csv")
    assert (tmp_path / "x.csv").read_text().startswith("Test Group (Free Run),,1: APOS,,")
    monkeypatch.setitem(sys.modules, "asammdf", None)
    with pytest.raises(Mdf4Unavailable):
        w.export_to(tmp_path / "x.MF4")
