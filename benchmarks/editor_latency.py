"""Editor latency on a 5 000-line APOSS program (offscreen Qt; goal: at most 5 ms per keystroke).

Run from the repository root:

    QT_QPA_PLATFORM=offscreen .venv/bin/python benchmarks/editor_latency.py [--lines 5000] [--keys 300]

Measures
- ``editor_open_5000_lines``: CodeEditor creation, setPlainText, show and the first paint (the first paint is
  forced with ``viewport().repaint()`` after the events of ``show`` are processed);
- ``editor_keystroke_median`` / ``editor_keystroke_p95``: typing in the middle of the program, one real key
  event at a time (``QTest.keyClick``), each followed by ``QApplication.processEvents()`` so re-highlighting,
  the margin, the completion popup and the repaint are included;
- ``editor_keystroke_max``: the slowest of those keystrokes, usually the first auto-completion (the third
  letter of a word builds the program's symbol list if there is none yet: the editor builds it in the first
  400 ms pause after the text changed, and this benchmark types right after opening) or a Return (every
  line below moves: the whole view and the margin are repainted).

The editor is a bare CodeEditor on the offscreen platform: the main window's per-keystroke work (caret
position in the status bar, restarting its live-check timer; about 0.4 ms) and the flush to a real screen
are not included.

The program comes from ``compile_speed.generate_program`` (the compiler benchmark's realistic generator);
exit status 1 if the median keystroke is above the goal.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from PySide6.QtCore import QEvent, QObject, Qt  # noqa: E402
from PySide6.QtTest import QTest  # noqa: E402
from PySide6.QtWidgets import QApplication  # noqa: E402

from motiontool.ui.editor import CodeEditor  # noqa: E402

GOAL_MS = 5.0
TYPED = "x = abc + 12 // note "


def program(lines: int) -> str:
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    try:
        from compile_speed import generate_program  # the compiler benchmark's generator

        text = generate_program(lines)
    except Exception:  # noqa: BLE001 - any failure: fall back to a simple program
        body = [f"pos_{i} = {i} * 10 // step {i}\nPOSA pos_{i}\nIF (IN 3) THEN\n  SET KPROP {i % 90}\nENDIF"
                for i in range(lines // 5 + 1)]
        text = "\n".join(body)
    return "\n".join(text.split("\n")[:lines])


class PaintCounter(QObject):
    def __init__(self) -> None:
        super().__init__()
        self.paints = 0

    def eventFilter(self, obj, event) -> bool:  # noqa: N802 (Qt override)
        if event.type() == QEvent.Type.Paint:
            self.paints += 1
        return False


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=5000)
    parser.add_argument("--keys", type=int, default=300)
    args = parser.parse_args(argv)
    app = QApplication.instance() or QApplication(sys.argv)
    text = program(args.lines)
    counter = PaintCounter()

    start = time.perf_counter()
    editor = CodeEditor()
    editor.resize(1000, 800)
    editor.setPlainText(text)
    editor.viewport().installEventFilter(counter)
    editor.show()
    app.processEvents()
    editor.viewport().repaint()
    open_ms = (time.perf_counter() - start) * 1000
    assert counter.paints > 0, "the editor was not painted"

    editor.goto_line(editor.blockCount() // 2)
    editor.moveCursor(editor.textCursor().MoveOperation.EndOfLine)
    app.processEvents()
    times = []
    for i in range(args.keys):
        ch = TYPED[i % len(TYPED)]
        t0 = time.perf_counter()
        if ch == " " and i % (3 * len(TYPED)) == len(TYPED) - 1:
            QTest.keyClick(editor, Qt.Key.Key_Return)
        else:
            QTest.keyClick(editor, ch)
        app.processEvents()
        times.append((time.perf_counter() - t0) * 1000)
    median = statistics.median(times)
    print(f"editor_keystroke_median: {median:.2f} ms")
    print(f"editor_keystroke_p95: {percentile(times, 0.95):.2f} ms")
    print(f"editor_keystroke_max: {max(times):.2f} ms")
    print(f"editor_open_{args.lines}_lines: {open_ms:.1f} ms")
    print(f"(lines: {editor.blockCount()}, keys: {len(times)}, goal: <= {GOAL_MS} ms per keystroke)")
    editor.close()
    return 0 if median <= GOAL_MS else 1


if __name__ == "__main__":
    raise SystemExit(main())
