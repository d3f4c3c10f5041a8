"""A CAM editor window on the embedded controller (the real kernel behind a comms link)."""

import pytest

from motiontool.cameditor.ui.window import CamEditor
from motiontool.comms.embedded import EmbeddedLink


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
    w.modified = False
