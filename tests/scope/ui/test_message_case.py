"""The oscilloscope's messages start with a capital, as its others do ("Uploaded …", "Trigger off", "Polling
stopped: …"); "no active curve to record" was the odd one out."""

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QToolButton

from tests.ui.conftest import scripted  # noqa: F401

SAID = "No active curve to record: add a curve first"


def test_start_without_a_curve_says_so_with_a_capital(scripted, qtbot):  # noqa: F811
    window, prompts = scripted
    window.actions_by_text["Oscilloscope"].trigger()
    scope = window._scopes[-1]
    qtbot.waitExposed(scope)
    for curve in list(scope.scope.curves):
        curve.active = False
    button = next(b for b in scope.findChildren(QToolButton) if b.defaultAction() is scope.start_action)
    qtbot.mouseClick(button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: "add a curve first" in scope.statusBar().currentMessage(), timeout=5000)
    assert scope.statusBar().currentMessage() == SAID
    assert prompts.asked == [("warn", "Oscilloscope", SAID)]
    assert not scope.run.running
