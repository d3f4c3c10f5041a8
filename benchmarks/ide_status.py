"""The IDE window on a slow FC line (issue 14): `motiontool drive --listen fc:pty,baud=9600` in its own process and
an APOSS window (offscreen) connected to its controller 1, which runs a program that prints 4 lines a second. For
`--seconds` (default 20) a 10 ms timer in the GUI thread notes when it fires. Prints
- ide_gui_stall_max_9600_baud: the longest the GUI thread did not get to its timer (ms; the timer's own 10 ms
  included) — a status exchange asked on the GUI thread stops the window for its whole wire time (~0.26 s),
- ide_gui_stall_p99_9600_baud: the 99th percentile of those gaps (ms),
- ide_status_answers_9600_baud: status answers that reached the window per second (the status is asked every
  `status_interval_s`, 2.6 s at 9600 baud),
- ide_printed_lines_9600_baud: PRINT lines of the program that reached the Communication pane per second (events),
- ide_axis_dialog_longest_stall: then, the program still running, Controller ▸ Parameters ▸ Axis is opened and left
  open until every value is shown; the longest gap of the 10 ms timer from just before the menu entry until then
  (ms; goal <= 50, issue 27 item 2: the ~115 reads stood the window still 6.6 s when they ran on the GUI thread),
- ide_axis_dialog_longest_busy: the most CPU time the GUI thread spent between two of those timer calls (ms): on a
  loaded machine a stall is mostly waiting for a core; this is the part the window's own work causes,
- ide_axis_dialog_values_shown: seconds from the menu entry until every value of the dialog is shown,
- ide_watch_longest_stall / ide_watch_longest_busy: the same while the Watch polls 4 process data and 2 parameters
  every 250 ms for `--seconds` (each poll is 6 requests, ~0.4 s of the line at 9600 baud),
- ide_watch_polls: Watch polls whose values reached the pane per second,
- ide_polling_scope_longest_stall / _longest_busy / _polls: the same while the oscilloscope polls APOS, CPOS and
  TRACKERR every 100 ms (a poll is one request of 4 signals; the reads go on the scope's poll thread).
- ide_connect_longest_stall / _longest_busy / ide_connect_seconds: the window connecting to controller 1 (as Esc
  does: open, identify) with the 10 ms timer running; before issue 27 item 2 the window stood still the whole time,
- ide_execute_longest_stall / _longest_busy / ide_execute_seconds: the same for Execute (status, download, start),
- ide_download_all_longest_stall / _longest_busy / ide_download_all_seconds: the same for Development ▸ Download
  all with Download and Verify (delete, download, upload to compare) on controller 1, from Start until done,
- ide_prepare_singlestep_* / ide_singlestep_* / ide_end_debug_*: the same, last, for the debugger's Prepare
  Singlestep (status, break, debug download, breakpoints, start), one Singlestep and End Debug.
`--baud` sets another baud rate (the names of the first four follow it)."""

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

from link_fc import start_drive

