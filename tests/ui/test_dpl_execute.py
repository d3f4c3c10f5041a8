"""F5 / Esc with a DPL program: the IDE moves to the simulated APC (through its comms Link), downloads the program,
starts it, and Esc stops it; an APOSS program brings the window back to the MCO 305 (issue 20)."""

from __future__ import annotations

from PySide6.QtCore import Qt

PROGRAM = "\n".join([
    "Initial {",
    "s% = APCSetRunMode(APC_DISABLE)",
    "s% = APCSetupOutputChannel(2, 0, 0)",
    "s% = APCEnableOutputChannel()",
    "s% = APCSetSpeedSetPoint(MULDIV(1073741824, 300, 60000))",
    "}",
    "Pos0{",
    "s% = APCSetRunMode(APC_ENABLE)",
    "s% = APCSelectReference(APC_SPEED_REF)",
    "n% = n% + 1",
    "}",
]) + "\n"


def test_f5_runs_a_dpl_program_on_the_apc_and_esc_stops_it(window, qtbot, tmp_path):
    path = tmp_path / "jog.dpl"
    path.write_text(PROGRAM, encoding="utf-8")
    editor = window.open_file(path)
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    assert window.connection.interface_key == "apcsim:" and "APC simulator" in window.windowTitle()
    assert "Executing jog.dpl on controller 1" in window.messages.toPlainText()
    link = window.bridge.link
    assert link.call("identify")["kind"] == "APC"
    qtbot.waitUntil(lambda: link.read_parameter("APC_FB_POS") > 65536, timeout=10_000)   # it turns at 300 rpm
    assert link.status().program_state == "running" and link.status().program == "jog.dpl"
    assert link.call("read_variables", names=["n%"])[0] > 0
    window.actions_by_text["Break"].trigger()
    qtbot.waitUntil(lambda: link.status().program_state == "idle", timeout=5000)
    counted = link.call("read_variables", names=["n%"])[0]
    qtbot.wait(100)
    assert link.call("read_variables", names=["n%"])[0] == counted                        # POS0 no longer runs


def test_a_run_time_error_reaches_the_messages_with_its_place(window, qtbot, tmp_path):
    path = tmp_path / "bad.dpl"
    path.write_text("Initial {\nDIM A%[2]\n}\nPos0{\ni% = i% + 1\nA%[i%] = 1\n}\n", encoding="utf-8")
    editor = window.open_file(path)
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    qtbot.waitUntil(lambda: f"{path}:6:1: error: index 2 is outside A%[0 … 1]" in window.messages.toPlainText(),
                    timeout=10_000)
    assert window.bridge.link.status().program_state == "error"


def test_an_aposs_program_goes_back_to_the_mco(window, qtbot, tmp_path):
    path = tmp_path / "jog.dpl"
    path.write_text(PROGRAM, encoding="utf-8")
    qtbot.keyClick(window.open_file(path), Qt.Key.Key_F5)
    assert window.connection.interface_key == "apcsim:"
    editor = window.new_file()
    editor.setPlainText('PRINT "mco"\n')
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    assert window.connection.interface_key == "sim" and window.bridge.controller_id == 1
    qtbot.waitUntil(lambda: "[01] mco" in window.messages.toPlainText(), timeout=5000)
