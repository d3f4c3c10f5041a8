"""Tools ▸ I/O Panel (issue 23 item 4): samples that wait for buttons, a probe or a potentiometer run when the user
sets the inputs with the panel's widgets; outputs light its lamps; a header's Test-inputs are offered and applied.

CR 1569-1570: "The status of a digital input can be read with the IN command. Depending on the signal level, a 0
or 1 will be given." CR 3097-3112: "OUT n s … s = condition 0 = OFF". CR 1608: "Terminal 53/54: -1000 – 1000 =
-10 V – 10 V"."""

from __future__ import annotations

import re

from PySide6.QtCore import Qt
from PySide6.QtTest import QTest

from tests.modal import answering
from tests.shots import shot_path
from tests.test_samples import SAMPLES_DIR, parse_header

SCREENSHOT = "io_panel.png"   # docs/screenshots/ (tests/shots.py)
KEY_MS = 120   # a human's pace between keys


def open_sample(window, name: str) -> None:
    """File ▸ Sample ▸ name."""
    next(a for a in window.samples_menu.actions() if a.text() == name).trigger()


def open_panel(window):
    window.actions_by_text["I/O Panel"].trigger()
    panel = window.io_panel
    assert panel.dock.isVisible()
    return panel


def controller_lines(window, before: int) -> list[str]:
    lines = window.messages.toPlainText().splitlines()[before:]
    return [line.removeprefix("[01] ") for line in lines if line.startswith("[01] ")]


def printed(window, before: int) -> list[str]:
    return [line for line in controller_lines(window, before) if not line.startswith("program ")]


def execute(window, qtbot) -> int:
    before = len(window.messages.toPlainText().splitlines())
    with answering(qtbot):
        window.actions_by_text["Execute"].trigger()
    return before


def wait_line(window, qtbot, before: int, text: str, timeout: int = 20_000) -> None:
    qtbot.waitUntil(lambda: any(line.startswith(text) for line in controller_lines(window, before)), timeout=timeout)


def click(qtbot, widget) -> None:
    qtbot.mouseClick(widget, Qt.MouseButton.LeftButton)


def test_sample_05_runs_with_the_panels_toggle_and_push_buttons(window, qtbot):
    """05_jog_inputs waits (WAITI 1 ON) for a jog button, jogs while 1 or 2 is held, and ends on input 3."""
    open_sample(window, "05_jog_inputs.m")
    panel = open_panel(window)
    before = execute(window, qtbot)
    wait_line(window, qtbot, before, "waiting for a jog button")
    qtbot.wait(300)
    assert printed(window, before) == ["waiting for a jog button"]   # it waits: nothing else comes
    click(qtbot, panel.toggles[1])                                             # input 1 on and it stays on
    wait_line(window, qtbot, before, "direction 1 at APOS")
    click(qtbot, panel.toggles[1])                                             # off again
    wait_line(window, qtbot, before, "direction 0 at APOS")
    push = panel.pushes[2]                                                     # held: backwards while held
    QTest.mousePress(push, Qt.MouseButton.LeftButton)
    wait_line(window, qtbot, before, "direction -1 at APOS")
    QTest.mouseRelease(push, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: sum(line.startswith("direction 0") for line in printed(window, before)) == 2,
                    timeout=20_000)
    click(qtbot, panel.toggles[3])
    wait_line(window, qtbot, before, "program ended")
    # the documented lines, with the positions the user's own timing gave
    expect = [re.escape(line) for line in parse_header(SAMPLES_DIR / "05_jog_inputs.m").expect]
    expect = [re.sub(r"APOS\\ \d+", r"APOS\\ -?\\d+", line) for line in expect]
    got = printed(window, before)
    assert len(got) == len(expect) and all(re.fullmatch(e, g) for e, g in zip(expect, got, strict=True)), got
    assert not panel.toggles[1].isChecked() and panel.toggles[3].isChecked()


def test_an_output_lamp_follows_out_and_a_toggle_releases_the_program(window, qtbot):
    editor = window.new_file()
    editor.setPlainText("OUT 3 1\nOUT 22 1\nWHILE IN 4 == 0 DO\n    DELAY 10\nENDWHILE\nOUT 3 0\n"
                        "PRINT \"input 4 seen\"\n")
    panel = open_panel(window)
    lamp = panel.lamps[3]
    assert lamp.property("on") is False
    before = execute(window, qtbot)
    qtbot.waitUntil(lambda: lamp.property("on") is True, timeout=10_000)
    assert panel.lamps[22].property("on") is True and panel.lamps[1].property("on") is False
    click(qtbot, panel.toggles[4])
    wait_line(window, qtbot, before, "input 4 seen")
    qtbot.waitUntil(lambda: lamp.property("on") is False, timeout=10_000)
    assert panel.lamps[22].property("on") is True   # outputs keep their state after the program (CR 3131-3135)


def test_the_analog_slider_moved_by_keys_sets_inad(window, qtbot):
    editor = window.new_file()
    editor.setPlainText("WHILE IN 1 == 0 DO\n    DELAY 10\nENDWHILE\nPRINT \"INAD \", INAD 53\n")
    panel = open_panel(window)
    before = execute(window, qtbot)
    slider = panel.sliders[53]
    slider.setFocus()
    qtbot.waitUntil(slider.hasFocus, timeout=5000)
    for key in [Qt.Key.Key_Right] * 5 + [Qt.Key.Key_PageUp] * 2 + [Qt.Key.Key_Left]:
        QTest.keyClick(slider, key, delay=KEY_MS)
    assert slider.value() == 240 and panel.analog_labels[53].text() == "+240  (+2.40 V)"
    qtbot.waitUntil(lambda: panel.jobs.pending == 0, timeout=5000)
    click(qtbot, panel.toggles[1])
    wait_line(window, qtbot, before, "INAD ")
    assert "INAD 240" in controller_lines(window, before)
    for _ in range(12):  # the slider stops at INAD's end, 10 V
        QTest.keyClick(slider, Qt.Key.Key_PageUp)
    assert slider.value() == 1000


