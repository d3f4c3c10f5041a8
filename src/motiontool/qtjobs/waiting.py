"""A command waiting for its controller (decision I34): `waiting(window, text, work)` is `jobs.wait_off_gui` while
the window says `text` in its status bar and shows a busy cursor; meanwhile and right after, what would start a
command again is dropped (`_CommandGuard`). The IDE's commands and the oscilloscope's (Start/Stop, Single Shot,
TESTSETP, Tune) wait through it."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QCoreApplication, QEvent, QObject, Qt
from PySide6.QtGui import QAction, QKeyEvent
from PySide6.QtWidgets import QAbstractButton, QApplication, QDialog, QMenu, QMenuBar, QWidget

from motiontool.qtjobs.jobs import wait_off_gui

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
