"""A failed save keeps the window open with a clear message and the user's work intact, on every save path of the IDE
and its tool windows (issue 18, item 1; decisions R7). Driven as a user does: menu actions, modal dialogs answered.

The failure is the one users meet: the folder is gone when the save comes (a share unmounted, a USB stick pulled);
the file dialog's folder disappears right after the name is chosen.
"""

from __future__ import annotations

import shutil

from PySide6.QtWidgets import QMessageBox

from motiontool import cli
from tests.answer_dialogs import Answers, ChooseFile

Button = QMessageBox.StandardButton


def share(tmp_path):
    folder = tmp_path / "share"
    folder.mkdir()
    return folder


def test_closing_with_a_failing_save_keeps_the_window_and_the_text(window, qtbot, tmp_path):
    """The text typed was lost: MainWindow.save() let the OSError escape from closeEvent and the window closed."""
    folder = share(tmp_path)
    (folder / "p.m").write_text('PRINT "old"\n', encoding="utf-8")
    editor = window.open_file(folder / "p.m")
    window.ask_to_save = True
    qtbot.keyClicks(editor, "// typed just now")
    typed = editor.toPlainText()
    shutil.rmtree(folder)
    with Answers(qtbot, Button.Save, Button.Ok) as answers:
        window.actions_by_text["Exit Program"].trigger()
    assert answers.seen[0].text.startswith("Save changes to p.m")
    assert answers.seen[1].title == "Save"
    assert answers.seen[1].text == f"Cannot write {folder / 'p.m'}:\nNo such file or directory."
    assert "still open in the editor" in answers.seen[1].informative
    assert window.isVisible() and window.tabs.count() == 1
    assert editor.toPlainText() == typed and editor.document().isModified()
    with Answers(qtbot, Button.Ok) as answers:  # File → Save says the same, and nothing changes
        window.actions_by_text["Save"].trigger()
    assert answers.seen[0].text.startswith("Cannot write")
    folder.mkdir()  # the share is back: the same Save works
    window.actions_by_text["Save"].trigger()
    assert (folder / "p.m").read_text(encoding="utf-8") == typed and not editor.document().isModified()


def test_compile_to_file_and_the_log_file_report_their_failure(window, qtbot, tmp_path):
    folder = share(tmp_path)
    editor = window.new_file()
    editor.setPlainText('PRINT "x"\n')
    with Answers(qtbot, ChooseFile(str(folder / "p.bin"), then=lambda: shutil.rmtree(folder)), Button.Ok) as answers:
        window.actions_by_text["Compile to file..."].trigger()
    assert answers.seen[1].text == f"Cannot write {folder / 'p.bin'}:\nNo such file or directory."
    assert f"Compile to file: cannot write {folder / 'p.bin'}: No such file or directory" in \
        window.messages.toPlainText()
    folder.mkdir()
    log_action = next(a for a in window.findChildren(type(window.actions_by_text["Save"]))
                      if a.text() == "Log file...")
    with Answers(qtbot, ChooseFile(str(folder / "m.log"), then=lambda: shutil.rmtree(folder)), Button.Ok) as answers:
        log_action.trigger()
    assert answers.seen[1].title == "Log file" and answers.seen[1].text.startswith("Cannot write")
    assert not window.messages.logging


def test_controller_parameters_save_to_file_reports_its_failure(window, qtbot, tmp_path):
    folder = share(tmp_path)
    with Answers(qtbot, ChooseFile(str(folder / "c.zbc"), then=lambda: shutil.rmtree(folder)), Button.Ok) as answers:
        window.actions_by_text["Save to file..."].trigger()
    assert answers.seen[1].text == f"Cannot write {folder / 'c.zbc'}:\nNo such file or directory."
    assert window.isVisible()


