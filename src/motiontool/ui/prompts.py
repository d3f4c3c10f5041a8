"""The IDE's Prompts (session/prompts.py): the message boxes, input dialogs and file dialogs a command asks
through, parented to its window. The dialogs are the ones the commands opened themselves before (same titles,
texts and buttons), so a user sees no change; a command no longer names Qt to ask."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from PySide6.QtWidgets import QFileDialog, QInputDialog, QMessageBox, QWidget

Button = QMessageBox.StandardButton
CANCEL_BUTTONS = {"Cancel": Button.Cancel, "Close": Button.Close}   # standard buttons: Esc presses them


class QtPrompts:
    def __init__(self, parent: QWidget | None) -> None:
        self.parent = parent

    def within(self, owner: QWidget) -> QtPrompts:
        return type(self)(owner)

    def confirm(self, title: str, text: str) -> bool:
        return QMessageBox.question(self.parent, title, text) == Button.Yes

    def choose(self, title: str, text: str, choices: Sequence[str], *, detail: str = "", warning: bool = False,
               cancel: str = "Cancel", destructive: bool = False) -> str | None:
        icon = QMessageBox.Icon.Warning if warning else QMessageBox.Icon.Question
        box = QMessageBox(icon, title, text, Button.NoButton, self.parent)
        if detail:
            box.setInformativeText(detail)
        buttons = {}
        for k, choice in enumerate(choices):
            role = QMessageBox.ButtonRole.DestructiveRole if destructive else \
                QMessageBox.ButtonRole.AcceptRole if k == 0 else QMessageBox.ButtonRole.ActionRole
            buttons[box.addButton(choice, role)] = choice
        dismiss = box.addButton(CANCEL_BUTTONS[cancel])
        if destructive:
            box.setDefaultButton(dismiss)
        box.exec()
        chosen = buttons.get(box.clickedButton())
        box.deleteLater()
        return chosen

    def decide(self, title: str, text: str, *, yes: str, no: str, cancel: str, detail: str = "") -> bool | None:
        box = QMessageBox(QMessageBox.Icon.Question, title, text, Button.Yes | Button.No | Button.Cancel,
                          self.parent)
        if detail:
            box.setInformativeText(detail)
        for button, label in ((Button.Yes, yes), (Button.No, no), (Button.Cancel, cancel)):
            box.button(button).setText(label)
        box.setDefaultButton(Button.Yes)
        answer = box.exec()
        box.deleteLater()
        return True if answer == Button.Yes else False if answer == Button.No else None

    def save_changes(self, title: str, text: str) -> str | None:
        answer = QMessageBox.question(self.parent, title, text, Button.Save | Button.Discard | Button.Cancel)
        return {Button.Save: "save", Button.Discard: "discard"}.get(answer)

    def text(self, title: str, label: str, *, default: str = "") -> str | None:
        text, ok = QInputDialog.getText(self.parent, title, label, text=default)
        return text if ok else None

    def integer(self, title: str, label: str, value: int, low: int, high: int) -> int | None:
        number, ok = QInputDialog.getInt(self.parent, title, label, value, low, high)
        return number if ok else None

    def save_path(self, title: str, suggested: str, filters: str) -> Path | None:
        chosen, _ = QFileDialog.getSaveFileName(self.parent, title, suggested, filters)
        return Path(chosen) if chosen else None

    def open_path(self, title: str, directory: str, filters: str) -> Path | None:
        chosen, _ = QFileDialog.getOpenFileName(self.parent, title, directory, filters)
        return Path(chosen) if chosen else None

    def warn(self, title: str, text: str, *, detail: str = "", critical: bool = False) -> None:
        if not detail and not critical:
            QMessageBox.warning(self.parent, title, text)
            return
        icon = QMessageBox.Icon.Critical if critical else QMessageBox.Icon.Warning
        box = QMessageBox(icon, title, text, Button.Ok, self.parent)
        box.setInformativeText(detail)
        box.exec()
        box.deleteLater()

    def inform(self, title: str, text: str) -> None:
        QMessageBox.information(self.parent, title, text)
