"""A PRINT flood in the IDE keeps real time and Break answers at once (issue 18, item 9; decisions K82)."""

from __future__ import annotations

import time

from PySide6.QtCore import QSettings

from motiontool.ui.main_window import MainWindow

FLOOD = 'main:\nPRINT "line ", TIME\nGOTO main\n'


def test_a_print_flood_in_the_ide_keeps_real_time_and_break_answers_at_once(qtbot, tmp_path):
    """Under a PRINT flood the IDE's controller fell behind real time (251 ms per wall second) and Break took up
    to 1.3 s: every line went to the GUI as its own event. Now the IDE's link takes about one line per ms and the
    GUI gets them in batches."""
    window = MainWindow(settings=QSettings(str(tmp_path / "s.ini"), QSettings.Format.IniFormat),
                        realtime_factor=1.0)
    window.ask_to_save = False
    qtbot.addWidget(window)
    window.show()
    try:
        editor = window.new_file()
        editor.setPlainText(FLOOD)
        window.actions_by_text["Execute"].trigger()
        qtbot.waitUntil(lambda: "[01] line" in window.messages.toPlainText(), timeout=10_000)
        link = window.bridge.link
        wall, virtual = time.monotonic(), link.status().time_ms
        qtbot.wait(2000)
        wall, virtual = time.monotonic() - wall, link.status().time_ms - virtual
        assert virtual > 0.5 * wall * 1000, (virtual, wall)  # real time is kept (48 ms/s before, on a busy machine)
        asked = time.monotonic()
        window.actions_by_text["Break"].trigger()
        qtbot.waitUntil(lambda: link.status().program_state == "break", timeout=10_000)
        assert time.monotonic() - asked < 1.0
        lines = window.messages.toPlainText().count("[01] line")
        assert lines > 200
    finally:
        window.bridge.detach(close=False)
        window.controllers.close()
