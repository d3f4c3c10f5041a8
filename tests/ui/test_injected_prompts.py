"""The window's questions come from the prompts object it was given (issue 27 item 5, "dialogs through one
injected prompts object"): a MainWindow built with a ScriptedPrompts opens no dialog; the script answers what
the user would, and the menu commands, triggered as a user does, act on those answers."""


from motiontool.formats.zbc import read_config


def test_reset_arrays_answered_no_leaves_the_arrays_and_yes_deletes_them(scripted, qtbot):
    """DG 2962: "The → Arrays function will delete all arrays in RAM"; the IDE asks "Continue?" first."""
    w, prompts = scripted
    link = w.bridge.link
    link.call("restore_arrays", arrays=[{"name": "table", "values": [1, 2, 3]}])
    prompts.answers.append(False)
    w.actions_by_text["Arrays..."].trigger()
    assert prompts.asked == [("confirm", "Reset Arrays", "Reset Arrays: all arrays in the controller are deleted "
                                                         "(like DELETE ARRAYS). Continue?")]
    assert len(link.call("list_arrays")) == 1 and not prompts.answers
    prompts.answers.append(True)
    w.actions_by_text["Arrays..."].trigger()
    qtbot.waitUntil(lambda: "reset arrays done" in w.messages.toPlainText(), timeout=10000)
    assert link.call("list_arrays") == []


def test_save_to_file_writes_where_the_script_says_and_an_unwritable_place_is_said(scripted, tmp_path, qtbot):
    """DG 2892: "enter a name in the subsequent "Save As" dialog"; the name comes from the prompts. A folder
    that does not exist is said through the same prompts (decision R7) and nothing is written."""
    w, prompts = scripted
    w.bridge.link.write_parameter("KPROP", 77)
    path = tmp_path / "backup.zbc"
    prompts.answers.append(path)
    w.actions_by_text["Save to file..."].trigger()
    qtbot.waitUntil(lambda: f"configuration saved to {path}" in w.messages.toPlainText(), timeout=10000)
    assert prompts.asked == [("save_path", "Save to file", "controller.zbc")]
    assert read_config(path).parameters["32-60"] == 77
    nowhere = tmp_path / "missing" / "backup.zbc"
    prompts.answers.append(nowhere)
    w.actions_by_text["Save to file..."].trigger()
    qtbot.waitUntil(lambda: len(prompts.asked) == 3, timeout=10000)
    kind, title, text = prompts.asked[2]
    assert (kind, title) == ("warn", "Save to file") and text.startswith(f"Cannot write {nowhere}")
    assert not nowhere.parent.exists()



def test_prepare_singlestep_asks_before_it_stops_the_running_program(scripted, qtbot):
    """As Execute (DG 2385: "the user is asked if the existing program can be stopped"), Prepare Singlestep asks;
    No leaves the controller's program running, Yes stops it and prepares the debug run (DG L3364-3382)."""
    w, prompts = scripted
    editor = w.new_file()
    editor.setPlainText("i = 0\nWHILE 1 DO\n  i = i + 1\n  DELAY 10\nENDWHILE\n")
    w.actions_by_text["Execute"].trigger()
    link = w.bridge.link
    qtbot.waitUntil(lambda: link.status().program_state == "running", timeout=10000)
    question = ("confirm", "Prepare Singlestep", "The controller is executing a program. Stop it?")
    prompts.answers.append(False)
    w.actions_by_text["Prepare Singlestep"].trigger()
    qtbot.waitUntil(lambda: question in prompts.asked, timeout=10000)
    qtbot.wait(300)
    assert link.status().program_state == "running" and not w.debugger.active
    assert "Prepare stepping ok" not in w.messages.toPlainText()
    prompts.answers.append(True)
    w.actions_by_text["Prepare Singlestep"].trigger()
    qtbot.waitUntil(lambda: "Prepare stepping ok" in w.messages.toPlainText(), timeout=10000)
    assert prompts.asked.count(question) == 2 and link.status().program_state == "break"
