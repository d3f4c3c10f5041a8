"""A main window on a fresh settings file, attached to embedded simulated controllers."""

import pytest
from PySide6.QtCore import QSettings

from motiontool.ui.main_window import MainWindow


@pytest.fixture
def window(qtbot, tmp_path):
    settings = QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat)
    w = MainWindow(settings=settings, realtime_factor=50.0)
    w.ask_to_save = False
    qtbot.addWidget(w)
    w.show()
    qtbot.waitExposed(w)
    w.activateWindow()
    yield w
    for editor in w.editors():  # no "Save changes?" question at teardown
        editor.document().setModified(False)
    w.bridge.detach(close=False)
    w.controllers.close()
