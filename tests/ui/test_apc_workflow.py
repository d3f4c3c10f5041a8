"""A Unidrive SP engineer's workflow in the IDE (issue 29 item 9): "A new user can, from the IDE alone, open a DPL
sample, change #18.11 in the parameter browser, run it, and see the reference on the scope."

Seed 004 L5068 (§7.1): "The position setpoint is set in 0.1 motor revolutions, entered into parameter 18.11."
Table 11-1 L8208: "81.12 POS Task scheduling rate … 0: Disable 1: 0.25ms … 6: 8ms" (the browser refuses 7).
Decisions A75 (the browser's table and file), A76 (polled curves on the APC)."""

from __future__ import annotations

import pytest
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QAbstractItemView, QApplication

from motiontool.scope.ui import ScopeWindow
from motiontool.ui.apc_parameters import ApcParametersDialog
from motiontool.ui.interface_dialog import SelectControllerDialog
from tests.modal import answering
from tests.shots import shot_path
from tests.ui.test_controller_dialogs import button, click

KEY_MS = 120   # a key every 120 ms: a user who looks at the keys
SCREENSHOT = "apc_parameters.png"   # docs/screenshots/ (tests/shots.py)
REV = 65536    # counts per revolution at 16 turns bits (the §7.1 setup)


def loaded(qtbot, dialog: ApcParametersDialog) -> None:
    qtbot.waitUntil(lambda: all(r.current is not None for r in dialog.rows.values()) and dialog.ok.isEnabled(),
                    timeout=10_000)


def show_group(qtbot, dialog: ApcParametersDialog, title: str) -> None:
    item = dialog.groups.findItems(title, Qt.MatchFlag.MatchStartsWith)[0]
    qtbot.mouseClick(dialog.groups.viewport(), Qt.MouseButton.LeftButton,
                     pos=dialog.groups.visualItemRect(item).center())


def type_value(qtbot, dialog: ApcParametersDialog, label: str, text: str) -> None:
    """Click the value cell, type at a human pace (the first key opens the editor), Return."""
    item = dialog.rows[label].item
    table = item.tableWidget()
    table.scrollToItem(item)
    qtbot.mouseClick(table.viewport(), Qt.MouseButton.LeftButton, pos=table.visualItemRect(item).center())
    for key in [*text, Qt.Key.Key_Return]:
        focused = QApplication.focusWidget()
        assert focused is not None and dialog.isAncestorOf(focused)
        qtbot.wait(KEY_MS)
        qtbot.keyClick(focused, key)
    qtbot.waitUntil(lambda: table.state() == QAbstractItemView.State.NoState, timeout=2000)


def browse(window, qtbot, edit) -> None:
    """Controller ▸ Parameters ▸ APC (Unidrive SP)..., wait for the values, `edit(dialog)`."""
    def reply(dialog):
        assert isinstance(dialog, ApcParametersDialog)
        dialog.activateWindow()
        qtbot.waitUntil(dialog.isActiveWindow, timeout=2000)
        loaded(qtbot, dialog)
        edit(dialog)

    with answering(qtbot, reply, timeout=20_000):
        window.actions_by_text["APC (Unidrive SP)..."].trigger()


def set_18_11(qtbot, text: str, *, screenshot: bool = False):
    def edit(dialog):
        show_group(qtbot, dialog, "Menu 18")
        type_value(qtbot, dialog, "18.11", text)
        assert dialog.pending() == {"18.11": int(text)} and dialog.rows["18.11"].item.font().bold()
        if screenshot:   # a click on the next name, so the changed value shows as marked, not as selected
            table, below = dialog.rows["18.11"].item.tableWidget(), dialog.rows["18.13"].item.row()
            qtbot.mouseClick(table.viewport(), Qt.MouseButton.LeftButton,
                             pos=table.visualRect(table.model().index(below, 1)).center())
            dialog.grab().save(str(shot_path(SCREENSHOT)))   # docs: menu 18 with the changed setpoint, before OK
        click(qtbot, button(dialog, "OK"))
        qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=10_000)
    return edit


