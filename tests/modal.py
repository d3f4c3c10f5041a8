"""Answering modal dialogs the way a user does, while the code under test waits in `exec()`.

A QTimer polls for the active modal widget (QApplication.activeModalWidget) and hands it to the next reply;
a reply fills in the dialog's widgets and presses its buttons. `answering(qtbot, reply, ...)` is a context
manager: the block fires the user's action (an action's trigger, a click, a key), the replies answer the
dialogs in order, and leaving the block fails the test if a dialog expected was never shown.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import (
    QApplication,
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QInputDialog,
    QLineEdit,
    QMessageBox,
    QWidget,
)

Reply = Callable[[QWidget], None]
POLL_MS = 20
REPLIES = "_modal_replies"  # dynamic property: how many replies this dialog got


def trace(line: str) -> None:
    """With MOTIONTOOL_GUI_TRACE=FILE the dialogs answered (and the walk's actions) are logged as they happen:
    the place to look when a GUI test hangs."""
    path = os.environ.get("MOTIONTOOL_GUI_TRACE")
    if path:
        with open(path, "a", encoding="utf-8") as f:
            f.write(line + "\n")


def file_reply(path: Path | str) -> Reply:
    """A file dialog: type the path into its file name field and press Open/Save."""
    def reply(dialog: QWidget) -> None:
        assert isinstance(dialog, QFileDialog), f"expected a file dialog, got {dialog!r}"
        dialog.findChild(QLineEdit).setText(str(path))
        dialog.selectFile(str(path))
        dialog.accept()
    return reply


def button_reply(button: QMessageBox.StandardButton) -> Reply:
    """A message box: click `button`."""
    def reply(box: QWidget) -> None:
        assert isinstance(box, QMessageBox), f"expected a message box, got {box!r}"
        box.button(button).click()
    return reply


def text_reply(text: str) -> Reply:
    """An input dialog: type the text (or number) and press OK."""
    def reply(dialog: QWidget) -> None:
        assert isinstance(dialog, QInputDialog), f"expected an input dialog, got {dialog!r}"
        dialog.setTextValue(text) if dialog.inputMode() == QInputDialog.InputMode.TextInput \
            else dialog.setIntValue(int(text))
        dialog.accept()
    return reply


def ok_reply(fill: Callable[[QDialog], None] | None = None, kind: type | None = None) -> Reply:
    """Any dialog: let `fill` set its widgets, then press OK (the accept role button of its button box)."""
    def reply(dialog: QWidget) -> None:
        if kind is not None:
            assert isinstance(dialog, kind), f"expected {kind.__name__}, got {dialog!r}"
        if fill is not None:
            fill(dialog)
        press(dialog, QDialogButtonBox.ButtonRole.AcceptRole)
    return reply


def cancel_reply(dialog: QWidget) -> None:
    """Any dialog: Cancel / Close / No / Esc."""
    if isinstance(dialog, QMessageBox):
        for button in (QMessageBox.StandardButton.Cancel, QMessageBox.StandardButton.No,
                       QMessageBox.StandardButton.Close, QMessageBox.StandardButton.Ok):
            if dialog.button(button) is not None:
                dialog.button(button).click()
                return
    dialog.reject() if isinstance(dialog, QDialog) else dialog.close()


def press(dialog: QWidget, role: QDialogButtonBox.ButtonRole) -> None:
    """Click the first button with `role` in the dialog's button boxes (accept() when there is none)."""
    for box in dialog.findChildren(QDialogButtonBox):
        for button in box.buttons():
            if box.buttonRole(button) == role and button.isEnabled():
                button.click()
                return
    dialog.accept() if role == QDialogButtonBox.ButtonRole.AcceptRole else dialog.reject()


def _text(dialog: QWidget) -> str:
    return dialog.text() if isinstance(dialog, QMessageBox) else ""


def when_idle(reply: Reply) -> Reply:
    """A reply given only once no command waits for its controller (the busy cursor gone): the answerer's timer
    also fires while a command of the dialog waits (ui/link_jobs.waiting), and a click then is dropped, as a
    person's would be (decision I34); a person waits for the dialog to show what it read before the next click."""
    reply.when_idle = True  # type: ignore[attr-defined]
    return reply


class Answerer:
    def __init__(self, replies: list[Reply], fallback: Reply | None = None) -> None:
        self.replies = list(replies)
        self.fallback = fallback
        self.seen: list[str] = []
        self.errors: list[BaseException] = []
        self._busy = False
        self.timer = QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)

    def _poll(self) -> None:
        dialog = QApplication.activeModalWidget()
        if dialog is None or self._busy or not dialog.isVisible():
            return
        if self.replies and getattr(self.replies[0], "when_idle", False) and QApplication.overrideCursor():
            return
        reply = self.replies.pop(0) if self.replies else self.fallback
        if reply is None:  # a dialog the test did not expect: closed, and the test fails (it would hang)
            self.errors.append(AssertionError(f"unexpected dialog {type(dialog).__name__} "
                                              f"{dialog.windowTitle()!r}: {_text(dialog)}"))
            reply = cancel_reply
        self._busy = True
        self.seen.append(f"{type(dialog).__name__} {dialog.windowTitle()!r}")
        # The count lives on the dialog itself: a Python id() is reused once a closed dialog's wrapper is freed,
        # so a count kept by id() added up the replies to different dialogs (a message box and a later file
        # dialog shared one) and failed a walk whose every dialog had closed.
        times = (dialog.property(REPLIES) or 0) + 1
        dialog.setProperty(REPLIES, times)
        if times > 3:  # the reply did not close it: give up on it rather than loop
            self.errors.append(AssertionError(f"{self.seen[-1]} stayed open after {times - 1} replies"))
            reply = cancel_reply
        trace("   modal " + self.seen[-1])
        try:
            reply(dialog)
        except BaseException as exc:  # noqa: BLE001 - reported when the block ends; the dialog is closed
            self.errors.append(exc)
            cancel_reply(dialog)
        finally:
            self._busy = False


