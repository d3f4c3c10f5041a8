"""Files keep what the user made, under a name File ▸ Open finds (issue 23 item 9): Save as adds the selected
filter's extension to a name typed without one, and closing the IDE asks about an unsaved scope recording.
Driven as a user does: menu actions, the name typed key by key into Qt's own file dialog, buttons clicked."""

from __future__ import annotations

from fnmatch import fnmatch

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QComboBox, QDialogButtonBox, QFileDialog, QLineEdit, QMessageBox, QToolButton

from motiontool.ui.documents import OPEN_FILTER
from tests.modal import answering, button_reply

Button = QMessageBox.StandardButton


def type_name(qtbot, name: str, *, filter_down: int = 0):
    """A file dialog: choose a filter with the arrow keys (`filter_down` rows down), type `name`, click Save."""
    def reply(dialog):
        assert isinstance(dialog, QFileDialog), f"expected a file dialog, got {dialog!r}"
        combo = dialog.findChild(QComboBox, "fileTypeCombo")
        for _ in range(filter_down):
            qtbot.keyClick(combo, Qt.Key.Key_Down)
        edit = dialog.findChild(QLineEdit, "fileNameEdit")
        edit.selectAll()
        qtbot.keyClicks(edit, name, delay=5)
        qtbot.wait(150)  # a user looks before clicking; the dialog lays out its buttons meanwhile
        save = dialog.findChild(QDialogButtonBox, "buttonBox").button(QDialogButtonBox.StandardButton.Save)
        qtbot.mouseClick(save, Qt.MouseButton.LeftButton)
    return reply


def opens(path) -> bool:
    """File ▸ Open's filter shows the file (any of its name patterns)."""
    patterns = [p for part in OPEN_FILTER.split(";;") for p in part.split("(")[-1].rstrip(")").split()]
    return any(fnmatch(path.name, p) for p in patterns if p != "*")


def test_save_as_adds_the_extension_of_the_chosen_filter(window, qtbot, tmp_path):
    """A program saved as `ctl2_test` was written without an extension, and File ▸ Open's filter then hid it."""
    editor = window.new_file()
    qtbot.keyClicks(editor, 'PRINT "ctl2"')
    with answering(qtbot, type_name(qtbot, str(tmp_path / "ctl2_test"))):
        window.actions_by_text["Save as..."].trigger()
    assert (tmp_path / "ctl2_test.m").read_text(encoding="utf-8") == 'PRINT "ctl2"'
    assert not (tmp_path / "ctl2_test").exists() and opens(tmp_path / "ctl2_test.m")
    assert window.tabs.tabText(window.tabs.currentIndex()) == "ctl2_test.m"

    dpl = window.new_file()
    qtbot.keyClicks(dpl, "Initial{")
    with answering(qtbot, type_name(qtbot, str(tmp_path / "cam_task"), filter_down=1)):  # DPL programs (*.dpl)
        window.actions_by_text["Save"].trigger()  # never saved: Save asks for the name
    assert (tmp_path / "cam_task.dpl").exists() and not (tmp_path / "cam_task").exists()
    assert dpl.language == "dpl"

    with answering(qtbot, type_name(qtbot, str(tmp_path / "notes.txt"))):  # a name with an extension is kept
        window.actions_by_text["Save as..."].trigger()
    assert (tmp_path / "notes.txt").exists() and not (tmp_path / "notes.txt.m").exists()


def test_closing_the_ide_asks_about_an_unsaved_scope_recording(window, qtbot, tmp_path):
    """Closing the IDE dropped an unsaved oscilloscope recording without asking."""
    window.ask_to_save = True
    window.actions_by_text["Oscilloscope"].trigger()
    scope = window._scopes[-1]
    scope.add_signal_curve("4119", group="Test Group (Free Run)")
    start = next(b for b in scope.findChildren(QToolButton) if b.defaultAction() is scope.start_action)
    qtbot.mouseClick(start, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(scope.scope.curves[0].buffer) > 20, timeout=5000)

    with answering(qtbot, button_reply(Button.Cancel)) as answers:
        window.actions_by_text["Exit Program"].trigger()
    assert answers.seen == ["QMessageBox 'Oscilloscope'"]
    assert window.isVisible() and scope.isVisible()  # Cancel: nothing closed, the recording goes on

    with answering(qtbot, button_reply(Button.Save), type_name(qtbot, str(tmp_path / "run1"))):
        window.actions_by_text["Exit Program"].trigger()
    assert (tmp_path / "run1.zbo").stat().st_size > 0 and opens(tmp_path / "run1.zbo")
    assert not window.isVisible() and not scope.isVisible()


def test_a_discarded_or_saved_recording_is_not_asked_about_again(window, qtbot, tmp_path):
    window.ask_to_save = True
    window.actions_by_text["Oscilloscope"].trigger()
    scope = window._scopes[-1]
    scope.add_signal_curve("4119", group="Test Group (Free Run)")
    start = next(b for b in scope.findChildren(QToolButton) if b.defaultAction() is scope.start_action)
    stop = next(b for b in scope.findChildren(QToolButton) if b.defaultAction() is scope.stop_action)
    qtbot.mouseClick(start, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(scope.scope.curves[0].buffer) > 20, timeout=5000)
    qtbot.mouseClick(stop, Qt.MouseButton.LeftButton)
    with answering(qtbot, type_name(qtbot, str(tmp_path / "kept"))):
        scope.save_action.trigger()
    assert (tmp_path / "kept.zbo").exists()
    assert not scope.unsaved_recording()
    with answering(qtbot):  # saved: no question
        window.actions_by_text["Exit Program"].trigger()
    assert not window.isVisible()
