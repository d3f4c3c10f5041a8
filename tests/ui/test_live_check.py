"""The live syntax check runs off the GUI thread and a newer edit cancels an older check (issue 18, item 4;
decisions R9). It compiled on the GUI thread after every pause in typing, so a program that compiles slowly -
such as 20 doubling #defines, 32 s - froze the IDE."""

from __future__ import annotations

import threading
import time

from PySide6.QtCore import QElapsedTimer, Qt, QTimer

from motiontool.ui import live_check

BIG = "".join(f"a{i % 50} = a{(i + 1) % 50} * 3 + {i}\n" for i in range(12_000)) + "POSA\n"


def test_typing_stays_responsive_while_a_slow_program_is_checked(window, qtbot, monkeypatch):
    """The user goes on typing while the program is checked, and the event loop keeps running. The check is held
    at its first cancellation poll until the test has typed for a while (on a fast machine the whole check took
    less time than the test needs to see ten timer beats, and the test failed with nothing wrong), then the real
    compiler goes on while the typing does. A check on the GUI thread would stop the beats: the test sees that."""
    typed_a_while = threading.Event()
    hold_first_poll(monkeypatch, typed_a_while)
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
        if len(gaps) > 15:
            typed_a_while.set()
    timer.stop()
    assert len(gaps) > 15
    assert max(gaps[1:]) < 1000, max(gaps)  # the event loop never stood still for a second
    # ...and the check that finally comes belongs to the text in the editor: the error in its last line
    qtbot.waitUntil(lambda: any(d[0] == 12_001 and d[2] == "error" for d in editor.diagnostics()), timeout=60_000)


def hold_first_poll(monkeypatch, release: threading.Event) -> None:
    """The live check of BIG waits at its first cancellation poll until `release` is set, then compiles as
    always (the real compiler, polling the real cancellation)."""
    real = live_check.compile_source

    def held_at_first_poll(text, path, cancelled):
        if text != BIG:
            return real(text, path, cancelled=cancelled)

        def poll() -> bool:
            release.wait(60)
            return cancelled()
        return real(text, path, cancelled=poll)

    monkeypatch.setattr(live_check, "compile_source", held_at_first_poll)


def test_a_newer_edit_cancels_the_older_check(window, qtbot, monkeypatch):
    """The big check is held at its first cancellation poll until the newer edit's check has been asked for, so it
    is surely still running when that edit comes, on any machine (it finished first, and there was nothing to
    cancel, when the machine happened to be fast enough or the typing's check slow to be asked for). Holding
    it changes nothing else: the real compiler then sees the newer edit and stops."""
    newer_asked = threading.Event()
    hold_first_poll(monkeypatch, newer_asked)
    editor = window.new_file()
    qtbot.waitUntil(lambda: not window.checker.busy, timeout=10_000)
    shown, cancelled = window.checker.finished, window.checker.cancelled
    editor.setPlainText(BIG)
    qtbot.waitUntil(lambda: window.checker.busy, timeout=10_000)
    editor.selectAll()
    qtbot.keyClicks(editor, "POSA 100")  # replaces the program: an error on line 2
    qtbot.keyClick(editor, Qt.Key.Key_Return)
    qtbot.keyClicks(editor, "VEL")
    qtbot.waitUntil(lambda: window.checker.newest_text() == editor.toPlainText(), timeout=30_000)
    newer_asked.set()
    qtbot.waitUntil(lambda: [(d[0], d[2]) for d in editor.diagnostics()] == [(2, "error")], timeout=30_000)
    assert window.checker.cancelled > cancelled  # the big check was stopped, not finished and thrown away
    assert window.checker.finished == shown + 1  # its diagnostics (line 12 001) were never shown
