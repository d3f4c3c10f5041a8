"""Settings ▸ Compiler / Language, the Window menu, Help (F1, Index, F11), the toolbar, File ▸ Save, the
controller's messages, and no greyed-out menu entry (issue 16 items 3 and 2; requests from dpl and kernel).
Everything is fired as a user fires it: menu actions, keys, toolbar clicks, dialogs answered."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QTextCursor
from PySide6.QtWidgets import QCheckBox, QMainWindow, QMenu, QToolBar, QToolButton

from motiontool.ui.compiler_settings import NO_XREF, CompilerSettings, CompilerSettingsDialog
from motiontool.ui.language import SETTING, LanguageDialog
from tests.modal import answering, file_reply, ok_reply


def click(qtbot, widget) -> None:
    qtbot.mouseClick(widget, Qt.MouseButton.LeftButton)


def tick(qtbot, box: QCheckBox) -> None:
    """Click a check box on its indicator (a box stretched by its layout does not take clicks at its centre)."""
    qtbot.mouseClick(box, Qt.MouseButton.LeftButton, pos=QPoint(6, box.height() // 2))


def back_to(qtbot, window) -> None:
    """After a modal dialog the window manager gives the focus back to the window (offscreen does not): keys
    and shortcuts go to it again."""
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow, timeout=2000)


def saved_program(window, tmp_path, text: str, name: str = "prog.m"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return window.open_file(path), path


# --- Settings ▸ Compiler ----------------------------------------------------------------------------------------
def test_compiler_options_cross_reference_off_no_ad_file_and_the_debugger_says_why(window, qtbot, tmp_path):
    """DG 3057-3085: "Generate Cross Reference … needed by the Watch and the debugger"."""
    editor, path = saved_program(window, tmp_path, "x = 1\nPRINT x\n")

    def options(dialog):
        assert isinstance(dialog, CompilerSettingsDialog)
        tick(qtbot, dialog.cross_reference)
        spin = dialog.stack_size
        spin.selectAll()
        qtbot.keyClicks(spin, "300")

    with answering(qtbot, ok_reply(options)):
        window.actions_by_text["Compiler..."].trigger()
    back_to(qtbot, window)
    saved = CompilerSettings.load(window.settings)
    assert not saved.cross_reference and saved.stack_size == 300
    qtbot.keyClick(editor, Qt.Key.Key_F4)
    assert "Syntax check: no errors" in window.messages.toPlainText()
    assert not path.with_suffix(".ad$").exists()
    window.actions_by_text["Prepare Singlestep"].trigger()
    assert NO_XREF in window.messages.toPlainText()


def test_compiler_options_preprocessor_off_refuses_a_directive_at_its_line(window, qtbot, tmp_path):
    editor, _path = saved_program(window, tmp_path, "x = 1\n#define LIMIT 5\nPRINT x\n")

    def options(dialog):
        tick(qtbot, dialog.preprocessor)

    with answering(qtbot, ok_reply(options)):
        window.actions_by_text["Compiler..."].trigger()
    back_to(qtbot, window)
    qtbot.keyClick(editor, Qt.Key.Key_F4)
    text = window.messages.toPlainText()
    assert "Syntax check: 1 error(s)" in text
    assert "prog.m:2:1" in text and "#define: the preprocessor is switched off" in text


def test_compiler_options_max_variables_refuses_a_larger_program(window, qtbot, tmp_path):
    editor, _path = saved_program(window, tmp_path, "a = 1\nb = 2\nc = 3\nPRINT a + b + c\n")

    def options(dialog):
        dialog.max_variables.selectAll()
        qtbot.keyClicks(dialog.max_variables, "2")

    with answering(qtbot, ok_reply(options)):
        window.actions_by_text["Compiler..."].trigger()
    back_to(qtbot, window)
    qtbot.keyClick(editor, Qt.Key.Key_F4)
    assert "the program has 3 variables (arrays count as one); Settings → Compiler allows 2" \
        in window.messages.toPlainText()


# --- Settings ▸ Language ----------------------------------------------------------------------------------------
def test_language_is_kept_for_the_next_start(window, qtbot):
    """DG 3113-3115: the chosen language takes effect after a restart."""
    def choose(dialog):
        assert isinstance(dialog, LanguageDialog)
        combo = dialog.choice
        combo.setFocus()
        qtbot.keyClick(combo, Qt.Key.Key_End)     # keys as a user chooses in a closed combo box
        for _ in range(combo.count()):
            if combo.currentData() == "de":
                break
            qtbot.keyClick(combo, Qt.Key.Key_Up)

    with answering(qtbot, ok_reply(choose)):
        window.actions_by_text["Language..."].trigger()
    assert window.settings.value(SETTING) == "de"
    assert "takes effect when motiontool starts again" in window.messages.toPlainText()


# --- Window menu --------------------------------------------------------------------------------------------------
def open_menu(qtbot, window, title: str) -> QMenu:
    bar = window.menuBar()
    action = next(a for a in bar.actions() if a.text().replace("&", "") == title)
    click_at = bar.actionGeometry(action).center()
    qtbot.mouseClick(bar, Qt.MouseButton.LeftButton, pos=click_at)
    qtbot.waitUntil(action.menu().isVisible, timeout=2000)
    return action.menu()


def test_window_menu_tiles_the_windows_and_lists_them_to_bring_one_to_the_front(window, qtbot):
    """DG 3240-3250: Cascade, Tile and the list of open windows with their controller binding."""
    assert window.development.connect_default()
    first = window.new_file()
    second = window.new_file()
    window.actions_by_text["CAM-Editor"].trigger()
    cam = next(w for w in window.findChildren(QMainWindow) if w.isWindow() and w.isVisible())
    window.actions_by_text["Tile vertically"].trigger()
    qtbot.wait(50)
    assert cam.frameGeometry().left() > window.frameGeometry().left()
    window.actions_by_text["Tile horizontally"].trigger()
    qtbot.wait(50)
    assert cam.geometry().top() > window.geometry().top()
    window.actions_by_text["Cascade"].trigger()
    assert window.current_editor() is second
    menu = open_menu(qtbot, window, "Window")
    labels = [a.text() for a in menu.actions() if not a.isSeparator()]
    first_label = window.tabs.tabText(window.tabs.indexOf(first))
    entry = next(a for a in menu.actions() if first_label in a.text())
    assert any(cam.windowTitle() in label for label in labels) and "[Controller:" in entry.text()
    rect = menu.actionGeometry(entry)
    qtbot.mouseClick(menu, Qt.MouseButton.LeftButton, pos=rect.center())
    assert window.current_editor() is first
    cam.close()


# --- Help -----------------------------------------------------------------------------------------------------------
def test_f1_shows_the_command_under_the_caret_index_searches_and_f11_the_sdo_dictionary(window, qtbot):
    """DG 2043-2049: context help for the command at the caret; the index; F11 the SDO dictionary."""
    editor = window.new_file()
    editor.setPlainText("VEL 50\nPOSA 1000\n")
    cursor = editor.textCursor()
    cursor.movePosition(QTextCursor.MoveOperation.Down)
    cursor.movePosition(QTextCursor.MoveOperation.Right, n=2)
    editor.setTextCursor(cursor)
    editor.setFocus()
    qtbot.keyClick(editor, Qt.Key.Key_F1)
    help_window = window.help_window
    qtbot.waitUntil(help_window.isVisible, timeout=2000)
    assert help_window.index.currentItem().text() == "POSA (command)"
    assert "POSA" in help_window.page.toPlainText()
    window.actions_by_text["Index"].trigger()
    qtbot.keyClicks(help_window.search, "kprop")
    shown = [help_window.index.item(i).text() for i in range(help_window.index.count())
             if not help_window.index.item(i).isHidden()]
    assert shown == ["32-60 KPROP (parameter)"]
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow, timeout=2000)
    qtbot.keyClick(editor, Qt.Key.Key_F11)
    assert "SDO Dictionary" in help_window.page.toPlainText() and "0x2500" in help_window.page.toPlainText()
    help_window.close()


# --- toolbar, menus -------------------------------------------------------------------------------------------------
def test_the_toolbar_runs_the_menus_actions(window, qtbot):
    """DG 2013: a toolbar with the common commands; its Execute runs the program like F5."""
    bar = window.findChild(QToolBar, "aposs-toolbar")
    texts = [a.text().replace("&", "") for a in bar.actions() if not a.isSeparator()]
    assert {"New", "Open...", "Save", "Execute", "Break", "Syntax Check", "Oscilloscope",
            "Select Controller..."} <= set(texts)
    editor = window.new_file()
    editor.setPlainText('PRINT "from the toolbar"\n')
    execute = next(b for b in bar.findChildren(QToolButton) if b.defaultAction() is window.actions_by_text["Execute"])
    click(qtbot, execute)
    qtbot.waitUntil(lambda: "from the toolbar" in window.messages.toPlainText(), timeout=10000)


def test_no_menu_entry_is_greyed_out_for_want_of_code(window):
    """Issue 16 item 3: every entry of every menu does something; only Stop logging and Update Log file wait
    for a log file to be chosen (DG 2420-2426)."""
    def entries(menu: QMenu, path: str):
        for action in menu.actions():
            if action.isSeparator():
                continue
            if action.menu() is not None:
                yield from entries(action.menu(), f"{path} ▸ {action.text()}")
            else:
                yield f"{path} ▸ {action.text()}", action

    disabled = [label for top in window.menuBar().actions() for label, action in entries(top.menu(), top.text())
                if not action.isEnabled()]
    assert disabled == ["&Development ▸ Messages ▸ Stop logging", "&Development ▸ Messages ▸ Update Log file"]


# --- File ▸ Save (request from dpl: save_bookmarks took `path` keyword-only and every Save raised) ------------------
def test_file_save_writes_the_program_first_through_save_as_then_to_its_path(window, qtbot, tmp_path):
    editor = window.new_file()
    qtbot.keyClicks(editor, "x = 1")
    target = tmp_path / "saved.m"
    with answering(qtbot, file_reply(target)):
        window.actions_by_text["Save"].trigger()
    back_to(qtbot, window)
    assert target.read_text(encoding="utf-8") == "x = 1"
    assert not editor.document().isModified()
    qtbot.keyClick(editor, Qt.Key.Key_End)
    qtbot.keyClicks(editor, "0")
    qtbot.keyClick(editor, Qt.Key.Key_S, Qt.KeyboardModifier.ControlModifier)
    assert target.read_text(encoding="utf-8") == "x = 10"
    assert Path(editor.property("path")) == target.resolve()


# --- the controller's messages (request from kernel) ----------------------------------------------------------------
def test_the_controllers_messages_show_in_the_communication_window(window, qtbot):
    """K11: after MOTOR OFF a POSA waits; the controller says why, and the Communication window shows it."""
    editor = window.new_file()
    editor.setPlainText("MOTOR OFF\nPOSA 1000\n")
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    qtbot.waitUntil(lambda: "POSA waits: the position control is off" in window.messages.toPlainText(),
                    timeout=10000)
    line = next(t for t in window.messages.toPlainText().splitlines() if "POSA waits" in t)
    assert "1" in line.split("POSA")[0]   # the controller's ID precedes the text


def test_the_chosen_language_translates_qts_texts_at_the_next_start(qapp, tmp_path):
    """The language is installed when motiontool starts: Qt's own texts (here a standard button) are German."""
    from PySide6.QtCore import QCoreApplication, QSettings

    from motiontool.ui.language import install

    settings = QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat)
    settings.setValue(SETTING, "de")
    translator = install(qapp, settings)
    try:
        assert translator is not None
        assert QCoreApplication.translate("QPlatformTheme", "Cancel") == "Abbrechen"
    finally:
        qapp.removeTranslator(translator)
