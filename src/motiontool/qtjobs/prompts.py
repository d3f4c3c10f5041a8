"""The IDE's Prompts (session/prompts.py): the message boxes, input dialogs and file dialogs a command asks
through, parented to its window. The dialogs are the ones the commands opened themselves before (same titles,
texts and buttons), so a user sees no change; a command no longer names Qt to ask.

It lives in qtjobs, below the tool packages, so the APOSS windows (`ui/`) and the tool windows (oscilloscope, CAM
editor, Array Editor) ask through the same class: a tool window asks through its APOSS window's prompts (the
bridge's, `window_prompts`) or, opened on its own, through a QtPrompts over itself (issue 27 item 5)."""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from PySide6.QtWidgets import QFileDialog, QInputDialog, QMessageBox, QWidget

from motiontool.fileio import filter_extension

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

    def pick(self, title: str, label: str, items: Sequence[str], current: int) -> str | None:
        item, ok = QInputDialog.getItem(self.parent, title, label, list(items), current, False)
        return item if ok else None

    def save_path(self, title: str, suggested: str, filters: str) -> Path | None:
        chosen, _ = QFileDialog.getSaveFileName(self.parent, title, suggested, filters)
        return Path(chosen) if chosen else None

    def save_name(self, title: str, suggested: str | Path, filters: str) -> Path | None:
        chosen, _ = ask_save_name(self.parent, title, suggested, filters)
        return Path(chosen) if chosen else None

    def open_path(self, title: str, directory: str, filters: str) -> Path | None:
        chosen, _ = QFileDialog.getOpenFileName(self.parent, title, directory, filters)
        return Path(chosen) if chosen else None

    def folder(self, title: str, directory: str) -> Path | None:
        chosen = QFileDialog.getExistingDirectory(self.parent, title, directory)
        return Path(chosen) if chosen else None

    def warn(self, title: str, text: str, *, detail: str = "", critical: bool = False) -> None:
        if not detail and not critical:
            QMessageBox.warning(self.parent, title, text)
            return
        if not detail:
            QMessageBox.critical(self.parent, title, text)
            return
        icon = QMessageBox.Icon.Critical if critical else QMessageBox.Icon.Warning
        box = QMessageBox(icon, title, text, Button.Ok, self.parent)
        box.setInformativeText(detail)
        box.exec()
        box.deleteLater()

    def inform(self, title: str, text: str) -> None:
        QMessageBox.information(self.parent, title, text)


def ask_save_name(parent: QWidget | None, title: str, suggested: str | Path, filters: str) -> tuple[str, str]:
    """(path, selected filter) like QFileDialog.getSaveFileName; ("", "") when cancelled. The dialog adds the
    selected filter's extension to a name typed without one (issue 23 item 9: a program saved as `ctl2_test` was
    then hidden by File ▸ Open's filter) itself (defaultSuffix), so its overwrite question is asked about the file
    that will be written. A suggested name whose extension one filter names selects that filter."""
    dialog = QFileDialog(parent, title, "", filters)
    dialog.setAcceptMode(QFileDialog.AcceptMode.AcceptSave)
    dialog.setFileMode(QFileDialog.FileMode.AnyFile)
    suggested = Path(suggested) if str(suggested) else None
    if suggested is not None:
        if str(suggested.parent) not in ("", "."):
            dialog.setDirectory(str(suggested.parent))
        for name_filter in dialog.nameFilters():
            if suggested.suffix.lower() in re.findall(r"\*(\.\w+)", name_filter.lower()):
                dialog.selectNameFilter(name_filter)
                break
        dialog.selectFile(suggested.name)
    dialog.filterSelected.connect(lambda name_filter: dialog.setDefaultSuffix(filter_extension(name_filter)))
    dialog.setDefaultSuffix(filter_extension(dialog.selectedNameFilter()))
    if not dialog.exec() or not dialog.selectedFiles():
        return "", ""
    return dialog.selectedFiles()[0], dialog.selectedNameFilter()


def window_prompts(window: QWidget, given: Any = None, bridge: Any = None) -> Any:
    """What a tool window asks through, shown over it: `given` (its `prompts=`), else its bridge's (the APOSS
    window's prompts), else the Qt dialogs (a window opened on its own: a .zbo, the sweep view's scope, a test)."""
    given = given if given is not None else getattr(bridge, "prompts", None)
    return QtPrompts(window) if given is None else given.within(window)


def prompts_for(widget: QWidget) -> Any:
    """What a dialog or pane of a tool window asks through, shown over it: its window's `prompts`, else the Qt
    dialogs."""
    owner = widget.parentWidget()
    given = getattr(owner.window(), "prompts", None) if owner is not None else None
    return QtPrompts(widget) if given is None else given.within(widget)
