"""The main window: menus of the manual, editing, syntax check, execute/break through the link (issue 7)."""

import subprocess
import sys

from PySide6.QtCore import Qt

from motiontool.ui.main_window import MainWindow

APOSS_MENUS = ["File", "Edit", "Development", "Controller", "Tools", "Settings", "Window", "Help"]


def test_menu_bar_has_the_aposs_menus(window):
    """ide-spec 1.26-1.50: File/Edit/Development/Controller/Tools/Settings/Window/Help."""
    titles = [a.text().replace("&", "") for a in window.menuBar().actions()]
    assert titles == APOSS_MENUS


def test_manual_shortcuts_are_bound(window):
    """DG 2380-2391 / ide-spec 2.4, 1.39: Execute is F5, Syntax Check is F4, Command List is F12."""
    shortcuts = {name: window.actions_by_text[name].shortcut().toString()
                 for name in ("Execute", "Syntax Check", "Command List...", "Break", "Next Bookmark")}
    assert shortcuts == {"Execute": "F5", "Syntax Check": "F4", "Command List...": "F12", "Break": "Esc",
                         "Next Bookmark": "F2"}


def test_open_file_shows_text_and_cursor_position(window, tmp_path):
    """ide-spec 1.5: the status bar shows line:column."""
    program = tmp_path / "hello.m"
    program.write_text("DIM a[2]\nPRINT \"hello\"\n", encoding="utf-8")
    editor = window.open_file(program)
    assert editor.toPlainText().startswith("DIM a[2]")
    assert window.tabs.tabText(window.tabs.currentIndex()) == "hello.m"
    editor.goto_line(2, col=2)
    assert window.cursor_label.text() == "2:2"
    assert window.open_file(program) is editor  # one program, one window (ide-spec 1.1)


def test_edit_menu_entries_act_on_the_program_being_edited(window):
    """DG L2294-2299: Edit → Toggle/Next/Clear All Bookmarks, Convert Tabs, Find; "[Ctrl]-[F2] will toggle the
    bookmark on the current line" (L2348), Convert Tabs "will replace tab characters ... with space characters"
    using the editor's tab spacing (L2356-2358). The entries reach the editor's parts (issue 27 item 7)."""
    editor = window.new_file()
    editor.setPlainText("a\n\tb\nc\n\td\n")
    entry = window.actions_by_text
    editor.goto_line(3)
    entry["Toggle Bookmark"].trigger()
    assert editor.bookmarks.lines() == [3]
    editor.goto_line(1)
    entry["Next Bookmark"].trigger()
    assert editor.caret_line_col() == (3, 1)
    entry["Clear All Bookmarks"].trigger()
    assert editor.bookmarks.lines() == []
    entry["Convert Tabs"].trigger()
    spaces = " " * editor.settings.tab_size
    assert editor.toPlainText() == f"a\n{spaces}b\nc\n{spaces}d\n"
    entry["Find..."].trigger()
    assert editor.search.find_dialog is not None and editor.search.find_dialog.isVisible()


def test_sample_syntax_check_and_error_at_the_right_line(window, qtbot):
    """DG 2479-2483: F4 test-compiles; on an error the message names the line and the caret goes there."""
    editor = window.open_sample("01_positioning.m")
    qtbot.keyClick(editor, Qt.Key.Key_F4)
    assert "Syntax check: no errors" in window.messages.toPlainText()
    editor.goto_line(5, col=1)
    editor.insertPlainText("POSA\n")
    assert window.development.syntax_check() is False
    text = window.messages.toPlainText()
    assert ":5:1: error: POSA needs more arguments" in text
    assert editor.caret_line_col()[0] == 5
    window.live_check()  # runs off the GUI thread (tests/ui/test_live_check.py)
    qtbot.waitUntil(lambda: any(d[0] == 5 and d[2] == "error" for d in editor.diagnostics()), timeout=10_000)


def test_execute_prints_in_the_messages_window_and_esc_breaks(window, qtbot):
    """DG 2380-2418: F5 compiles, downloads and starts; PRINT output appears prefixed with the controller
    ID; Esc stops the program and the axis decelerates."""
    editor = window.new_file()
    editor.setPlainText('PRINT "start"\nVEL 100\nACC 100\nDEC 100\nmain:\nPOSA 400000\nPOSA 0\nGOTO main\n')
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    qtbot.waitUntil(lambda: "[01] start" in window.messages.toPlainText(), timeout=5000)
    qtbot.waitUntil(lambda: window.bridge.last_status is not None
                    and window.bridge.last_status.program_state == "running", timeout=5000)
    window.actions_by_text["Break"].trigger()
    qtbot.waitUntil(lambda: window.bridge.link.status().program_state == "break", timeout=5000)
    qtbot.waitUntil(lambda: window.bridge.link.status().axend & 1, timeout=10000)  # decelerated to standstill
    # the status bar and messages follow through queued events: wait for them rather than race them
    qtbot.waitUntil(lambda: "stopped" in window.controller_label.text()
                    or "break" in window.messages.toPlainText(), timeout=5000)


