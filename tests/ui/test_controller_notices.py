"""The controller's notices reach the user in the Communication window (issue 17 item 8)."""

from __future__ import annotations


def test_a_positioning_after_motor_off_says_in_the_communication_window_why_the_program_waits(window, qtbot):
    """CR 624-648: a motion command does not imply MOTOR ON, so after MOTOR OFF the POSA waits (decision K11); issue 17
    item 8: "the user needs to see why the program does not go on (a warning in the Communication window …)"."""
    editor = window.current_editor() or window.new_file()
    editor.setPlainText('MOTOR OFF\nPRINT "off"\nPOSA 1000\nPRINT "never"\n')
    window.actions_by_text["Execute"].trigger()
    qtbot.waitUntil(lambda: "POSA waits: the position control is off" in window.messages.toPlainText(),
                    timeout=10000)
    text = window.messages.toPlainText()
    assert "[01] off" in text and "never" not in text
