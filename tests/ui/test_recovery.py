"""Autosave and crash recovery belong to one IDE instance (issue 18, item 2; decisions R8).

A second instance saw the first one's live autosave, claimed "not closed properly" and, answered No, deleted it;
recover() cleared the folder right after reopening, so a second crash within 30 s lost everything; autosave ran
every 30 s. Now: a session folder per instance, locked while it runs; only sessions of IDEs that are gone are
offered; copies live until the buffer is saved or discarded; autosave follows typing by a couple of seconds.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest
from PySide6.QtCore import QSettings, Qt
from PySide6.QtWidgets import QMessageBox

from motiontool.ui.main_window import MainWindow
from motiontool.ui.recovery import AUTOSAVE_AFTER_MS, offer_recovery
from tests.answer_dialogs import Answers

Button = QMessageBox.StandardButton


@pytest.fixture
def ide(qtbot, tmp_path):
    """Start IDE windows on one configuration folder, as several `motiontool` processes of one user would."""
    made = []

    def start() -> MainWindow:
        w = MainWindow(settings=QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat),
                       realtime_factor=50.0)
        w.ask_to_save = False
        qtbot.addWidget(w)
        w.show()
        made.append(w)
        return w

    yield start
    for w in made:
        for editor in w.editors():
            editor.document().setModified(False)
        w.bridge.detach(close=False)
        w.controllers.close()


def copies(tmp_path) -> dict[str, str]:
    """Every autosaved buffer on disk: file → text."""
    found = {}
    for path in (tmp_path / "motiontool" / "recovery").glob("session-*/buffer-*.json"):
        found[str(path)] = json.loads(path.read_text(encoding="utf-8"))["text"]
    return found


def test_autosave_follows_typing_and_lives_until_the_buffer_is_saved(ide, qtbot, tmp_path):
    window = ide()
    program = tmp_path / "p.m"
    program.write_text("a = 1\n", encoding="utf-8")
    editor = window.open_file(program)
    editor.setFocus()
    started = time.monotonic()
    qtbot.keyClicks(editor, "b = 2")
    qtbot.waitUntil(lambda: any("b = 2" in t for t in copies(tmp_path).values()), timeout=10_000)
    assert time.monotonic() - started < AUTOSAVE_AFTER_MS / 1000 + 5  # seconds, not the old 30 s
    window.actions_by_text["Save"].trigger()
    assert copies(tmp_path) == {}
    qtbot.keyClicks(editor, "c = 3")
    qtbot.waitUntil(lambda: len(copies(tmp_path)) == 1, timeout=10_000)
    window.ask_to_save = True
    with Answers(qtbot, Button.Discard):
        window.actions_by_text["Close"].trigger()
    assert copies(tmp_path) == {}


def test_a_running_instance_is_never_offered_or_robbed_of_its_autosaves(ide, qtbot, tmp_path):
    first = ide()
    editor = first.new_file()
    qtbot.keyClicks(editor, 'PRINT "typed in the first IDE"')
    qtbot.waitUntil(lambda: len(copies(tmp_path)) == 1, timeout=10_000)
    before = copies(tmp_path)
    second = ide()
    with Answers(qtbot):  # no question at all
        assert offer_recovery(second) == 0
    assert copies(tmp_path) == before


CRASHING_IDE = """
import sys, time
from PySide6.QtCore import QSettings
from PySide6.QtWidgets import QApplication
from motiontool.ui.main_window import MainWindow
app = QApplication([])
w = MainWindow(settings=QSettings(sys.argv[1], QSettings.Format.IniFormat), realtime_factor=1.0)
w.show()
editor = w.new_file()
editor.insertPlainText('PRINT "typed before the crash"\\n')
w.autosave()
print("autosaved", flush=True)
while True:
    app.processEvents()
    time.sleep(0.05)
