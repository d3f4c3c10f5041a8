"""What link_jobs.waiting drops of the input that waited while a command waited (decision I34; found by review):
a person's clicks and keys come from the window system, are held back during the wait and delivered when it ends,
inside the command, between its steps. There a click on another program's tab would change what Execute compiles
next, and Space on a focused button would start a second command inside the first. Tests cannot queue input as the
window system does, so the guard is given the events as the drain delivers them (QApplication.sendEvent, its
event filter in place, as after a wait)."""

from __future__ import annotations

from PySide6.QtCore import QEvent, QPointF, Qt
from PySide6.QtGui import QKeyEvent, QMouseEvent
from PySide6.QtWidgets import QApplication, QLabel, QMainWindow, QPlainTextEdit, QPushButton, QTabWidget

from motiontool.ui.link_jobs import _CommandGuard


def press(widget, pos) -> None:
    for kind in (QEvent.Type.MouseButtonPress, QEvent.Type.MouseButtonRelease):
        QApplication.sendEvent(widget, QMouseEvent(kind, QPointF(pos), QPointF(widget.mapToGlobal(pos)),
                                                   Qt.MouseButton.LeftButton, Qt.MouseButton.LeftButton,
                                                   Qt.KeyboardModifier.NoModifier))


def key(widget, code, text="") -> None:
    for kind in (QEvent.Type.KeyPress, QEvent.Type.KeyRelease):
        QApplication.sendEvent(widget, QKeyEvent(kind, code, Qt.KeyboardModifier.NoModifier, text))


def test_the_input_that_waited_changes_no_tab_presses_no_button_and_keeps_typing(qtbot):
    w = QMainWindow()
    tabs = QTabWidget()
    editor = QPlainTextEdit()
    tabs.addTab(editor, "Program A")
    tabs.addTab(QLabel("B"), "Program B")
    button = QPushButton("Start")
    pressed: list[bool] = []
    button.clicked.connect(lambda *_: pressed.append(True))
    tabs.setCornerWidget(button)
    w.setCentralWidget(tabs)
    qtbot.addWidget(w)
    w.show()
    qtbot.waitExposed(w)
    guard = _CommandGuard(w)
    guard.draining = True                      # as waiting() sets it when its outermost wait ends
    app = QApplication.instance()
    app.installEventFilter(guard)
    try:
        press(tabs.tabBar(), tabs.tabBar().tabRect(1).center())
        key(button, Qt.Key.Key_Space, " ")
        press(button, button.rect().center())
        key(editor, Qt.Key.Key_A, "a")
        key(editor, Qt.Key.Key_Space, " ")
        key(editor, Qt.Key.Key_Return, "\r")
    finally:
        app.removeEventFilter(guard)
    assert tabs.currentIndex() == 0
    assert pressed == []
    assert editor.toPlainText() == "a \n"      # typing is kept, Space and Return in the text too
    press(tabs.tabBar(), tabs.tabBar().tabRect(1).center())    # and once the command is over, clicks work again
    assert tabs.currentIndex() == 1
