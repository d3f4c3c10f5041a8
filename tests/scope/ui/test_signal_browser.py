"""Add Curve ▸ Browse… (issue 23 item 8: "Add Curve has no signal browser"): the signals the connected controller
can record, asked for with `list_signals` off the GUI thread, filtered as the user types, taken by a double click.
DG 5227-5236: a curve's source is a signal of the controller (APOS, CPOS, TRACKERR …, a parameter, a SYSVAR)."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QDialogButtonBox

from motiontool.scope.ui.dialogs import AddCurveDialog
from motiontool.scope.ui.signal_browser import SignalBrowser
from tests.modal import answering, answering_inner
from tests.scope.ui.test_user_actions import GROUP, click, open_scope_moving, record
from tests.shots import shot_path


def browse_and_take(qtbot, typed: str, name: str, seen: dict):
    """The browser: wait for the list, type a filter at a human pace, double-click the signal."""
    def reply(browser):
        assert isinstance(browser, SignalBrowser)
        qtbot.waitUntil(lambda: browser.tree.topLevelItemCount() > 0, timeout=10000)
        seen["groups"] = [browser.tree.topLevelItem(g).text(0) for g in range(browser.tree.topLevelItemCount())]
        qtbot.keyClicks(browser.filter, typed, delay=120)
        visible = [browser.tree.topLevelItem(g).child(k) for g in range(browser.tree.topLevelItemCount())
                   for k in range(browser.tree.topLevelItem(g).childCount())
                   if not browser.tree.topLevelItem(g).child(k).isHidden()]
        seen["visible"] = [item.text(0) for item in visible]
        browser.grab().save(str(shot_path("scope_signal_browser.png")))
        item = next(item for item in visible if item.text(0) == name)
        rect = browser.tree.visualItemRect(item)
        qtbot.mouseClick(browser.tree.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())   # a double click:
        qtbot.mouseDClick(browser.tree.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())  # press, then dbl
    return reply


def test_browse_filters_the_controllers_signals_and_a_double_click_takes_one(window, qtbot):
    scope = open_scope_moving(window, qtbot)
    seen: dict = {}

    def add(dialog):
        assert isinstance(dialog, AddCurveDialog)
        with answering_inner(qtbot, SignalBrowser, browse_and_take(qtbot, "track", "TRACKERR", seen)):
            qtbot.mouseClick(dialog.browse, Qt.MouseButton.LeftButton)
        assert dialog.signal.text() == "TRACKERR"
        dialog.method.setCurrentText(GROUP)
        qtbot.mouseClick(dialog.findChild(QDialogButtonBox).button(QDialogButtonBox.StandardButton.Ok),
                         Qt.MouseButton.LeftButton)

    with answering(qtbot, add):
        click(qtbot, scope, scope.add_action)
    assert seen["groups"] == ["Axis", "Process data (SYSVAR)", "Parameters"]
    assert "TRACKERR" in seen["visible"] and "APOS" not in seen["visible"]
    assert "4102" in seen["visible"]                       # REG_TRACKERR, the process data of SYSVAR 4102
    assert [c.name for c in scope.scope.curves] == ["1: TRACKERR"]
    record(scope, qtbot)
    t, _y = scope.scope.curves[0].raw()
    assert t.size > 50
    scope.close()


def test_without_a_controller_the_browser_says_so(qtbot):
    dialog = AddCurveDialog(["Test Group (Free Run)"], [], fetch=None)
    qtbot.addWidget(dialog)
    seen = []

    def look(browser):
        seen.append(browser.status.text())
        browser.reject()

    with answering(qtbot, look):
        qtbot.mouseClick(dialog.browse, Qt.MouseButton.LeftButton)
    assert "Not connected" in seen[0] and dialog.signal.text() == "APOS"
