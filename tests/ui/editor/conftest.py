from __future__ import annotations

import pytest

from motiontool.ui.editor import CodeEditor


@pytest.fixture
def editor(qtbot):
    """A shown CodeEditor (offscreen), 700x500."""
    widget = CodeEditor()
    qtbot.addWidget(widget)
    widget.resize(700, 500)
    widget.show()
    qtbot.waitExposed(widget)
    return widget
