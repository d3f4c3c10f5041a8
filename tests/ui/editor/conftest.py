from __future__ import annotations

import pytest

from motiontool.ui.editor import CodeEditor


@pytest.fixture
def editor(qtbot):
    """A shown CodeEditor (offscreen), 700x500, in the active window with the keyboard focus, as after a person
    clicks into it. Without the focus the completer hides its popup at the next key (QCompleter does so when its
    widget lost the focus): a window left active by an earlier test in the same worker made the typing tests flaky."""
    widget = CodeEditor()
    qtbot.addWidget(widget)
    widget.resize(700, 500)
    widget.show()
    qtbot.waitExposed(widget)
    widget.activateWindow()
    widget.setFocus()
    qtbot.waitUntil(widget.hasFocus)
    return widget