"""


def test_a_crashed_ide_is_offered_once_and_its_copies_survive_a_second_crash(ide, qtbot, tmp_path):
    crashing = subprocess.Popen([sys.executable, "-c", CRASHING_IDE, str(tmp_path / "settings.ini")],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                env={**os.environ, "QT_QPA_PLATFORM": "offscreen"})
    try:
        assert crashing.stdout.readline().strip() == "autosaved", crashing.stderr.read()
        living = ide()
        with Answers(qtbot):  # while the other IDE runs, nothing is offered
            assert offer_recovery(living) == 0
    finally:
        crashing.send_signal(signal.SIGKILL)  # kill -9: no clean-up of any kind
        crashing.wait(timeout=30)
    (crashed_copy,) = copies(tmp_path)
    restarted = ide()
    with Answers(qtbot, Button.Yes) as answers:
        assert offer_recovery(restarted) == 1
    assert answers.seen[0].text.startswith("motiontool was not closed properly. 1 program(s) had unsaved changes")
    editor = restarted.current_editor()
    assert editor.toPlainText() == 'PRINT "typed before the crash"\n' and editor.document().isModified()
    # The restored buffer is already autosaved in the new IDE's session, before the old copy went: a second
    # crash now loses nothing. And the other running IDE (`living`) is not offered the buffer again.
    now = copies(tmp_path)
    assert crashed_copy not in now and list(now.values()) == ['PRINT "typed before the crash"\n']
    with Answers(qtbot):
        assert offer_recovery(ide()) == 0


def test_discard_deletes_and_not_now_keeps_the_copies_of_a_crashed_ide(ide, qtbot, tmp_path):
    folder = tmp_path / "motiontool" / "recovery" / "session-999999999-00000000"
    folder.mkdir(parents=True)
    (folder / "buffer-1.json").write_text(json.dumps({"version": 2, "original": "", "text": "x = 1\n"}))
    with Answers(qtbot, Button.Cancel):
        assert offer_recovery(ide()) == 0
    assert folder.exists()
    with Answers(qtbot, Button.No):
        assert offer_recovery(ide()) == 0
    assert not folder.exists()


def test_an_autosave_that_cannot_be_written_is_said_once(ide, qtbot, tmp_path):
    window = ide()
    (tmp_path / "motiontool" / "recovery").write_text("not a folder")  # e.g. a full disk, a read-only home
    editor = window.new_file()
    qtbot.keyClicks(editor, "a = 1")
    qtbot.waitUntil(lambda: "Autosave failed" in window.messages.toPlainText(), timeout=10_000)
    qtbot.keyClick(editor, Qt.Key.Key_Return)
    window.autosave()
    assert window.messages.toPlainText().count("Autosave failed") == 1
    assert window.isVisible() and editor.toPlainText() == "a = 1\n"


def test_restore_replaces_the_empty_untitled_tab_of_the_start_but_keeps_typed_work(ide, qtbot, tmp_path):
    """At start-up the IDE opens an empty Untitled program, then offers recovery (ui/app.py): after Restore the
    restored programs take its place instead of standing beside an empty tab; an Untitled with text stays."""
    def crashed_session(name: str, text: str) -> None:
        folder = tmp_path / "motiontool" / "recovery" / f"session-99999999{name}-00000000"
        folder.mkdir(parents=True)
        (folder / "buffer-1.json").write_text(json.dumps({"version": 2, "original": "", "text": text}))

    crashed_session("8", "x = 1\n")
    window = ide()
    window.new_file()
    with Answers(qtbot, Button.Yes):
        assert offer_recovery(window) == 1
    assert [e.toPlainText() for e in window.editors()] == ["x = 1\n"]
    # a program without a file, changed:
    assert [window.tabs.tabText(i) for i in range(window.tabs.count())] == ["Untitled *"]

    crashed_session("9", "y = 2\n")
    other = ide()
    typed = other.new_file()
    qtbot.keyClicks(typed, "z = 3")
    with Answers(qtbot, Button.Yes):
        assert offer_recovery(other) == 1
    assert [e.toPlainText() for e in other.editors()] == ["z = 3", "y = 2\n"]