def test_cam_editor_save_and_export_report_their_failure(window, qtbot, tmp_path):
    folder = share(tmp_path)
    window.actions_by_text["CAM-Editor"].trigger()
    cam = window.cam_editor
    stamping = tmp_path / "stamping.zbc"
    assert cli.main(["cam", "build", "--name", "stamping", "--point", "0,0", "--point", "1500,1200,T", "--point",
                     "2500,2400,T", "--point", "4000,3600", "-o", str(stamping)]) == 0
    assert cam.open_file(stamping)  # set-up; the saves below go through the toolbar
    cam.edits.edit("Stop position", lambda c: c.__class__(**{**c.__dict__, "slave_stop_position": 5}))
    assert cam.modified
    with Answers(qtbot, ChooseFile(str(folder / "c.zbc"), then=lambda: shutil.rmtree(folder)), Button.Ok) as answers:
        cam.actions_by_name["save_as"].trigger()
    assert answers.seen[1].text == f"Cannot write {folder / 'c.zbc'}:\nNo such file or directory.", \
        cam.message_line.text()
    assert cam.isVisible() and cam.modified and cam.path == stamping
    assert cam.message_line.text() == f"Save failed: cannot write {folder / 'c.zbc'}: No such file or directory"
    folder.mkdir()
    cam.select_array(0)
    with Answers(qtbot, ChooseFile(str(folder / "c.dat"), then=lambda: shutil.rmtree(folder)), Button.Ok) as answers:
        cam.actions_by_name["export"].trigger()
    assert answers.seen[1].title == "CAM-Editor — Export" and answers.seen[1].text.startswith("Cannot write")
    cam.modified = False


def test_scope_save_reports_its_failure(window, qtbot, tmp_path):
    folder = share(tmp_path)
    window.actions_by_text["Oscilloscope"].trigger()
    scope = window._scopes[-1]
    with Answers(qtbot, ChooseFile(str(folder / "s.zbo"), then=lambda: shutil.rmtree(folder)), Button.Ok) as answers:
        scope.save_action.trigger()
    assert answers.seen[1].title == "Save"
    assert answers.seen[1].text == f"Cannot write {folder / 's.zbo'}:\nNo such file or directory."
    assert answers.seen[1].informative == "The curves are still in this window: save them somewhere else."
    assert scope.isVisible()
    folder.mkdir()
    with Answers(qtbot, ChooseFile(str(folder / "s.csv"), then=lambda: shutil.rmtree(folder)), Button.Ok) as answers:
        scope.export_action.trigger()
    assert answers.seen[1].title == "Export" and answers.seen[1].text.startswith("Cannot write")


def test_array_editor_save_reports_its_failure(window, qtbot, tmp_path):
    folder = share(tmp_path)
    window.actions_by_text["Array Editor"].trigger()
    arrays = window._array_editor
    save = arrays.actions_by_text["Save File"]
    with Answers(qtbot, ChooseFile(str(folder / "a.zba"), then=lambda: shutil.rmtree(folder)), Button.Ok) as answers:
        save.trigger()
    assert answers.seen[1].title == "Array Editor"
    assert answers.seen[1].text == f"Cannot write {folder / 'a.zba'}:\nNo such file or directory."
    assert arrays.isVisible() and arrays.path is None


def test_a_file_that_cannot_be_opened_is_said_and_nothing_else_changes(window, qtbot, tmp_path):
    """File → Open of a device or pipe read until memory ran out (a FIFO never ends); a recent file deleted since,
    or a folder, let an OSError escape the slot: a traceback on stderr and no word in the IDE."""
    import os

    fifo = tmp_path / "pipe.m"
    os.mkfifo(fifo)
    before = window.tabs.count()
    with Answers(qtbot, ChooseFile(str(fifo)), Button.Ok) as answers:
        window.actions_by_text["Open..."].trigger()
    assert answers.seen[1].title == "Open"
    assert answers.seen[1].text == f"{fifo}: not a regular file (a device, pipe or socket)"
    gone = tmp_path / "gone.m"
    gone.write_text("a = 1\n", encoding="utf-8")
    window.open_file(gone)
    window.close_tab(window.tabs.currentIndex())
    gone.unlink()
    (recent,) = [a for a in window.recent_menu.actions() if a.text() == str(gone)]
    with Answers(qtbot, Button.Ok) as answers:
        recent.trigger()
    assert answers.seen[0].text == f"{gone}: No such file or directory"
    assert window.tabs.count() == before and f"Open: {gone}: No such file" in window.messages.toPlainText()
