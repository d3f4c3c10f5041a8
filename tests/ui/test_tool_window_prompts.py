"""The tool windows and the program editor ask through their APOSS window's prompts (issue 27 item 5, "dialogs
through one injected prompts object"): a MainWindow built with a ScriptedPrompts gives them its prompts (the CAM
editor, Array Editor and oscilloscope through the bridge, the editor when the window creates it), so the script
answers what the user would and no dialog opens. Driven as a user does: menu and toolbar actions triggered, keys."""

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QPushButton

from motiontool.scope import zbo


def test_the_cam_editors_write_to_controller_asks_through_the_windows_prompts(scripted, qtbot):
    """DG 3507: "the existing controller parameters will be overwritten ... when this configuration file is
    downloaded to the controller"; the editor asks first. No keeps the controller's KPROP, Yes writes it."""
    w, prompts = scripted
    link = w.bridge.link
    w.actions_by_text["CAM-Editor"].trigger()
    editor = w.cam_editor
    qtbot.waitExposed(editor)
    editor.actions_by_name["read"].trigger()      # not modified yet: no question
    assert editor.parameters and prompts.asked == []
    key = next(k for k in editor.parameters if k.startswith("32-60") or k == "KPROP")
    link.write_parameter("KPROP", 5)
    editor.parameters[key] = 91
    question = ("confirm", "CAM-Editor", "Write all parameters and arrays of this file to the controller? Its own "
                                         "parameters and arrays are overwritten.")
    prompts.answers.append(False)
    editor.actions_by_name["write"].trigger()
    assert prompts.asked == [question] and link.read_parameter("KPROP") == 5
    prompts.answers.append(True)
    editor.actions_by_name["write"].trigger()
    assert prompts.asked == [question, question]
    assert editor.message_line.text() == "Parameters and arrays written to the controller"
    assert link.read_parameter("KPROP") == 91
    editor.set_modified(modified=False)   # closing at teardown asks nothing


def test_the_oscilloscopes_save_asks_for_its_name_through_the_windows_prompts(scripted, qtbot, tmp_path):
    """DG 5351: the curves and settings "can be saved as an "oscilloscope file" ... Oscilloscope files will always
    have a ".zbo" file extension". A folder that does not exist is said through the same prompts (decision R7)."""
    w, prompts = scripted
    w.actions_by_text["Oscilloscope"].trigger()
    scope = w._scopes[-1]
    qtbot.waitExposed(scope)
    prompts.answers.append(tmp_path / "recording")
    scope.save_action.trigger()
    assert prompts.asked == [("save_name", "Save oscilloscope", "")]
    assert zbo.load(tmp_path / "recording.zbo").variant == scope.scope.variant
    nowhere = tmp_path / "missing" / "recording.zbo"
    prompts.answers.append(nowhere)
    scope.save_action.trigger()
    kind, title, text = prompts.asked[-1]
    assert (kind, title) == ("warn", "Save") and text.startswith(f"Cannot write {nowhere}")
    assert not nowhere.parent.exists()


def test_the_array_editors_add_array_asks_its_size_through_the_windows_prompts(scripted, qtbot):
    """DG 4398: Add Array "will allow a new array to be added after the last existing array. The user will be
    prompted for the array size." Cancel adds none."""
    w, prompts = scripted
    w.actions_by_text["Array Editor"].trigger()
    editor = w._array_editor
    qtbot.waitExposed(editor)
    before = len(editor.data_list.rows)
    prompts.answers.extend([None, 7])
    editor.actions_by_text["Add array..."].trigger()
    assert len(editor.data_list.rows) == before
    editor.actions_by_text["Add array..."].trigger()
    assert prompts.asked == [("integer", "Add array", "Number of elements:")] * 2
    assert len(editor.data_list.rows) == before + 7


def test_the_program_editor_asks_through_the_windows_prompts(scripted, qtbot, tmp_path):
    """DG 2116: "[Ctrl]-[G] Go to line (opens dialog)"; DG 2328-2330: Find in Files searches "within files" - its
    folder is chosen through the same prompts."""
    w, prompts = scripted
    editor = w.current_editor() or w.new_file()
    editor.setPlainText("a = 1\nb = 2\nc = 3\nd = 4\n")
    editor.setFocus()
    qtbot.waitUntil(editor.hasFocus)
    prompts.answers.append(3)
    qtbot.keyClick(editor, Qt.Key.Key_G, Qt.KeyboardModifier.ControlModifier)
    assert prompts.asked == [("integer", "Go to Line", "Line number (1-5):")]
    assert editor.caret_line_col() == (3, 1)
    w.actions_by_text["Find in Files..."].trigger()
    dialog = editor.search.files_dialog
    qtbot.waitExposed(dialog)
    button = next(b for b in dialog.findChildren(QPushButton) if b.text() == "...")
    before = dialog.folder_edit.text()
    prompts.answers.append(tmp_path)
    qtbot.mouseClick(button, Qt.MouseButton.LeftButton)
    assert prompts.asked[-1] == ("folder", "Folder", before)
    assert dialog.folder_edit.text() == str(tmp_path)
    dialog.close()
