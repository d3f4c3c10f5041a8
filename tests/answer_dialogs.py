"""Answer the modal dialogs an action opens, as a user would: read the message, click its button, choose a file.

    with Answers(qtbot, QMessageBox.StandardButton.Save, QMessageBox.StandardButton.Ok) as answers:
        window.actions_by_text["Exit Program"].trigger()
    assert "Cannot write" in answers.seen[1].text

Each answer is used for the next modal dialog that appears: a StandardButton is clicked with the mouse on a
QMessageBox; a ``ChooseFile(path, then=...)`` types the name into a QFileDialog and accepts it (``then`` runs
right after, before the application gets the name back: e.g. the folder disappears, like a share going away).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import QApplication, QFileDialog, QLineEdit, QMessageBox


@dataclass
class ChooseFile:
    path: str
    then: Callable[[], None] | None = None


@dataclass
class Seen:
    kind: str
    title: str
    text: str
    informative: str = ""


class Answers:
    def __init__(self, qtbot, *answers):
        self.qtbot = qtbot
        self.answers = list(answers)
        self.seen: list[Seen] = []
        self.unexpected: list[str] = []
        # a mark on the dialog itself, not id(dialog): a closed dialog's wrapper is freed and the next dialog's
        # wrapper may get its address, so an id set took a new dialog for an answered one and left the test
        # hanging in its modal loop (a full run stopped in test_save_failures' Compile to file)
        self._mark = f"answered_by_{id(self)}"
        self._timer = QTimer()
        self._timer.setInterval(20)
        self._timer.timeout.connect(self._poll)

    def __enter__(self) -> Answers:
        self._timer.start()
        return self

    def __exit__(self, *exc) -> None:
        self._timer.stop()
        if exc[0] is None:
            assert not self.unexpected, f"unexpected dialogs (closed): {self.unexpected}; seen: {self.seen}"
            assert not self.answers, f"dialogs that never came: {self.answers}; seen: {self.seen}"

    def _poll(self) -> None:
        dialog = QApplication.activeModalWidget()
        if dialog is None or dialog.property(self._mark) or not dialog.isVisible():
            return
        dialog.setProperty(self._mark, True)
        text = dialog.text() if isinstance(dialog, QMessageBox) else ""
        if not self.answers or (isinstance(dialog, QMessageBox) != (not isinstance(self.answers[0], ChooseFile))) \
                or (isinstance(dialog, QMessageBox) and dialog.button(self.answers[0]) is None):
            self.unexpected.append(f"{type(dialog).__name__} {dialog.windowTitle()!r} {text!r}")
            dialog.reject()  # never leave a test hanging in a modal loop
            return
        answer = self.answers.pop(0)
        if isinstance(dialog, QMessageBox):
            self.seen.append(Seen("message", dialog.windowTitle(), text, dialog.informativeText()))
            self.qtbot.mouseClick(dialog.button(answer), Qt.MouseButton.LeftButton)
        elif isinstance(dialog, QFileDialog):
            self.seen.append(Seen("file", dialog.windowTitle(), answer.path))
            name = dialog.findChild(QLineEdit, "fileNameEdit")  # typed, as a user does (selectFile may keep the
            if name is not None:                                # dialog's default name while its model loads)
                name.setText(answer.path)
            else:
                dialog.selectFile(answer.path)
            dialog.accept()
            if answer.then is not None:
                answer.then()
        else:
            self.unexpected.append(f"{type(dialog).__name__} {dialog.windowTitle()!r}")
            dialog.reject()
