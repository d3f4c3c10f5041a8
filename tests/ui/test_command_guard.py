"""What link_jobs.waiting drops of the input that waited while a command waited (decision I34; found by review):
a person's clicks and keys come from the window system, are held back during the wait and delivered when it ends,
inside the command, between its steps. There a click on another program's tab would change what Execute compiles
next, and Space on a focused button would start a second command inside the first. Tests cannot queue input as the
window system does, so the clicks and keys are given as the drain delivers them: at once, through the application's
event filters, with the guard in place as after a wait."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QApplication, QLabel, QMainWindow, QPlainTextEdit, QPushButton, QTabWidget

from motiontool.ui.link_jobs import _CommandGuard


def test_the_input_that_waited_changes_no_tab_presses_no_button_and_keeps_typing(qtbot):
    left = Qt.MouseButton.LeftButton

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
        qtbot.mouseClick(tabs.tabBar(), left, pos=tabs.tabBar().tabRect(1).center())
        qtbot.keyClick(button, Qt.Key.Key_Space)
        qtbot.mouseClick(button, left)
        qtbot.keyClicks(editor, "a ")
        qtbot.keyClick(editor, Qt.Key.Key_Return)
    finally:
        app.removeEventFilter(guard)
    assert tabs.currentIndex() == 0
    assert pressed == []
    assert editor.toPlainText() == "a \n"      # typing is kept, Space and Return in the text too
    qtbot.mouseClick(tabs.tabBar(), left, pos=tabs.tabBar().tabRect(1).center())   # after the command, clicks work
    assert tabs.currentIndex() == 1
