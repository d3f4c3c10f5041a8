"""Link requests the window makes on a worker thread (like the status poll, ui/status_worker.py): on a slow line
one exchange takes a quarter of a second or more, and the window must not stand still meanwhile.

`LinkJobs.run(work, done)` calls `work()` on the jobs' own thread, one job after another in the order asked, and
hands its result (or the LinkError/ValueError it raised) to `done` in the GUI thread. `wait_off_gui(work)` is for
a command that needs the answer before it goes on (Execute's array check): the request runs on a thread while
the GUI thread keeps painting (user input waits, so the command is not started twice meanwhile); `waiting(window,
text, work)` is wait_off_gui that says so: the text in the window's status bar and a busy cursor until the answer.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QCoreApplication, QEvent, QEventLoop, QObject, Qt, Signal, Slot
from PySide6.QtGui import QAction, QKeyEvent
from PySide6.QtWidgets import QAbstractButton, QApplication, QDialog, QMenu, QMenuBar, QWidget

from motiontool.comms.protocol import LinkError

Done = Callable[[Any], None]


class _Relay(QObject):
    """Emits from a worker thread; lives as long as its job, not as long as the window (as in status_worker)."""

    answer = Signal(object, object)   # (done callback, result or exception)


class LinkJobs(QObject):
    def __init__(self, parent: QObject | None = None):
        super().__init__(parent)
        self._queue: queue.Queue = queue.Queue()
        self._thread: threading.Thread | None = None
        self._gone = threading.Event()
        self.destroyed.connect(lambda *_, gone=self._gone: gone.set())
        self.pending = 0                  # jobs asked and not yet delivered (tests wait for 0)

    def run(self, work: Callable[[], Any], done: Done) -> None:
        relay = _Relay()
        relay.answer.connect(self._deliver, Qt.ConnectionType.QueuedConnection)
        self.pending += 1
        self._queue.put((work, done, relay))
        if self._thread is None or not self._thread.is_alive():
            self._thread = threading.Thread(target=self._work, name="link-jobs", daemon=True)
            self._thread.start()

    def _work(self) -> None:
        while not self._gone.is_set():
            try:
                work, done, relay = self._queue.get(timeout=1.0)
            except queue.Empty:
                continue          # one thread for the window's life: it ends when the window is deleted
            result = _call(work)
            if not self._gone.is_set():
                relay.answer.emit(done, result)
            relay.deleteLater()

    @Slot(object, object)
    def _deliver(self, done: Done, result: Any) -> None:
        self.pending -= 1
        done(result)


def _call(work: Callable[[], Any]) -> Any:
    try:
        return work()
    except (LinkError, ValueError) as exc:
        return exc
    except Exception as exc:  # noqa: BLE001 - a failing request is reported, never lost on a thread
        return LinkError(f"request failed: {type(exc).__name__}: {exc}")


def wait_off_gui(work: Callable[[], Any]) -> Any:
    """`work()` on a thread; the GUI thread paints while it waits. Raises what `work` raised."""
    box: list[Any] = []
    loop = QEventLoop()
    relay = _Relay()
    relay.answer.connect(lambda _done, _result: loop.quit(), Qt.ConnectionType.QueuedConnection)

    def body() -> None:
        box.append(_call(work))
        relay.answer.emit(None, None)

    thread = threading.Thread(target=body, name="link-wait", daemon=True)
    thread.start()
    while not box:  # the queued quit may come before exec(): then the loop ends at its first pass
        loop.exec(QEventLoop.ProcessEventsFlag.ExcludeUserInputEvents)
    # The answer is in the box before the thread emits: a quick answer is seen without a pass of the loop, and the
    # relay deleted then could be deleted while the thread still emits from it (a segfault under load).
    thread.join()
    relay.deleteLater()
    if isinstance(box[0], Exception):
        raise box[0]
    return box[0]


_CLICKS = (QEvent.Type.MouseButtonPress, QEvent.Type.MouseButtonRelease, QEvent.Type.MouseButtonDblClick)


class _CommandGuard(QObject):
    """What would start a command again while a command of `window` waits (a second click on Prepare Singlestep
    ran it twice, one after the other) is dropped: during the wait, a shortcut or a click on a button, menu or
    toolbar of that window (a test's input comes at once); when the wait ends, the input that waited (a person's)
    is delivered inside the command, between its steps, so there every click, wheel turn and shortcut of that
    window, a key on a button and Return, Enter and Escape that reach a dialog (its default button) are dropped:
    a click on another program's tab must not change what the command compiles next. Typing is kept, and windows
    opened meanwhile (a dialog) get everything. The active window at the start is guarded too: Programs' Start waits for
    the main window's controller from a dialog of its own."""

    def __init__(self, window: QWidget) -> None:
        super().__init__()
        self.windows = {window, QApplication.activeWindow()} - {None}
        self.draining = False

    def _ours(self, obj: QObject) -> bool:
        widget = obj.parent() if isinstance(obj, QAction) else obj
        while isinstance(widget, QMenu) and widget.parentWidget() is not None:   # a menu is a window of its own
            widget = widget.parentWidget()
        return isinstance(widget, QWidget) and widget.window() in self.windows

    def eventFilter(self, obj: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt's name
        kind = event.type()
        if kind == QEvent.Type.Shortcut or (kind in _CLICKS and isinstance(obj, (QAbstractButton, QMenu, QMenuBar))):
            return self._ours(obj)
        if not self.draining:
            return False
        if kind in _CLICKS or kind == QEvent.Type.Wheel:
            return self._ours(obj)
        if kind in (QEvent.Type.KeyPress, QEvent.Type.KeyRelease) and isinstance(event, QKeyEvent) and (
                isinstance(obj, QAbstractButton) or (isinstance(obj, QDialog) and event.key() in _DIALOG_KEYS)):
            return self._ours(obj)
        return False


_DIALOG_KEYS = (Qt.Key.Key_Return, Qt.Key.Key_Enter, Qt.Key.Key_Escape)   # its default button, Cancel


_guarding = [0]   # waits under way: the outermost one delivers, and drops, what came during all of them


def waiting(window, text: str, work: Callable[[], Any]) -> Any:
    """wait_off_gui while `window` (a main window, or a widget inside one) shows that it waits for the controller;
    meanwhile and right after, what would start a command again is dropped (_CommandGuard)."""
    main = window.window() if hasattr(window, "window") else window
    bar = main.statusBar() if hasattr(main, "statusBar") else None
    if bar is not None:
        bar.showMessage(text)
    QApplication.setOverrideCursor(Qt.CursorShape.BusyCursor)
    guard = _CommandGuard(main)
    app = QCoreApplication.instance()
    assert app is not None
    app.installEventFilter(guard)
    _guarding[0] += 1
    try:
        return wait_off_gui(work)
    finally:
        _guarding[0] -= 1
        if _guarding[0] == 0:   # the clicks and keys that waited are delivered now, through the guard
            guard.draining = True
            QCoreApplication.processEvents()
        app.removeEventFilter(guard)
        QApplication.restoreOverrideCursor()
        if bar is not None and bar.currentMessage() == text:   # a later message of the command stays
            bar.clearMessage()
