"""The Controller menu's dialogs as a user drives them (issue 16 item 3): Parameters ▸ Axis / Global / Name,
Error History, Programs (Include Sourcecode, Upload, the Source column), Memory, Development ▸ Download all.
Each dialog is opened through its menu action and answered by clicking and typing into its widgets; a button
that opens a dialog of its own is clicked after the reply returns (`later`), so the next reply answers that."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QPoint, Qt, QTimer
from PySide6.QtWidgets import QCheckBox, QLineEdit, QMessageBox, QPushButton, QWidget

from motiontool.ui.controller_menu import ProgramsDialog
from motiontool.ui.download_dialog import DownloadDialog, parse_ids
from motiontool.ui.error_history import ErrorHistoryDialog
from motiontool.ui.parameter_dialogs import NameDialog, ParametersDialog
from tests.modal import answering, answering_inner, button_reply, file_reply, text_reply, when_idle
from tests.ui.test_user_defects import run_failing


def click(qtbot, widget) -> None:
    qtbot.mouseClick(widget, Qt.MouseButton.LeftButton)


def tick(qtbot, box: QCheckBox) -> None:
    """Click a check box on its indicator (a box stretched by its layout does not take clicks at its centre)."""
    qtbot.mouseClick(box, Qt.MouseButton.LeftButton, pos=QPoint(6, box.height() // 2))


def later(action) -> None:
    """Run `action` once the current reply has returned (a button whose slot opens another modal dialog)."""
    QTimer.singleShot(0, action)


def retype(qtbot, edit: QLineEdit, text: str, *, leave_to: QWidget | None = None) -> None:
    """Click into the field, select all, type, then end the entry as a user does: Return (which also presses the
    dialog's default button) or a click into another field (`leave_to`)."""
    click(qtbot, edit)
    edit.selectAll()
    qtbot.keyClicks(edit, text)
    if leave_to is None:
        qtbot.keyClick(edit, Qt.Key.Key_Return)
    else:
        click(qtbot, leave_to)


def button(dialog, text: str) -> QPushButton:
    return next(b for b in dialog.findChildren(QPushButton) if b.text().replace("&", "") == text)


def values_read(qtbot, dialog: ParametersDialog, timeout_ms: int = 10_000) -> None:
    """The dialog appears at once and reads its values on a worker (issue 27 item 2): wait as a user waits."""
    qtbot.waitUntil(lambda: dialog.waiting == 0 and dialog.ok.isEnabled(), timeout=timeout_ms)


def choose_group(qtbot, dialog: ParametersDialog, title: str) -> None:
    item = dialog.groups.findItems(title, Qt.MatchFlag.MatchExactly)[0]
    qtbot.mouseClick(dialog.groups.viewport(), Qt.MouseButton.LeftButton,
                     pos=dialog.groups.visualItemRect(item).center())


# --- Parameters ▸ Axis / Global / Name -------------------------------------------------------------------------
def test_axis_parameters_refuse_a_bad_kprop_with_the_reason_and_write_a_good_one(window, qtbot):
    """DG 2830-2836: "the axis parameters … are displayed" in the manual's groups; a value outside the range is
    refused with the reason and never sent; a changed value is marked; OK writes it to the controller."""
    seen = {}

    def edit(dialog):
        assert isinstance(dialog, ParametersDialog)
        dialog.activateWindow()             # as the window manager does: typing goes to the dialog, focus moves
        qtbot.waitUntil(dialog.isActiveWindow, timeout=2000)
        values_read(qtbot, dialog)
        seen["groups"] = [dialog.groups.item(i).text() for i in range(dialog.groups.count())]
        choose_group(qtbot, dialog, "Position Regulation")
        field = dialog.fields["32-60"]
        assert field.widget.isVisible() and field.widget.text() == "30"
        retype(qtbot, field.widget, "100001")
        seen["refused"] = dialog.message.text()
        click(qtbot, button(dialog, "OK"))          # refused: the dialog stays open and says why
        seen["after_ok"] = (dialog.isVisible(), dialog.message.text(), dialog.w.bridge.link.read_parameter("KPROP"))
        retype(qtbot, field.widget, "250", leave_to=dialog.fields["32-61"].widget)
        seen["changed_style"] = field.widget.styleSheet()
        seen["pending"] = dialog.message.text()
        click(qtbot, button(dialog, "OK"))
        qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=10_000)   # once written (link-jobs thread)

    with answering(qtbot, edit):
        window.actions_by_text["Axis..."].trigger()
    assert seen["groups"] == ["Basic Settings", "Encoder Data", "Predefined I/Os", "Homing", "Synchronization",
                              "Sync Marker", "Position Regulation"]
    assert "KPROP: 100001 is outside 0..100000" in seen["refused"]
    assert seen["after_ok"] == (True, "Not written: 32-60 KPROP: 100001 is outside 0..100000", 30)
    assert "bold" in seen["changed_style"] and "1 changed value" in seen["pending"]
    assert window.bridge.link.read_parameter("KPROP") == 250
    assert "Controller 1: wrote 32-60 KPROP" in window.messages.toPlainText()