PROGRAM = """main:
PRINT "tick ", TIME
DELAY 250
GOTO main
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--baud", type=int, default=9600)
    args = parser.parse_args()
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtCore import QEventLoop, QSettings, QTimer
    from PySide6.QtWidgets import QApplication

    from motiontool.controller import schemes
    from motiontool.session.controllers import InterfaceConfig
    from motiontool.ui import gui_gc
    from motiontool.ui.main_window import MainWindow
    from motiontool.ui.parameter_dialogs import ParametersDialog

    schemes.register()  # the window's simulators, as the `motiontool` command registers them

    app = QApplication.instance() or QApplication(sys.argv)

    gui_gc.install(app)   # garbage collected on the GUI thread, as in the IDE (ui/app.py): never by a worker
    proc, url = start_drive(args.baud)
    with tempfile.TemporaryDirectory() as tmp:
        window = MainWindow(settings=QSettings(f"{tmp}/settings.ini", QSettings.Format.IniFormat))
        window.ask_to_save = False
        window.show()
        try:
            window.controllers.set_default(InterfaceConfig("fc", url.removeprefix("fc:"), args.baud, 1, 1))
            connected, *connect = measured(window, lambda: window.connection.select(1), QEventLoop, QTimer)
            if not connected:
                raise SystemExit(window.messages.toPlainText())
            editor = window.new_file()
            editor.setPlainText(PROGRAM)
            window.save(editor=editor, path=Path(tmp) / "tick.m")
            download = download_all(app, window, QEventLoop, QTimer)
            # a command: it waits for its download (off the GUI thread: the window paints meanwhile)
            _, *execute = measured(window, window.actions_by_text["Execute"].trigger, QEventLoop, QTimer)
            for name, (stall, busy, took) in (("connect", connect), ("download_all", download),
                                              ("execute", execute)):
                print(f"ide_{name}_longest_stall: {stall:.0f} ms")
                print(f"ide_{name}_longest_busy: {busy:.0f} ms")
                print(f"ide_{name}_seconds: {took:.2f} s")
            answers, ticks = [], []
            window.bridge.status_changed.connect(lambda status: answers.append(status.time_ms))
            timer = QTimer(window, interval=10, timeout=lambda: ticks.append(time.monotonic()))
            app.processEvents()
            answers.clear()
            printed = window.messages.toPlainText().count("tick ")
            timer.start()
            loop = QEventLoop()
            QTimer.singleShot(int(1000 * args.seconds), loop.quit)
            loop.exec()
            timer.stop()
            printed = window.messages.toPlainText().count("tick ") - printed
            gaps = sorted(1000 * (b - a) for a, b in zip(ticks, ticks[1:], strict=False))
            span = ticks[-1] - ticks[0]
            print(f"ide_gui_stall_max_{args.baud}_baud: {gaps[-1]:.0f} ms")
            print(f"ide_gui_stall_p99_{args.baud}_baud: {gaps[int(0.99 * (len(gaps) - 1))]:.0f} ms")
            print(f"ide_status_answers_{args.baud}_baud: {len(answers) / span:.2f} /s")
            print(f"ide_printed_lines_{args.baud}_baud: {printed / span:.2f} /s")
            stall, busy, shown = axis_dialog(app, window, ParametersDialog, QEventLoop, QTimer)
            print(f"ide_axis_dialog_longest_stall: {stall:.0f} ms")
            print(f"ide_axis_dialog_longest_busy: {busy:.0f} ms")
            print(f"ide_axis_dialog_values_shown: {shown:.1f} s")
            stall, busy, polls = watch(window, args.seconds, QEventLoop, QTimer)
            print(f"ide_watch_longest_stall: {stall:.0f} ms")
            print(f"ide_watch_longest_busy: {busy:.0f} ms")
            print(f"ide_watch_polls: {polls:.2f} /s")
            stall, busy, polls = polling_scope(window, args.seconds, QEventLoop, QTimer)
            print(f"ide_polling_scope_longest_stall: {stall:.0f} ms")
            print(f"ide_polling_scope_longest_busy: {busy:.0f} ms")
            print(f"ide_polling_scope_polls: {polls:.2f} /s")
            for name, entry in (("prepare_singlestep", "Prepare Singlestep"), ("singlestep", "Singlestep"),
                                ("end_debug", "End Debug")):   # last: Prepare stops the ticking program
                _, stall, busy, took = measured(window, window.actions_by_text[entry].trigger, QEventLoop, QTimer)
                print(f"ide_{name}_longest_stall: {stall:.0f} ms")
                print(f"ide_{name}_longest_busy: {busy:.0f} ms")
                print(f"ide_{name}_seconds: {took:.2f} s")
        finally:
            window.bridge.detach(close=False)
            window.controllers.close()
            window.close()
            proc.terminate()
            proc.wait(timeout=20)


def measured(window, act, QEventLoop, QTimer):  # noqa: N803 - Qt's names
    """`act()` with a 10 ms timer running: (its result, longest gap of the timer in ms, most GUI-thread CPU time in
    one gap in ms, seconds `act` took). The timer runs a moment before and after, so a window that stood still
    for the whole of `act` shows that as one gap."""
    ticks: list[tuple[float, float]] = []
    timer = QTimer(window, interval=10, timeout=lambda: ticks.append((time.monotonic(), time.thread_time())))
    timer.start()
    pause(100, QEventLoop, QTimer)
    started = time.monotonic()
    result = act()
    took = time.monotonic() - started
    pause(100, QEventLoop, QTimer)
    timer.stop()
    pairs = list(zip(ticks, ticks[1:], strict=False))
    return result, 1000 * max(b[0] - a[0] for a, b in pairs), 1000 * max(b[1] - a[1] for a, b in pairs), took


def pause(ms: int, QEventLoop, QTimer) -> None:  # noqa: N803 - Qt's names
    loop = QEventLoop()
    QTimer.singleShot(ms, loop.quit)
    loop.exec()


def download_all(app, window, QEventLoop, QTimer):  # noqa: N803 - Qt's names
    """Development ▸ Download all, Start pressed once the dialog shows, closed when it is done: (longest gap in
    ms, most GUI-thread CPU time in one gap in ms, seconds from Start until done)."""
    from motiontool.ui.download_dialog import DownloadDialog

    figures: list = []

    def press() -> None:
        dialog = app.activeModalWidget()
        if not isinstance(dialog, DownloadDialog) or figures:
            return
        poll.stop()
        figures.extend(measured(window, dialog.buttons["Start"].click, QEventLoop, QTimer)[1:])
        if "Done for controllers: 1" not in dialog.log.toPlainText():
            print(f"Download all failed: {dialog.log.toPlainText()}", file=sys.stderr)
            figures[:] = [float("nan")] * 3
        dialog.reject()

    poll = QTimer(window, interval=20, timeout=press)
    poll.start()
    window.actions_by_text["Download all"].trigger()    # returns when the dialog is closed
    return figures or [float("nan")] * 3


def axis_dialog(app, window, dialog_class, QEventLoop, QTimer):  # noqa: N803 - Qt's names
    """Parameters ▸ Axis until every value is shown: (longest gap of a 10 ms timer in ms, most GUI-thread CPU time
    in one gap in ms, seconds until shown)."""
    ticks: list[tuple[float, float]] = []      # (wall clock, this thread's CPU time) at each timer call
    shown: list[float] = []
    timer = QTimer(window, interval=10, timeout=lambda: ticks.append((time.monotonic(), time.thread_time())))

    def check() -> None:
        dialog = app.activeModalWidget()
        if not isinstance(dialog, dialog_class):
            return
        if dialog.waiting == 0 and dialog.ok.isEnabled():
            shown.append(time.monotonic() - started)
        elif time.monotonic() - started > 120 or dialog.message.styleSheet():   # a fault: said, not waited for
            shown.append(float("nan"))
            print(f"the Axis dialog did not fill in: {dialog.message.text()}", file=sys.stderr)
        else:
            return
        poll.stop()
        dialog.reject()

    poll = QTimer(window, interval=10, timeout=check)
    timer.start()
    loop = QEventLoop()
    QTimer.singleShot(200, loop.quit)     # the timer's ordinary pace before the menu entry
    loop.exec()
    started = time.monotonic()
    poll.start()
    window.actions_by_text["Axis..."].trigger()     # returns when the dialog is closed
    timer.stop()
    if not shown:
        return float("nan"), float("nan"), float("nan")
    pairs = [(a, b) for a, b in zip(ticks, ticks[1:], strict=False) if a[0] < started + shown[0]]
    return (1000 * max(b[0] - a[0] for a, b in pairs), 1000 * max(b[1] - a[1] for a, b in pairs), shown[0])


def watch(window, seconds: float, QEventLoop, QTimer):  # noqa: N803 - Qt's names
    """The Watch polling for `seconds`: (longest gap of a 10 ms timer in ms, most GUI-thread CPU time in one gap in
    ms, polls shown per second)."""
    from motiontool.ui.watch import WatchEntry

    pane = window.debugger.watch
    for key in ("APOS", "CPOS", "AVEL", "TRACKERR"):
        pane.add(WatchEntry("signal", key))
    for key in ("KPROP", "KDER"):
        pane.add(WatchEntry("parameter", key))
    shown = pane._show
    polls: list[float] = []

    def counted(entries, values) -> None:
        polls.append(time.monotonic())
        shown(entries, values)

    pane._show = counted          # counts the polls that reach the pane
    ticks: list[tuple[float, float]] = []
    timer = QTimer(window, interval=10, timeout=lambda: ticks.append((time.monotonic(), time.thread_time())))
    timer.start()
    window.debugger.watch_start()
    loop = QEventLoop()
    QTimer.singleShot(int(1000 * seconds), loop.quit)
    loop.exec()
    window.debugger.watch_stop()
    timer.stop()
    pairs = list(zip(ticks, ticks[1:], strict=False))
    return (1000 * max(b[0] - a[0] for a, b in pairs), 1000 * max(b[1] - a[1] for a, b in pairs),
            len(polls) / seconds)


def polling_scope(window, seconds: float, QEventLoop, QTimer):  # noqa: N803 - Qt's names
    """Tools ▸ Oscilloscope in polling mode, APOS, CPOS and TRACKERR polled every 100 ms for `seconds`: (longest
    gap of a 10 ms timer in ms, most GUI-thread CPU time in one gap in ms, polls recorded per second)."""
    window.actions_by_text["Oscilloscope"].trigger()
    scope = window._scopes[-1]
    scope.set_variant("polling")
    scope.poll_box.setValue(100)
    for signal in ("APOS", "CPOS", "TRACKERR"):
        scope.add_signal_curve(signal)
    ticks: list[tuple[float, float]] = []
    timer = QTimer(window, interval=10, timeout=lambda: ticks.append((time.monotonic(), time.thread_time())))
    timer.start()
    scope.start_action.trigger()
    loop = QEventLoop()
    QTimer.singleShot(int(1000 * seconds), loop.quit)
    loop.exec()
    polls = scope.run.polling.polls
    scope.stop_action.trigger()
    timer.stop()
    scope.close()
    pairs = list(zip(ticks, ticks[1:], strict=False))
    return (1000 * max(b[0] - a[0] for a, b in pairs), 1000 * max(b[1] - a[1] for a, b in pairs), polls / seconds)


if __name__ == "__main__":
    main()