def test_command_list_inserts_the_preview(window, qtbot):
    """DG 2554-2607: POSA with position 3000 and a comment previews as `POSA 3000  // …` and is inserted."""
    from motiontool.ui.command_list import CommandListDialog

    editor = window.new_file()
    dialog = CommandListDialog(window)
    qtbot.addWidget(dialog)
    dialog.insert_requested.connect(editor.insertPlainText)
    dialog.select_command("POSA")
    dialog.fields[0].setText("3000")
    dialog.comment.setText("Move to position 3000")
    assert dialog.preview.text() == "POSA 3000  // Move to position 3000"
    dialog.insert_button.click()
    assert editor.toPlainText() == "POSA 3000  // Move to position 3000"


def test_recent_files(window, tmp_path):
    """Crash recovery: tests/ui/test_recovery.py (a crash needs a second process)."""
    program = tmp_path / "r.m"
    program.write_text("x = 1\n")
    window.open_file(program)
    assert window.recent_files()[0] == str(program.resolve())


def test_screenshot_command_writes_png(tmp_path):
    """`motiontool --screenshot PATH --open FILE` paints the window, writes a PNG and exits 0."""
    out = tmp_path / "window.png"
    proc = subprocess.run([sys.executable, "-m", "motiontool", "--screenshot", str(out), "--open",
                           "resources/samples/01_positioning.m"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert out.stat().st_size > 5000


def test_without_display_the_gui_explains_what_to_do(tmp_path):
    """`make run` without a display: a clear message and the headless alternatives, exit 1."""
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}
    proc = subprocess.run([sys.executable, "-m", "motiontool"], capture_output=True, text=True,
                          timeout=60, env=env)
    assert proc.returncode == 1
    assert "no display" in proc.stderr and "offscreen" in proc.stderr and "check" in proc.stderr


def test_open_last_file_option_and_editor_settings(window, tmp_path, qtbot):
    """DG 3156-3230: Options → Open last file; DG 3117-3150: editor tab size and colours persist."""
    program = tmp_path / "last.m"
    program.write_text("x = 1\n")
    window.open_file(program)
    window.actions_by_text["Open last file"].setChecked(True)
    from motiontool.ui.editor.settings import EditorSettings

    window.set_editor_settings(EditorSettings(tab_size=2))
    again = MainWindow(settings=window.settings)
    again.ask_to_save = False
    qtbot.addWidget(again)
    editor = again.open_last_file()
    assert editor is not None and editor.toPlainText() == "x = 1\n"
    assert again.editor_settings().tab_size == 2


def test_run_in_several_controllers_and_break_all(window, qtbot):
    """DG 2393-2404, 2504-2518: Execute on controller 1, Select Controller 2 (1 keeps running), Execute
    again; Break all stops both; messages carry the controller ID."""
    editor = window.new_file()
    editor.setPlainText('PRINT "go"\nmain:\nDELAY 10\nGOTO main\n')
    assert window.development.execute(ask=False)
    assert window.development.select_controller(2)
    assert window.development.execute(ask=False)
    qtbot.waitUntil(lambda: "[02] go" in window.messages.toPlainText(), timeout=5000)
    links = dict(window.controllers.open_links())
    assert {links[1].status().program_state, links[2].status().program_state} == {"running"}
    window.development.break_all()
    assert {links[1].status().program_state, links[2].status().program_state} == {"break"}
    assert "[01] go" in window.messages.toPlainText()


def test_outline_lists_subprograms_and_jumps_or_says_it_is_empty(window, qtbot):
    """The outline pane lists the program's subprograms (DG 6086: SUBPROG name … RETURN); a click on one moves
    the caret there. A program without any says so instead of showing a blank pane."""
    editor = window.open_sample("07_heartbeat.m")
    window.live_check()
    items = [window.outline.item(i) for i in range(window.outline.count())]
    names = [item.text() for item in items]
    assert "subprog: beat  (46)" in names and "subprog: stop_beat  (52)" in names
    window.outline.itemClicked.emit(items[names.index("subprog: stop_beat  (52)")])
    assert editor.caret_line_col()[0] == 52
    window.open_sample("01_positioning.m")
    window.live_check()
    assert window.outline.count() == 1
    hint = window.outline.item(0)
    assert hint.text().startswith("No labels") and not hint.flags() & Qt.ItemFlag.ItemIsEnabled
    window.outline.itemClicked.emit(hint)  # nothing to jump to: no error