def test_choosing_another_controller_writes_the_changed_kprop_to_the_one_left_and_reads_the_next(window, qtbot):
    """DG 2816-2818: "the changed values are written to the previous controller and the new controller's values
    are read and displayed in the fields" - on the dialog's link-jobs thread (I30): while the values come the
    fields wait and say so."""
    seen = {}
    other = window.controllers.link(2, interface=window.connection.interface_key)
    other.write_parameter("KPROP", 44)

    def switch(dialog):
        assert isinstance(dialog, ParametersDialog)
        dialog.activateWindow()
        qtbot.waitUntil(dialog.isActiveWindow, timeout=2000)
        values_read(qtbot, dialog)
        choose_group(qtbot, dialog, "Position Regulation")
        field = dialog.fields["32-60"]
        retype(qtbot, field.widget, "55", leave_to=dialog.fields["32-61"].widget)
        seen["controllers"] = [dialog.controller.itemText(i) for i in range(dialog.controller.count())]
        qtbot.keyClick(dialog.controller, Qt.Key.Key_Down)       # the next controller, as from the keyboard
        assert not dialog.ok.isEnabled()                         # writing to 1, then reading 2
        values_read(qtbot, dialog)
        seen["shown"] = (dialog.controller.currentData(), field.widget.text(), field.widget.styleSheet())
        click(qtbot, button(dialog, "Cancel"))

    with answering(qtbot, switch):
        window.actions_by_text["Axis..."].trigger()
    assert seen["controllers"][:2] == ["Controller 1", "Controller 2"]
    assert seen["shown"] == (2, "44", "")
    assert window.controllers.link(1, interface=window.connection.interface_key).read_parameter("KPROP") == 55
    assert other.read_parameter("KPROP") == 44
    assert "Controller 1: wrote 32-60 KPROP" in window.messages.toPlainText()


def test_global_parameters_show_the_manuals_groups_and_cancel_writes_nothing(window, qtbot):
    """DG 2808: the global parameters (the I/O functions, 33-8*); Cancel leaves the controller as it was."""
    seen = {}

    def look(dialog):
        assert isinstance(dialog, ParametersDialog)
        values_read(qtbot, dialog)
        labels = [w.text() for w in dialog.findChildren(type(dialog.message)) if w.isVisible()]
        seen["headings"] = [t for t in labels if t in ("Inputs and outputs", "Global", "CAN bus and RS-485")]
        field = next(f for f in dialog.fields.values() if isinstance(f.widget, QLineEdit))
        seen["number"] = field.p.number
        seen["before"] = dialog.w.bridge.link.read_parameter(field.p.number)
        retype(qtbot, field.widget, str(int(field.p.minimum)))
        click(qtbot, button(dialog, "Cancel"))

    with answering(qtbot, look):
        window.actions_by_text["Global..."].trigger()
    assert seen["headings"] == ["Inputs and outputs", "Global", "CAN bus and RS-485"]
    assert window.bridge.link.read_parameter(seen["number"]) == seen["before"]


def test_the_name_dialog_takes_upper_case_as_typed_and_refuses_a_long_name_before_ok(window, qtbot):
    """DG 2870-2882: "Names cannot be longer than 8 characters and must be uppercase". Lower case becomes upper
    case as it is typed; a ninth character is refused at once, with OK off (issue 23 item 11: both waited for OK)."""
    seen = {}

    def name(dialog):
        assert isinstance(dialog, NameDialog)
        qtbot.waitUntil(dialog.name.isEnabled, timeout=5000)          # read on the link-jobs thread (I30)
        retype(qtbot, dialog.name, "conveyor1")
        seen["typed"] = (dialog.name.text(), dialog.message.text(), dialog.ok.isEnabled())
        click(qtbot, button(dialog, "OK"))
        seen["visible"] = dialog.isVisible()
        retype(qtbot, dialog.name, "feeder")                          # its Return presses OK, now enabled
        qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=10_000)   # once written

    with answering(qtbot, name):
        window.actions_by_text["Name..."].trigger()
    text, message, ok = seen["typed"]
    assert text == "CONVEYOR1" and "'CONVEYOR1': 9 characters, at most 8" in message and not ok
    assert seen["visible"]
    assert window.bridge.link.call("identify")["name"] == "FEEDER"


