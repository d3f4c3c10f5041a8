"""A CAM editor window on the embedded controller (the real kernel behind a comms link)."""

import pytest
from PySide6.QtWidgets import QApplication

from motiontool.cameditor.ui.window import CamEditor
from motiontool.controller.embedded import EmbeddedLink


@pytest.fixture
def link():
    link = EmbeddedLink()
    yield link
    link.close()


@pytest.fixture
def editor(qtbot, link):
    w = CamEditor(link_provider=lambda: link)
    w.confirm = False
    qtbot.addWidget(w)
    w.resize(1400, 900)
    w.show()
    qtbot.waitExposed(w)
    yield w
    # a test that fires a context-menu entry with trigger() leaves the menu open (a user's click would close it);
    # open, it took the keys of a later test in the same worker
    for _ in range(10):   # menus opened by two right-clicks stack
        popup = QApplication.activePopupWidget()
        if popup is None:
            break
        popup.close()
    w.modified = False
