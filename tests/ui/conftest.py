"""A main window on a fresh settings file, attached to embedded simulated controllers; `scripted`: the same window
given a ScriptedPrompts (issue 27 item 5), which answers what the user would - a dialog that opens past the
prompts is noted and closed, and the test fails."""

import pytest
from PySide6.QtCore import QSettings, QTimer
from PySide6.QtWidgets import QApplication

from motiontool.session.prompts import ScriptedPrompts
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


@pytest.fixture
def scripted(qtbot, tmp_path):
    # a dialog opened past the prompts would wait for a user: it is noted and closed, and the test fails
    opened: list[str] = []
    guard = QTimer()
    guard.timeout.connect(lambda: (box := QApplication.activeModalWidget()) is not None
                          and (opened.append(box.windowTitle()), box.close()))
    guard.start(50)
    prompts = ScriptedPrompts()
    settings = QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat)
    w = MainWindow(settings=settings, realtime_factor=50.0, prompts=prompts)
    w.ask_to_save = False
    qtbot.addWidget(w)
    w.show()
    qtbot.waitExposed(w)
    assert w.development.connect_default()
    yield w, prompts
    guard.stop()
    assert not opened, f"dialogs opened past the window's prompts: {opened}"
    for editor in w.editors():  # no "Save changes?" question at teardown
        editor.document().setModified(False)
    w.bridge.detach(close=False)
    w.controllers.close()