@pytest.mark.slow  # several seconds on an idle machine: make test runs it, make test-fast does not
def test_open_the_sample_set_18_11_run_it_and_see_the_reference_on_the_scope(window, qtbot):
    sample = next(a for a in window.dpl_samples_menu.actions() if a.text() == "apc_7_1_position.dpl")
    sample.trigger()                                                   # File ▸ Sample ▸ DPL ▸ §7.1
    assert window.current_editor().language == "dpl"
    browse(window, qtbot, set_18_11(qtbot, "50", screenshot=True))     # 5.0 revolutions
    assert "wrote #18.11 = 50" in window.messages.toPlainText()
    window.actions_by_text["Execute"].trigger()
    assert window.connection.interface_key == "apcsim:"
    link = window.bridge.link
    qtbot.waitUntil(lambda: link.read_parameter("APC_FB_POS") == 5 * REV, timeout=20_000)

    window.actions_by_text["Oscilloscope"].trigger()                   # Tools ▸ Oscilloscope
    scope = window._scopes[-1]
    assert isinstance(scope, ScopeWindow)
    scope.mode_actions["polling"].trigger()

    def add_curve(dialog):
        dialog.kind.setCurrentText("Signal")
        qtbot.mouseClick(dialog.signal, Qt.MouseButton.LeftButton)
        qtbot.keyClick(dialog.signal, Qt.Key.Key_A, Qt.KeyboardModifier.ControlModifier)
        qtbot.keyClicks(dialog.signal, "APC_PROF_OUT_POS", delay=KEY_MS)
        dialog.method.setCurrentText("Polled (no group)")
        click(qtbot, button(dialog, "OK"))

    with answering(qtbot, add_curve, timeout=20_000):
        scope.add_action.trigger()
    curve = scope.scope.curve("1: APC_PROF_OUT_POS")
    scope.poll_box.setValue(10)
    scope.start_action.trigger()
    qtbot.waitUntil(lambda: len(curve.raw()[0]) >= 3, timeout=10_000)
    browse(window, qtbot, set_18_11(qtbot, "100"))                     # the reference moves on to 10 revolutions
    qtbot.waitUntil(lambda: curve.raw()[1][-1] == 10 * REV, timeout=20_000)
    scope.stop_action.trigger()
    times, values = curve.raw()
    assert values[0] == 5 * REV and values[-1] == 10 * REV
    assert all(b >= a for a, b in zip(values, values[1:], strict=False))   # a profile, no jump back
    assert all(b > a for a, b in zip(times, times[1:], strict=False))      # time-stamped by the APC's clock
    assert link.read_parameter("18.12") == 100                         # the program's own readback (L5509)


def test_the_browser_refuses_a_value_outside_the_manuals_range_and_restores_a_file(window, qtbot, tmp_path):
    saved = tmp_path / "line3.apcpar"

    def edit(dialog):
        show_group(qtbot, dialog, "Menu 81")
        assert dialog.rows["81.12"].item.text() == "3" and dialog.rows["90.49"].p.read_only
        type_value(qtbot, dialog, "81.12", "7")
        assert dialog.refused() == ["#81.12 POS task scheduling rate (1: 0.25 2: 0.5 3: 1 4: 2 5: 4 6: 8 ms; at "
                                    "REINIT): 7 is outside 0 .. 6"] and dialog.pending() == {}
        type_value(qtbot, dialog, "81.12", "4")
        show_group(qtbot, dialog, "Menu 18")
        type_value(qtbot, dialog, "18.11", "25")
        assert dialog.save_to(saved)
        click(qtbot, button(dialog, "Cancel"))

    browse(window, qtbot, edit)
    text = saved.read_text(encoding="utf-8")
    assert text.startswith("motiontool APC parameters 1\n") and "\n18.11 = 25 ; " in text
    assert "\n81.12 = 4 ; " in text and "90.01" not in text                # readouts are not saved
    link = window.controllers.link(1, interface="apcsim:")
    assert link.read_parameter("18.11") == 0                               # Cancel wrote nothing

    bad = tmp_path / "bad.apcpar"
    bad.write_text(text.replace("18.11 = 25", "18.11 = 2x"), encoding="utf-8")

    def restore(dialog):
        assert not dialog.restore_from(bad)
        assert dialog.message.text().startswith(f"{bad}:") and "'2x' is not a whole number" in dialog.message.text()
        assert dialog.pending() == {}                                      # a bad file changes nothing
        assert dialog.restore_from(saved)
        assert dialog.pending() == {"18.11": 25, "81.12": 4}               # only what differs is written
        click(qtbot, button(dialog, "OK"))
        qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=10_000)

    browse(window, qtbot, restore)
    assert link.read_parameter("18.11") == 25 and link.read_parameter("81.12") == 4


def test_select_controller_opens_the_apc_like_an_mco(window, qtbot):
    def reply(dialog):
        assert isinstance(dialog, SelectControllerDialog)
        combo = dialog.interface
        combo.setCurrentIndex(combo.findData("apcsim"))
        click(qtbot, dialog.open_button)
        top = next(dialog.tree.topLevelItem(i) for i in range(dialog.tree.topLevelItemCount())
                   if dialog.tree.topLevelItem(i).text(0) == "APC simulator")
        item = top.child(0)
        assert item.text(0) == "Controller 1"
        qtbot.mouseClick(dialog.tree.viewport(), Qt.MouseButton.LeftButton,
                         pos=dialog.tree.visualItemRect(item).center())
        click(qtbot, dialog.buttons.button(dialog.buttons.StandardButton.Ok))

    with answering(qtbot, reply):
        window.actions_by_text["Select Controller..."].trigger()
    assert window.connection.interface_key == "apcsim:" and "APC simulator" in window.windowTitle()
    assert window.bridge.link.call("identify")["kind"] == "APC"
