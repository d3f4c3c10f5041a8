"""The smaller defects a new user met in the first hour (issue 23 item 11), each driven as a user does:
menu actions triggered, buttons clicked with the mouse, names typed key by key."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtGui import QFontMetrics
from PySide6.QtWidgets import QInputDialog, QLineEdit, QPushButton

from tests.modal import answering


def click(qtbot, widget) -> None:
    qtbot.mouseClick(widget, Qt.MouseButton.LeftButton)


def button(dialog, text: str) -> QPushButton:
    return next(b for b in dialog.findChildren(QPushButton) if b.text() == text)


def in_font(widget, text: str) -> bool:
    metrics = QFontMetrics(widget.font())
    return all(metrics.inFontUcs4(ord(ch)) for ch in text)


def typed_name(qtbot, seen: list[str], name: str | None = None):
    """An input dialog: note the name it suggests, type `name` over it (or keep it) and press OK."""
    def reply(dialog):
        assert isinstance(dialog, QInputDialog), f"expected an input dialog, got {dialog!r}"
        seen.append(dialog.textValue())
        if name is not None:
            edit = dialog.findChild(QLineEdit)
            edit.selectAll()
            qtbot.keyClicks(edit, name, delay=5)
        dialog.accept()
    return reply


def in_programs_dialog(qtbot, window, body) -> None:
    """Controller ▸ Programs, `body(dialog)` in it, then Close."""
    errors = []

    def reply(dialog):
        try:
            body(dialog)
        except BaseException as exc:  # noqa: BLE001 - raised after the dialog is closed, not left to hang
            errors.append(exc)
        click(qtbot, button(dialog, "Close"))

    with answering(qtbot, reply, timeout=20000):
        window.actions_by_text["Programs..."].trigger()
    if errors:
        raise errors[0]


def test_the_autostart_mark_is_a_glyph_of_the_table_font(window, qtbot):
    """DG 2727: "The Autostart program will be marked with a ⊙ in the Autostart column"; the mark was "⦿",
    which no installed font has, so the cell showed an empty box."""
    editor = window.new_file()
    qtbot.keyClicks(editor, 'PRINT "boot"')
    marks = []

    def body(dialog):
        with answering(qtbot, typed_name(qtbot, [])):
            click(qtbot, button(dialog, "Save"))
        table = dialog.table
        rect = table.visualItemRect(table.item(0, 1))
        qtbot.mouseClick(table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
        click(qtbot, button(dialog, "Autostart on"))
        marks.append(table.item(0, 2).text())
        marks.append(in_font(table, table.item(0, 2).text()))

    in_programs_dialog(qtbot, window, body)
    assert marks == ["\u2299", True]
