"""A PRINT flood in the IDE: does the embedded controller keep real time, and how fast does Break answer?

Run from the repository root (offscreen; a display is not needed):

    QT_QPA_PLATFORM=offscreen .venv/bin/python benchmarks/print_flood.py [--seconds 5]

The program prints as fast as it can (`main: PRINT "flood …" GOTO main`) on the IDE's embedded controller at real
time (factor 1). Prints ``name: value unit`` lines: ``flood_virtual_ms_per_s`` (virtual ms the controller advanced per
wall second; 1000 = real time), ``flood_lines_per_s`` (lines that reached the Communication pane), ``flood_break_s``
(from Development → Break until the controller reports the break), ``flood_gui_gap_ms`` (the longest the GUI's event
loop stood still). Goals: ~1000 ms/s, Break < 0.2 s, GUI gap < 200 ms.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from PySide6.QtCore import QElapsedTimer, QSettings, QTimer  # noqa: E402
from PySide6.QtWidgets import QApplication  # noqa: E402

from motiontool.controller import schemes  # noqa: E402
from motiontool.ui import gui_gc  # noqa: E402
from motiontool.ui.main_window import MainWindow  # noqa: E402

PROGRAM = 'main:\nPRINT "flood line ", TIME\nGOTO main\n'


def main(argv: list[str] | None = None) -> int:
    schemes.register()  # the window's simulators, as the `motiontool` command registers them
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=5.0)
    args = parser.parse_args(argv)
    app = QApplication.instance() or QApplication([])
    gui_gc.install(app)   # garbage collected on the GUI thread, as in the IDE (ui/app.py): never by a worker
    scratch = tempfile.TemporaryDirectory()
    window = MainWindow(settings=QSettings(f"{scratch.name}/s.ini", QSettings.Format.IniFormat), realtime_factor=1.0)
    window.ask_to_save = False
    window.show()
    lines = {"n": 0}
    window.bridge.printed.connect(lambda *_: lines.__setitem__("n", lines["n"] + 1))
    gaps, clock = [0], QElapsedTimer()
    clock.start()
    beat = QTimer()
    beat.timeout.connect(lambda: gaps.append(clock.restart()))
    beat.start(10)
    editor = window.new_file()
    editor.setPlainText(PROGRAM)
    window.development.execute(ask=False)

    def wait(seconds: float, until=lambda: False) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end and not until():
            app.processEvents()
            time.sleep(0.001)

    wait(1.0)  # settle
    link = window.bridge.link
    t0, v0, n0 = time.monotonic(), link.status().time_ms, lines["n"]
    gaps[:] = [0]
    wait(args.seconds)
    t1, v1, n1 = time.monotonic(), link.status().time_ms, lines["n"]
    start = time.monotonic()
    window.actions_by_text["Break"].trigger()
    wait(30, lambda: link.status().program_state == "break")
    broke = time.monotonic() - start
    print(f"flood_virtual_ms_per_s: {(v1 - v0) / (t1 - t0):.0f} ms/s")
    print(f"flood_lines_per_s: {(n1 - n0) / (t1 - t0):.0f} lines/s")
    print(f"flood_break_s: {broke:.3f} s")
    print(f"flood_gui_gap_ms: {max(gaps)} ms")
    window.controllers.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