@contextlib.contextmanager
def answering(qtbot, *replies: Reply, fallback: Reply | None = None, timeout: int = 5000):
    """Answer the modal dialogs the block opens with `replies`, in order (then `fallback`, if given)."""
    answerer = Answerer(list(replies), fallback)
    answerer.timer.start()
    try:
        yield answerer
        if answerer.replies:
            qtbot.waitUntil(lambda: not answerer.replies, timeout=timeout)
    finally:
        answerer.timer.stop()
    if answerer.errors:
        raise answerer.errors[0]


@contextlib.contextmanager
def answering_inner(qtbot, kind: type, *replies: Reply, timeout: int = 5000):
    """For a button clicked inside a reply (the outer dialog is waiting in that reply): answer only the next
    dialogs of type `kind`, in order, and then stop. `answering` would go on polling after its replies, and
    a processEvents() in the code that runs after them (a progress log) let it take the outer dialog for an
    unexpected one and close it - a failure that came and went with the machine's load."""
    pending = list(replies)
    errors: list[BaseException] = []
    timer = QTimer()
    timer.setInterval(POLL_MS)

    def poll() -> None:
        dialog = QApplication.activeModalWidget()
        if not pending or not isinstance(dialog, kind) or not dialog.isVisible() or dialog.property(REPLIES):
            return
        dialog.setProperty(REPLIES, 1)
        reply = pending.pop(0)
        if not pending:
            timer.stop()
        trace(f"   inner {type(dialog).__name__} {dialog.windowTitle()!r}")
        try:
            reply(dialog)
        except BaseException as exc:  # noqa: BLE001 - reported when the block ends; the dialog is closed
            errors.append(exc)
            cancel_reply(dialog)

    timer.timeout.connect(poll)
    timer.start()
    try:
        yield
        if pending:
            qtbot.waitUntil(lambda: not pending, timeout=timeout)
    finally:
        timer.stop()
    if errors:
        raise errors[0]
