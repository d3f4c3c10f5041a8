"""Every action of every window, fired the way a user fires it (issue 16 item 1).

The walk starts at the APOSS main window with a program running on the embedded controller. It discovers the
actions of each window by itself -- the menu bar with its submenus, the toolbars, and the actions that only
have a shortcut -- so an action added later is walked too. Toolbar actions are clicked on their buttons, menu
entries are triggered, and every shortcut is typed as its key sequence. Windows an action opens (CAM editor,
oscilloscope, array editor, Command List, find dialogs …) are walked in turn; non-modal dialogs get each of
their buttons clicked. Every modal dialog is answered: once by cancelling everything, once by accepting
everything (file dialogs get a real file of the right type, or a new path to save to). Any exception that
reaches sys.excepthook fails the test with the action that raised it.
"""

from __future__ import annotations

import gc
import sys
import traceback

import pytest
import shiboken6
from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QKeySequence, QShortcut
from PySide6.QtWidgets import (
    QAbstractButton,
    QApplication,
    QColorDialog,
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QInputDialog,
    QMainWindow,
    QMenu,
    QMessageBox,
    QProgressDialog,
    QPushButton,
    QToolBar,
    QToolButton,
    QWidget,
)

from tests.modal import Answerer, cancel_reply, press, trace
from tests.ui.sample_files import Files

RUNNING = "VEL 50\nACC 100\nDEC 100\ni = 0\nmain:\ni = i + 1\nPOSA 20000\nPOSA 0\nGOTO main\n"
NOT_WALKED = {"Exit Program"}   # closes the window being walked; fired last, on its own
# A window the walk has seen carries this property. Not its id(): a window deleted during the walk frees its
# address, and a window opened later at the same address was taken as seen and never walked (a flaky walk).
SEEN = "walk_seen"


def see(widget: QWidget) -> None:
    widget.setProperty(SEEN, True)


def actions_of(window: QWidget) -> list[tuple[str, QAction, QToolButton | None]]:
    """(label, action, toolbar button or None) for the window's menus, toolbars and shortcut-only actions."""
    found: dict[int, tuple[str, QAction, QToolButton | None]] = {}

    def add(label: str, action: QAction, button: QToolButton | None = None) -> None:
        if action.isSeparator() or action.menu() is not None or id(action) in found:
            return
        found[id(action)] = (label, action, button)

    def walk_menu(menu: QMenu, path: str) -> None:
        for action in menu.actions():
            if action.menu() is not None:
                walk_menu(action.menu(), f"{path} ▸ {action.text()}")
            else:
                add(f"{path} ▸ {action.text()}", action)

    for bar in window.findChildren(QToolBar):  # first: an action on a toolbar is clicked there
        if bar.window() is not window:
            continue
        for action in bar.actions():
            button = bar.widgetForAction(action)
            if isinstance(button, QToolButton) and not button.isVisible():
                continue   # in the toolbar's overflow (or a hidden toolbar): the menu entry is fired instead
            add(f"toolbar {bar.windowTitle()} ▸ {action.text()}", action,
                button if isinstance(button, QToolButton) else None)
    if isinstance(window, QMainWindow):
        for top in window.menuBar().actions():
            if top.menu() is not None:
                walk_menu(top.menu(), top.text())
    for action in window.actions():
        add(f"shortcut {action.text()}", action)
    return [f for f in found.values() if f[0].split(" ▸ ")[-1].replace("&", "") not in NOT_WALKED]


def shortcuts_of(window: QWidget) -> list[tuple[str, QKeySequence]]:
    keys = [(label, action.shortcut()) for label, action, _ in actions_of(window) if not action.shortcut().isEmpty()]
    keys += [(f"QShortcut {s.key().toString()}", s.key()) for s in window.findChildren(QShortcut)
             if s.parent() is not None and s.parent().window() is window]
    return keys


def accept_everything(files: Files):
    def reply(dialog: QWidget) -> None:
        if isinstance(dialog, QFileDialog):
            files.answer(dialog)
        elif isinstance(dialog, QMessageBox):
            for button in (QMessageBox.StandardButton.Yes, QMessageBox.StandardButton.Ok,
                           QMessageBox.StandardButton.Save, QMessageBox.StandardButton.Discard):
                if dialog.button(button) is not None:
                    dialog.button(button).click()
                    return
            cancel_reply(dialog)
        elif isinstance(dialog, QInputDialog):
            dialog.accept()
        elif isinstance(dialog, QColorDialog | QProgressDialog) or type(dialog).__name__ == "QPrintDialog":
            cancel_reply(dialog)   # nothing to print to here
        else:
            press(dialog, QDialogButtonBox.ButtonRole.AcceptRole)
    return reply