# --- Error History ---------------------------------------------------------------------------------------------
def test_error_history_lists_the_error_with_its_line_writes_a_file_and_a_double_click_jumps(window, qtbot,
                                                                                             tmp_path):
    """DG 2982-3027: the table Error, Message, Data, Offset, Line, Age; Write saves it as a text file; a
    double-click closes the dialog and shows the line in the program."""
    editor = run_failing(window, qtbot)            # error 171 (array index) in line 5
    editor.goto_line(1)
    target = tmp_path / "errors.txt"
    seen = {}

    def look(dialog):
        assert isinstance(dialog, ErrorHistoryDialog)
        table = dialog.table
        headers = [table.horizontalHeaderItem(c).text() for c in range(table.columnCount())]
        seen["row"] = dict(zip(headers, (table.item(0, c).text() for c in range(table.columnCount())), strict=True))
        later(lambda: click(qtbot, button(dialog, "Write...")))

    def jump(dialog):
        assert isinstance(dialog, ErrorHistoryDialog)
        rect = dialog.table.visualRect(dialog.table.model().index(0, 4))
        qtbot.mouseClick(dialog.table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
        qtbot.mouseDClick(dialog.table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())

    with answering(qtbot, look, file_reply(target), jump):
        window.actions_by_text["Error History..."].trigger()
    row = seen["row"]
    assert row["Error"] == "171" and row["Line"] == "5" and row["Message"] == "Array too small"
    assert row["Offset"].isdigit() and float(row["Age"]) >= 0
    text = target.read_text(encoding="utf-8").splitlines()
    assert text[1] == "#\tTime\tAge\tError\tMessage\tData\tOffset\tLine\tProgram"
    assert text[2].split("\t")[3] == "171" and text[2].split("\t")[8] == "Untitled.m"
    assert window.current_editor() is editor and editor.textCursor().blockNumber() + 1 == 5


def test_error_history_clear_empties_the_list(window, qtbot):
    run_failing(window, qtbot)
    seen = {}

    def clear(dialog):
        seen["before"] = dialog.table.rowCount()
        click(qtbot, button(dialog, "Clear"))
        seen["after"] = dialog.table.rowCount()
        click(qtbot, button(dialog, "Close"))

    with answering(qtbot, clear):
        window.actions_by_text["Error History..."].trigger()
    assert seen == {"before": 1, "after": 0}
    assert window.bridge.link.call("error_history") == []


# --- Programs: Include Sourcecode, Upload -----------------------------------------------------------------------
def test_programs_save_with_source_and_upload_it_into_a_new_tab(window, qtbot, tmp_path):
    """DG 2643-2675: with Include Sourcecode the source is stored with the program; Upload brings it back."""
    source = 'PRINT "kept with its source"\n'
    editor = window.new_file()
    editor.setPlainText(source)
    target = tmp_path / "uploaded.m"
    seen = {}

    def save(dialog):
        assert isinstance(dialog, ProgramsDialog)
        tick(qtbot, dialog.findChild(QCheckBox))
        seen["checked"] = dialog.include_source.isChecked()
        later(lambda: click(qtbot, button(dialog, "Save")))

    @when_idle   # Save's store and refresh are answered first: the program is listed, a click is not dropped
    def upload(dialog):
        assert isinstance(dialog, ProgramsDialog)
        seen["row"] = [dialog.table.item(0, c).text() for c in range(4)]
        rect = dialog.table.visualRect(dialog.table.model().index(0, 1))
        qtbot.mouseClick(dialog.table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
        later(lambda: click(qtbot, button(dialog, "Upload...")))

    def close(dialog):
        click(qtbot, button(dialog, "Close"))

    with answering(qtbot, save, text_reply("KEEPSRC"), upload, file_reply(target), close):
        window.actions_by_text["Programs..."].trigger()
    assert seen["checked"]
    assert seen["row"] == ["0", "KEEPSRC", "", "✓"]
    assert target.read_text(encoding="utf-8") == source
    assert window.current_editor().toPlainText() == source and window.current_editor() is not editor


# --- Memory -------------------------------------------------------------------------------------------------------
def test_memory_save_ram_keeps_a_parameter_through_power_on_and_delete_eprom_forgets_it(window, qtbot):
    """DG 2908-2946: Save RAM copies the parameters to the EPROM (a SET value survives a power cycle only then);
    Delete EPROM brings the factory settings at the next power on. Each asks first."""
    assert window.development.connect_default()
    link = window.bridge.link
    link.write_parameter("KPROP", 77)
    with answering(qtbot, button_reply(QMessageBox.StandardButton.Yes)):
        window.actions_by_text["Save RAM"].trigger()
    link.call("power_on")
    assert link.read_parameter("KPROP") == 77
    with answering(qtbot, button_reply(QMessageBox.StandardButton.No)):
        window.actions_by_text["Delete EPROM"].trigger()
    link.call("power_on")
    assert link.read_parameter("KPROP") == 77
    with answering(qtbot, button_reply(QMessageBox.StandardButton.Yes)):
        window.actions_by_text["Delete EPROM"].trigger()
    link.call("power_on")
    assert link.read_parameter("KPROP") == 30
    text = window.messages.toPlainText()
    assert "Save RAM done" in text and "Delete EPROM done (takes effect at the next power on)" in text


# --- Download all -----------------------------------------------------------------------------------------------
def test_parse_ids_reads_lists_and_ranges_and_names_a_bad_part():
    assert parse_ids("1-3,7, 9,2") == [1, 2, 3, 7, 9]
    with pytest.raises(ValueError, match="'x' is not an ID"):
        parse_ids("1,x")
    with pytest.raises(ValueError, match="runs backwards"):
        parse_ids("5-2")


def confirm_deletion(qtbot, seen: dict, *, delete: bool = True):
    """Download all's question before it deletes the stored programs: note what it names, then answer."""
    def reply(box):
        assert isinstance(box, QMessageBox), f"expected a message box, got {box!r}"
        seen["asked"] = box.informativeText()
        chosen = next(b for b in box.buttons() if b.text() == "Delete and Download") if delete \
            else box.button(QMessageBox.StandardButton.Cancel)
        click(qtbot, chosen)
    return reply


def test_download_all_stores_program_0_on_each_controller_verifies_and_sets_autostart(window, qtbot, tmp_path):
    """DG 3276-3336: one program to several controllers: delete all, download and save as program 0, Verify,
    Set Autostart; the log names the controllers done."""
    path = tmp_path / "line.m"
    path.write_text('PRINT "line"\n', encoding="utf-8")
    window.open_file(path)
    assert window.development.connect_default()
    old = window.controllers.link(2)
    old.download(window.development.compile_current().result.image.to_bytes(), number=5, name="OLD")
    seen = {}

    def run(dialog):
        assert isinstance(dialog, DownloadDialog)
        assert dialog.file.text() == str(path) and dialog.name.text() == "LINE"
        retype(qtbot, dialog.controllers, "1-2")
        tick(qtbot, dialog.options["autostart"])
        with answering_inner(qtbot, QMessageBox, confirm_deletion(qtbot, seen)):  # controller 2 has a stored program
            click(qtbot, button(dialog, "Start"))
        seen["log"] = dialog.log.toPlainText()
        click(qtbot, button(dialog, "Close"))

    with answering(qtbot, run):
        window.actions_by_text["Download all"].trigger()
    log = seen["log"]
    assert seen["asked"] == "Controller 2: 5 OLD"
    assert "Controller 1: verify ok" in log and "Controller 2: verify ok" in log
    assert "Done for controllers: 1, 2" in log and "Failed" not in log
    for cid in (1, 2):
        programs = window.controllers.link(cid).call("list_programs")
        assert [(p["number"], p["name"], bool(p["autostart"])) for p in programs] == [(0, "LINE", True)], cid


def test_download_all_with_verify_only_reports_a_controller_whose_program_differs(window, qtbot, tmp_path):
    """Verify without Download compares only; a mismatch fails that controller and the summary names it."""
    path = tmp_path / "line.m"
    path.write_text('PRINT "line"\n', encoding="utf-8")
    window.open_file(path)
    seen = {}

    def run(dialog):
        tick(qtbot, dialog.options["download"])
        click(qtbot, button(dialog, "Start"))
        seen["log"] = dialog.log.toPlainText()
        click(qtbot, button(dialog, "Close"))

    with answering(qtbot, run):
        window.actions_by_text["Download all"].trigger()
    assert "Controller 1: no program 0" in seen["log"] and "Failed for controllers: 1" in seen["log"]
    assert window.controllers.link(1).call("list_programs") == []


def test_global_parameters_show_each_description_whole(window, qtbot):
    """Issue 23 item 11: "Global Parameters labels truncated" - cut at 60 characters, 33-61's lost the end of
    '(input 11; visible when IOMODE = 0)'. Each label holds the whole description, wrapped."""
    from PySide6.QtWidgets import QLabel

    seen = {}

    def look(dialog):
        assert isinstance(dialog, ParametersDialog)
        qtbot.waitUntil(lambda: any("[33-61" in label.text() for label in dialog.findChildren(QLabel)), timeout=5000)
        label = next(label for label in dialog.findChildren(QLabel) if "[33-61" in label.text())
        seen["text"], seen["wraps"] = label.text(), label.wordWrap()
        click(qtbot, button(dialog, "Cancel"))

    with answering(qtbot, look):
        window.actions_by_text["Global..."].trigger()
    assert "(input 11; visible when IOMODE = 0) [33-61 I_FUNCTION_11]" in seen["text"] and seen["wraps"]