def test_a_samples_test_inputs_are_offered_and_applied_at_execute(window, qtbot):
    """25_analog_speed's header asks for 1=0@0 53=500@0 … 1=1@5500: opening it offers them; with Apply at Execute
    the run prints exactly what its header documents, as `motiontool run --input` does."""
    open_sample(window, "25_analog_speed.m")
    panel = window.io_panel
    assert panel.dock.isVisible() and panel.offer.isVisible()
    assert "25_analog_speed.m</b> asks for test inputs 1=0@0 53=500@0 53=-250@1500" in panel.offer_label.text()
    assert "Apply at Execute" in window.messages.toPlainText()
    click(qtbot, panel.apply_button)
    assert panel.apply_button.isChecked()
    before = execute(window, qtbot)
    wait_line(window, qtbot, before, "program ended", timeout=30_000)
    got = printed(window, before)
    assert got == parse_header(SAMPLES_DIR / "25_analog_speed.m").expect
    qtbot.waitUntil(lambda: panel.toggles[1].isChecked(), timeout=5000)  # the scheduled input shows in the panel


def test_test_settings_are_written_when_chosen_and_a_bad_header_names_its_line(window, qtbot):
    """22_app_parameters reads its feed length from parameter 1900 (Test-settings: 1900=7500)."""
    open_sample(window, "22_app_parameters.m")
    panel = window.io_panel
    assert "settings 1900=7500" in panel.offer_label.text() and not panel.apply_button.isChecked()
    click(qtbot, panel.apply_button)
    before = execute(window, qtbot)
    wait_line(window, qtbot, before, "program ended", timeout=30_000)
    assert printed(window, before) == parse_header(SAMPLES_DIR / "22_app_parameters.m").expect
    editor = window.new_file()
    editor.setPlainText("// Title: bad\n// Test-inputs: 1=1@500 1on\nPRINT \"ran\"\n")
    before = execute(window, qtbot)
    assert "Untitled.m line 2: Test-inputs entry 1on: give N=V@T (input, value, ms)" in window.messages.toPlainText()
    wait_line(window, qtbot, before, "ran")   # not chosen: the header's fault does not stop Execute
    editor.setPlainText("// Title: good\n// Test-inputs: 7=1@0\nWAITI 7 ON\nPRINT \"input 7 on\"\n")
    execute(window, qtbot)                     # the first Execute offers; the user then chooses
    assert panel.offered is editor and "inputs 7=1@0" in panel.offer_label.text()
    assert not panel.apply_button.isChecked()  # another program: chosen anew
    window.actions_by_text["Break"].trigger()
    click(qtbot, panel.apply_button)
    editor.setPlainText("// Title: bad\n// Test-inputs: 7=1@x\nPRINT \"ran\"\n")
    before = execute(window, qtbot)
    assert ("Untitled.m line 2: Test-inputs entry 7=1@x: time x: give a whole number from 0 to 864000000: program "
            "not executed") in window.messages.toPlainText()
    qtbot.wait(200)
    assert "ran" not in controller_lines(window, before)


def test_on_a_controller_without_set_input_the_inputs_are_disabled_and_say_why(window, qtbot, tmp_path):
    """The simulated APC (a DPL program's F5) has no MCO terminals to set: the panel says so on every input."""
    from tests.ui.test_dpl_execute import PROGRAM

    panel = open_panel(window)
    path = tmp_path / "jog.dpl"
    path.write_text(PROGRAM, encoding="utf-8")
    editor = window.open_file(path)
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    qtbot.waitUntil(lambda: panel.can_set is False, timeout=10_000)
    assert not panel.inputs_box.isEnabled() and not panel.analog_box.isEnabled() and panel.note.isVisible()
    why = panel.toggles[1].toolTip()
    assert why.startswith("The inputs of Unidrive SP + SM-Applications APC (simulated) cannot be set from here")
    assert panel.pushes[12].toolTip() == why and panel.sliders[53].toolTip() == why
    window.actions_by_text["Break"].trigger()
    back = window.new_file()
    back.setPlainText("PRINT \"on the MCO\"\n")
    execute(window, qtbot)                   # an APOSS program takes the window back to the MCO 305
    qtbot.waitUntil(lambda: panel.can_set is True, timeout=10_000)
    assert panel.inputs_box.isEnabled() and not panel.note.isVisible()
    assert panel.toggles[1].toolTip() == "Input 1: click to switch it on or off"


def test_screenshot_of_the_panel(window, qtbot):
    open_sample(window, "06_touch_probe.m")
    panel = window.io_panel
    editor = window.new_file()
    editor.setPlainText("OUT 1 1\nOUT 4 1\nOUT 21 1\nWAITI 12 ON\n")
    before = execute(window, qtbot)
    click(qtbot, panel.toggles[2])
    click(qtbot, panel.toggles[8])
    panel.sliders[53].setValue(350)
    qtbot.waitUntil(lambda: panel.lamps[21].property("on") is True, timeout=10_000)
    panel.dock.setFloating(True)
    panel.dock.resize(panel.dock.sizeHint())
    qtbot.wait(300)
    assert panel.dock.grab().save(str(shot_path(SCREENSHOT)))
    click(qtbot, panel.toggles[12])
    wait_line(window, qtbot, before, "program ended")