class Walk:
    def __init__(self, qtbot, main, reply) -> None:
        self.qtbot = qtbot
        self.main = main
        self.answerer = Answerer([], fallback=reply)
        self.current = "start"
        self.errors: list[str] = []
        self.fired: list[str] = []
        self.walked: list[str] = []

    def hook(self, kind, value, tb) -> None:
        self.errors.append(f"{self.current}: {''.join(traceback.format_exception(kind, value, tb))}")

    def settle(self) -> None:
        """Let queued events run and every modal dialog be answered."""
        self.qtbot.wait(30)
        self.qtbot.waitUntil(lambda: QApplication.activeModalWidget() is None, timeout=10000)

    def fire(self, label: str, fire) -> None:
        self.current = label
        self.fired.append(label)
        trace(label)
        fire()
        self.settle()

    def new_windows(self) -> list[QWidget]:
        # topLevelWidgets() releases the GIL while Qt builds the list; a garbage collection started meanwhile by
        # another thread (live check, status worker) can destroy a garbage widget or its child windows and leave
        # dangling pointers in the list (a segmentation fault here in a full run). So collect here, on the GUI
        # thread, and let no collection run until the list is read (ui/gui_gc.py does this for the IDE).
        gc.collect()
        collecting = gc.isenabled()
        gc.disable()
        try:
            return self._new_windows()
        finally:
            if collecting:
                gc.enable()

    def _new_windows(self) -> list[QWidget]:
        fresh = []
        for widget in QApplication.topLevelWidgets():
            if not shiboken6.isValid(widget):  # a stale wrapper PySide handed out for a widget Qt deleted
                continue
            if widget.property(SEEN) or not widget.isVisible() or isinstance(widget, QMenu):
                continue
            see(widget)
            fresh.append(widget)
        return fresh

    def ensure_program(self) -> None:
        """The main window's current tab is a program that runs (actions like Close or New change it)."""
        editor = self.main.current_editor()
        if editor is None or "POSA 20000" not in editor.toPlainText():
            editor = self.main.new_file()
            editor.setPlainText(RUNNING)

    def walk(self, window: QWidget) -> None:
        self.walked.append(type(window).__name__)
        for label, action, button in actions_of(window):
            if not window.isVisible():
                return
            if window is self.main:
                self.ensure_program()
            if not action.isEnabled() or (button is not None and not button.isVisible()):
                continue
            if button is not None:
                self.fire(label, lambda b=button: self.qtbot.mouseClick(b, Qt.MouseButton.LeftButton))
            else:
                self.fire(label, action.trigger)
            self.follow()
        for label, keys in shortcuts_of(window):
            if not window.isVisible():
                return
            window.activateWindow()
            self.qtbot.waitUntil(window.isActiveWindow, timeout=2000)
            combination = keys[0]
            target = QApplication.focusWidget() or window
            self.fire(f"{label} by {keys.toString()}",
                      lambda t=target, c=combination: self.qtbot.keyClick(t, c.key(), c.keyboardModifiers()))
            self.follow()

    def follow(self) -> None:
        """Walk the windows and non-modal dialogs the last action opened, then close them."""
        for widget in self.new_windows():
            if type(widget).__name__ in self.walked:
                pass   # one window of a kind is walked (a scope's Open opens another scope …)
            elif isinstance(widget, QMainWindow):
                self.walk(widget)
            elif isinstance(widget, QDialog):
                self.click_buttons(widget)
            widget.close()
            self.settle()

    def click_buttons(self, dialog: QDialog) -> None:
        self.walked.append(type(dialog).__name__)
        for button in dialog.findChildren(QAbstractButton):
            if isinstance(button, QPushButton) and button.isVisible() and button.isEnabled() \
                    and button.text().replace("&", "") not in ("Close", "Cancel", "OK"):
                self.fire(f"{type(dialog).__name__} ▸ {button.text()}",
                          lambda b=button: self.qtbot.mouseClick(b, Qt.MouseButton.LeftButton))
                if not dialog.isVisible():
                    return


@pytest.mark.slow
@pytest.mark.parametrize("answer", ["cancel", "accept"])
def test_every_action_of_every_window_runs_without_an_exception(window, qtbot, tmp_path, monkeypatch, answer):
    files = Files(tmp_path)
    monkeypatch.chdir(tmp_path)
    walk = Walk(qtbot, window, cancel_reply if answer == "cancel" else accept_everything(files))
    monkeypatch.setattr(sys, "excepthook", walk.hook)
    for widget in QApplication.topLevelWidgets():
        see(widget)
    walk.ensure_program()
    qtbot.keyClick(window.current_editor(), Qt.Key.Key_F5)     # a program moves while everything is walked
    walk.answerer.timer.start()
    try:
        walk.walk(window)
        exit_action = window.actions_by_text["Exit Program"]
        walk.fire("File ▸ Exit Program", exit_action.trigger)
    finally:
        walk.answerer.timer.stop()
    assert not walk.errors, "\n\n".join(walk.errors)
    assert not walk.answerer.errors, walk.answerer.errors
    assert {"MainWindow", "CamEditor", "ScopeWindow", "ArrayEditor", "CommandListDialog"} <= set(walk.walked)
    assert len(walk.fired) > 150
    assert not window.isVisible()
