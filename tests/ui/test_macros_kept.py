"""Macros belong to the IDE, not to one tab, and outlive it (DG L2204: "Up to 10 different macros can be defined.
These macros are saved and restored the next time that the APOS-IDE is started"; L2225: "All currently defined
macros can be cleared using Edit → Clear Macros"). Recorded and played with keys at a person's pace."""

from __future__ import annotations

from PySide6.QtCore import QSettings, Qt
from PySide6.QtWidgets import QApplication

from motiontool.ui.editor.macros import MACROS_KEY
from motiontool.ui.main_window import MainWindow

PACE_MS = 120
CTRL, SHIFT, ALT = (Qt.KeyboardModifier.ControlModifier, Qt.KeyboardModifier.ShiftModifier,
                    Qt.KeyboardModifier.AltModifier)


def key(qtbot, widget, code, modifiers=Qt.KeyboardModifier.NoModifier) -> None:
    qtbot.keyClick(widget, code, modifiers, delay=PACE_MS)


def window(qtbot, settings: QSettings) -> MainWindow:
    w = MainWindow(settings=settings, realtime_factor=50.0)
    w.ask_to_save = False
    qtbot.addWidget(w)
    w.show()
    qtbot.waitExposed(w)
    return w


def typed_tab(qtbot, w: MainWindow):
    w.actions_by_text["New"].trigger()
    w.activateWindow()
    editor = w.current_editor()
    editor.setFocus()
    return editor


def record_alt_m(qtbot, editor) -> None:
    """Ctrl+Shift+R, type "ab", Ctrl+Shift+R; in Save Macro press Alt+M and OK (DG L2206-2216)."""
    key(qtbot, editor, Qt.Key.Key_R, CTRL | SHIFT)
    for letter in (Qt.Key.Key_A, Qt.Key.Key_B):
        key(qtbot, editor, letter)
    key(qtbot, editor, Qt.Key.Key_R, CTRL | SHIFT)
    dialog = editor.recorder.macro_dialog
    qtbot.waitUntil(lambda: dialog.isVisible(), timeout=5000)
    dialog.shortcut_edit.setFocus()
    key(qtbot, dialog.shortcut_edit, Qt.Key.Key_M, ALT)
    qtbot.waitUntil(lambda: dialog.ok_button.isEnabled(), timeout=5000)
    qtbot.mouseClick(dialog.ok_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=5000)


def test_a_macro_recorded_in_one_tab_plays_in_another_and_after_a_restart_until_cleared(qtbot, tmp_path):
    settings = QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat)
    first = window(qtbot, settings)
    recorded = typed_tab(qtbot, first)
    record_alt_m(qtbot, recorded)
    assert recorded.toPlainText() == "ab"

    other = typed_tab(qtbot, first)                    # another program of the same IDE
    key(qtbot, other, Qt.Key.Key_M, ALT)
    assert other.toPlainText() == "ab"

    first.actions_by_text["New APOSS Window"].trigger()   # another window of the same IDE
    second = first.other_windows[-1]
    qtbot.addWidget(second)
    in_second = typed_tab(qtbot, second)
    key(qtbot, in_second, Qt.Key.Key_M, ALT)
    assert in_second.toPlainText() == "ab"
    assert second.macros is first.macros                  # one set: a macro saved in either is the other's

    restarted = window(qtbot, QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat))
    editor = typed_tab(qtbot, restarted)
    key(qtbot, editor, Qt.Key.Key_M, ALT)
    assert editor.toPlainText() == "ab"

    restarted.actions_by_text["Clear Macros"].trigger()
    key(qtbot, editor, Qt.Key.Key_M, ALT)
    assert not editor.toPlainText().startswith("abab")  # Alt+M is no macro any more: "ab" is not typed again
    assert restarted.macros.shortcuts() == []
    again = window(qtbot, QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat))
    assert again.macros.shortcuts() == []


def test_a_damaged_macro_entry_is_said_and_the_ide_starts_without_macros(qtbot, tmp_path):
    settings = QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat)
    settings.setValue(MACROS_KEY, '[["Alt+M", [[1, "x"]]]]')      # a keystroke without its text
    w = window(qtbot, settings)
    assert w.macros.shortcuts() == []
    assert any(f"Macros not restored: {MACROS_KEY} in the settings file is damaged" in line
               for line in w.messages.toPlainText().splitlines())
    QApplication.processEvents()
