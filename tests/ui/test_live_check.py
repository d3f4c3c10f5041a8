"""The live syntax check runs off the GUI thread and a newer edit cancels an older check (issue 18, item 4;
decisions R9). It compiled on the GUI thread after every pause in typing, so a program that compiles slowly -
such as 20 doubling #defines, 32 s - froze the IDE."""

from __future__ import annotations

import time

from PySide6.QtCore import QElapsedTimer, Qt, QTimer

BIG = "".join(f"a{i % 50} = a{(i + 1) % 50} * 3 + {i}\n" for i in range(12_000)) + "POSA\n"
# Long enough to be still compiling when the typing's check comes (600 ms after the last key) on an idle machine
# too: BIG alone (~1 s idle) could finish first, and then there was nothing to cancel.
BIGGER = BIG * 5


def test_typing_stays_responsive_while_a_slow_program_is_checked(window, qtbot):
    editor = window.new_file()
    qtbot.waitUntil(lambda: not window.checker.busy, timeout=10_000)
    editor.setPlainText(BIG)  # a paste: the live check starts after the pause
    qtbot.waitUntil(lambda: window.checker.busy, timeout=10_000)
    gaps, clock = [], QElapsedTimer()
    clock.start()

    def beat() -> None:
        gaps.append(clock.restart())

    timer = QTimer()
    timer.timeout.connect(beat)
    timer.start(20)
    editor.moveCursor(editor.textCursor().MoveOperation.End)
    started = time.monotonic()
    while window.checker.busy and time.monotonic() - started < 60:
        qtbot.keyClick(editor, Qt.Key.Key_Space)  # the user goes on typing...
        qtbot.keyClick(editor, Qt.Key.Key_Backspace)
        qtbot.wait(30)
    timer.stop()
    assert len(gaps) > 10
    assert max(gaps[1:]) < 1000, max(gaps)  # the event loop never stood still for a second
    # ...and the check that finally comes belongs to the text in the editor: the error in its last line
    qtbot.waitUntil(lambda: any(d[0] == 12_001 and d[2] == "error" for d in editor.diagnostics()), timeout=60_000)


def test_a_newer_edit_cancels_the_older_check(window, qtbot):
    editor = window.new_file()
    qtbot.waitUntil(lambda: not window.checker.busy, timeout=10_000)
    shown, cancelled = window.checker.finished, window.checker.cancelled
    editor.setPlainText(BIGGER)
    qtbot.waitUntil(lambda: window.checker.busy, timeout=10_000)
    qtbot.wait(200)  # the big check is under way
    started = time.monotonic()
    editor.selectAll()
    qtbot.keyClicks(editor, "POSA 100")  # replaces the program: an error on line 2
    qtbot.keyClick(editor, Qt.Key.Key_Return)
    qtbot.keyClicks(editor, "VEL")
    qtbot.waitUntil(lambda: [(d[0], d[2]) for d in editor.diagnostics()] == [(2, "error")], timeout=30_000)
    assert window.checker.cancelled > cancelled  # the big check was stopped, not finished and thrown away
    assert window.checker.finished == shown + 1  # its diagnostics (line 12 001) were never shown
    assert time.monotonic() - started < 10
