"""Driving the CAM editor like a user: toolbar actions, dialogs, table cells and real mouse events on the
pyqtgraph diagram (QMouseEvents sent to its viewport, so pyqtgraph's own hover/drag/click logic runs)."""

from __future__ import annotations

import contextlib

from PySide6.QtCore import QEvent, QPoint, QPointF, Qt
from PySide6.QtGui import QMouseEvent
from PySide6.QtWidgets import QApplication, QComboBox, QDialogButtonBox, QLineEdit

L, R, NONE = Qt.MouseButton.LeftButton, Qt.MouseButton.RightButton, Qt.MouseButton.NoButton


def ok(dialog) -> None:
    dialog.findChild(QDialogButtonBox).button(QDialogButtonBox.StandardButton.Ok).click()


def add_array(editor, name="stamping", length=4000, intervals=40, interpolation=True) -> None:
    """Toolbar Add CAM array → dialog → OK."""
    editor.actions_by_name["add"].trigger()
    dialog = editor.dialog
    dialog.name.setText(name)
    dialog.master_length.setValue(length)
    dialog.intervals.setValue(intervals)
    dialog.interpolation.setChecked(interpolation)
    ok(dialog)


def add_fix_points(editor, text: str) -> None:
    editor.fix_table.add_button.click()
    editor.dialog.text.setPlainText(text)
    ok(editor.dialog)


def add_pairs(editor, text: str) -> None:
    editor.pair_table.add_button.click()
    editor.dialog.text.setPlainText(text)
    ok(editor.dialog)


def cell_center(view, row: int, col: int) -> QPoint:
    return view.visualRect(view.model().index(row, col)).center()


@contextlib.contextmanager
def handled_edit(qtbot, editor, expected: str):
    """The block commits a Fix Points cell; leaving it waits until the editor has handled that edit (applied it
    or shown why not) and checks that the value committed is `expected`.

    The editor applies a cell edit queued, after the cell editor has closed (and Qt deletes the cell editor
    with deleteLater): a fixed wait read the message line before the edit under load, and a wait on the closed
    editor touched a deleted QLineEdit. A probe connected queued after the editor's own slot runs after it:
    queued calls to one thread arrive in the order they were posted.
    """
    model = editor.fix_table.model
    committed: list[object] = []

    def probe(_row: int, _field: str, value: object) -> None:
        committed.append(value)

    model.edit_requested.connect(probe, Qt.ConnectionType.QueuedConnection)
    try:
        yield
        qtbot.waitUntil(lambda: bool(committed), timeout=5000)
    finally:
        model.edit_requested.disconnect(probe)
    assert committed == [expected], f"the cell committed {committed}, typed {expected!r}"


def choose_type(qtbot, editor, row: int, new_type: str) -> None:
    """Double-click the Type cell and pick a type in its combo box [DG L3986]."""
    view = editor.fix_table.view
    qtbot.mouseClick(view.viewport(), L, pos=cell_center(view, row, 3))
    qtbot.mouseDClick(view.viewport(), L, pos=cell_center(view, row, 3))
    combos = [w for w in view.findChildren(QComboBox) if w.isVisible()]
    assert combos, "no type editor opened"
    combo = combos[0]
    combo.hidePopup()
    with handled_edit(qtbot, editor, new_type):
        combo.setCurrentText(new_type)
        combo.activated.emit(combo.currentIndex())


def edit_cell(qtbot, editor, row: int, col: int, text: str) -> None:
    """Double-click a Fix Points cell, type `text` and press Enter; returns when the editor has handled the edit."""
    view = editor.fix_table.view
    qtbot.mouseClick(view.viewport(), L, pos=cell_center(view, row, col))
    qtbot.mouseDClick(view.viewport(), L, pos=cell_center(view, row, col))
    lines = [w for w in view.findChildren(QLineEdit) if w.isVisible()]
    assert lines, "no cell editor opened"
    line = lines[0]
    with handled_edit(qtbot, editor, text):
        line.selectAll()
        qtbot.keyClicks(line, text)
        qtbot.keyClick(line, Qt.Key.Key_Return)


def field(qtbot, widget, text: str) -> None:
    """Type into a card field and press Enter."""
    widget.setFocus()
    widget.selectAll()
    qtbot.keyClicks(widget, text)
    qtbot.keyClick(widget, Qt.Key.Key_Return)


# -- diagram ----------------------------------------------------------------------------------------------------------
def to_pixel(editor, master: float, slave: float) -> QPoint:
    scene = editor.diagram.box.mapViewToScene(QPointF(master, slave))
    return editor.diagram.mapFromScene(scene)


def _send(editor, kind, pos: QPoint, button, buttons, modifiers=Qt.KeyboardModifier.NoModifier) -> None:
    viewport = editor.diagram.viewport()
    event = QMouseEvent(kind, QPointF(pos), QPointF(viewport.mapToGlobal(pos)), button, buttons, modifiers)
    QApplication.sendEvent(viewport, event)


def hover(qtbot, editor, pos: QPoint) -> None:
    _send(editor, QEvent.Type.MouseMove, pos, NONE, NONE)
    qtbot.wait(30)  # pyqtgraph drops mouse moves closer than its rate limit


def drag(qtbot, editor, start: QPoint, end: QPoint, button=L, steps: int = 6, modifiers=Qt.KeyboardModifier.NoModifier,
         between=None) -> None:
    hover(qtbot, editor, start)
    _send(editor, QEvent.Type.MouseButtonPress, start, button, button, modifiers)
    for k in range(1, steps + 1):
        qtbot.wait(30)
        p = start + (end - start) * (k / steps)
        _send(editor, QEvent.Type.MouseMove, p, NONE, button, modifiers)
        if between is not None and k == steps // 2:
            between()
    qtbot.wait(30)
    _send(editor, QEvent.Type.MouseButtonRelease, end, button, NONE, modifiers)
    qtbot.wait(30)


def click(qtbot, editor, pos: QPoint, button=L) -> None:
    hover(qtbot, editor, pos)
    _send(editor, QEvent.Type.MouseButtonPress, pos, button, button)
    _send(editor, QEvent.Type.MouseButtonRelease, pos, button, NONE)
    qtbot.wait(30)


def double_click(qtbot, editor, pos: QPoint) -> None:
    hover(qtbot, editor, pos)
    _send(editor, QEvent.Type.MouseButtonPress, pos, L, L)
    _send(editor, QEvent.Type.MouseButtonRelease, pos, L, NONE)
    _send(editor, QEvent.Type.MouseButtonDblClick, pos, L, L)
    _send(editor, QEvent.Type.MouseButtonRelease, pos, L, NONE)
    qtbot.wait(30)


def menu_action(editor, text: str):
    menu = editor.edits.context_menu
    assert menu is not None
    for action in menu.actions():
        if action.text() == text:
            return action
    raise AssertionError(f"{text!r} not in {[a.text() for a in menu.actions()]}")
