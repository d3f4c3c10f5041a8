"""Errors a user can see and clear (issue 23 item 3). Samples run one after another in one window stopped at
14_recipe_2d with error 176 "Array size wrong" (13 had DIMmed other arrays), without line or detail, and then every
later program failed with 105 "Error not reset": nothing in the IDE cleared a pending error. Now Execute names
the array clash first and offers Reset ▸ Arrays (decision I20); a pending error is red in the status bar with
Clear Error beside it, in the Controller menu, on the toolbar and in its message box; Controller ▸ Restart switches
the controller off and on."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QMessageBox

from tests.modal import answering, button_reply
from tests.test_samples import SAMPLES_DIR, parse_header
from tests.ui.test_user_defects import FAILING

RESET_AND_EXECUTE = "Reset Arrays and Execute"


def click_button(text: str):
    """A message box: click its button `text` with the mouse."""
    def reply(box):
        assert isinstance(box, QMessageBox), f"expected a message box, got {box!r}"
        button = next(b for b in box.buttons() if b.text() == text)
        QTest.mouseClick(button, Qt.MouseButton.LeftButton)
    return reply


def run_sample(window, qtbot, name: str, *replies) -> list[str]:
    """File ▸ Sample ▸ name, then Development ▸ Execute; the controller's lines until the program has ended."""
    next(a for a in window.samples_menu.actions() if a.text() == name).trigger()
    before = len(window.messages.toPlainText().splitlines())
    with answering(qtbot, *replies):
        window.actions_by_text["Execute"].trigger()
    qtbot.waitUntil(lambda: any(line.startswith("[01] program ended")
                                for line in window.messages.toPlainText().splitlines()[before:]), timeout=30_000)
    lines = window.messages.toPlainText().splitlines()[before:]
    return [line.removeprefix("[01] ") for line in lines if line.startswith("[01] ")]


def printed(lines: list[str]) -> list[str]:
    return [line for line in lines if not line.startswith(("program ", "error "))]


def test_samples_run_one_after_another_in_one_window(window, qtbot):
    """13 DIMs station[5], 14 recipe[3][3] and backup[9], 15 gaps[4]: array 1 has another size each time. Execute
    says so before it downloads and Reset Arrays and Execute lets each one run and print what its header says."""
    for name, question in (("13_position_table.m", ()), ("14_recipe_2d.m", (click_button(RESET_AND_EXECUTE),)),
                           ("15_functions.m", (click_button(RESET_AND_EXECUTE),))):
        lines = run_sample(window, qtbot, name, *question)
        assert printed(lines) == parse_header(SAMPLES_DIR / name).expect, name
        assert lines[-1] == "program ended", lines
    text = window.messages.toPlainText()
    assert "error" not in text and text.count("arrays deleted (Reset ▸ Arrays)") == 2
    assert not window.pending_error.indicator.isVisible()


def test_a_pending_error_shows_in_the_status_bar_and_clear_error_clears_it(window, qtbot):
    run_sample(window, qtbot, "13_position_table.m")
    lines = run_sample(window, qtbot, "14_recipe_2d.m", click_button("Execute Anyway"))
    qtbot.waitUntil(lambda: "error 176 hint:" in window.messages.toPlainText(), timeout=5000)
    text = window.messages.toPlainText()
    # the Communication window names the error with its DIM line, the controller's detail and what clears it
    assert lines[:2] == ["error 176: Array size wrong (line 23)",
                         "program ended with error 176: Array size wrong (line 23)"]
    assert "[01] error 176 detail: DIM recipe[9] but array 1 in the controller has 5 elements" in text
    assert "Controller ▸ Reset ▸ Arrays deletes them; then Clear Error" in text
    indicator = window.pending_error.indicator
    qtbot.waitUntil(indicator.isVisible, timeout=5000)
    assert indicator.text() == "⚠ Error 176: Array size wrong" and window.pending_error.clear_button.isVisible()
    # the next program stops at its first motion command: the error is still pending
    lines = run_sample(window, qtbot, "01_positioning.m")
    assert any(line.startswith("error 105: Error not reset") for line in lines)
    qtbot.waitUntil(lambda: "error 105 hint:" in window.messages.toPlainText(), timeout=5000)
    assert indicator.text() == "⚠ Error 176: Array size wrong"   # the pending one, not the 105 it caused
    seen = {}

    def read_and_clear(box):
        seen["text"], seen["info"] = box.text(), box.informativeText()
        click_button("Clear Error")(box)

    with answering(qtbot, read_and_clear):
        qtbot.mouseClick(indicator, Qt.MouseButton.LeftButton)
    assert seen["text"] == "Controller 1: error 176: Array size wrong"
    assert "Line 23" in seen["info"] and "DIM recipe[9] but array 1" in seen["info"]
    qtbot.waitUntil(lambda: not indicator.isVisible(), timeout=5000)
    assert window.bridge.link.status().error == 0
    assert "Controller 1: error 176 cleared" in window.messages.toPlainText()
    assert "— error" not in window.windowTitle()


def execute_text(window, qtbot, text: str) -> None:
    editor = window.new_file()
    editor.setPlainText(text)
    with answering(qtbot):
        window.actions_by_text["Execute"].trigger()


def test_clear_error_on_the_toolbar_and_restart_in_the_controller_menu(window, qtbot):
    indicator = window.pending_error.indicator
    execute_text(window, qtbot, FAILING)                     # error 171 at line 5, pending
    qtbot.waitUntil(indicator.isVisible, timeout=10_000)
    assert indicator.text() == "⚠ Error 171: Array too small"
    qtbot.mouseClick(window.toolbar.widgetForAction(window.actions_by_text["Clear Error"]), Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: not indicator.isVisible(), timeout=5000)
    # Restart: the running program stops and a pending error goes; parameters and arrays stay (a drive keeps them)
    link = window.bridge.link
    link.write_parameter("KPROP", 77)
    execute_text(window, qtbot, FAILING)                     # pending again
    qtbot.waitUntil(indicator.isVisible, timeout=10_000)
    execute_text(window, qtbot, "main:\nDELAY 10\nGOTO main\n")  # no motion command: it runs, the error stays
    qtbot.waitUntil(lambda: link.status().program_state == "running" and link.status().error == 171,
                    timeout=10_000)
    with answering(qtbot, button_reply(QMessageBox.StandardButton.Yes)):
        window.actions_by_text["Restart..."].trigger()
    qtbot.waitUntil(lambda: "Controller 1: restarted (switched off and on)" in window.messages.toPlainText(),
                    timeout=5000)
    status = link.status()
    assert status.error == 0 and status.program_state == "idle"
    assert link.read_parameter("KPROP") == 77 and [a["size"] for a in link.call("list_arrays")] == [2]
    qtbot.waitUntil(lambda: not indicator.isVisible(), timeout=5000)
