"""The main window opens with the APOSS menu bar and can be captured headless."""

import subprocess
import sys

from motiontool.ui.main_window import MainWindow

APOSS_MENUS = ["File", "Edit", "Development", "Controller", "Tools", "Settings", "Window", "Help"]


def test_menu_bar_has_the_aposs_menus(qtbot):
    """ide-spec 1.26-1.50: File/Edit/Development/Controller/Tools/Settings/Window/Help."""
    window = MainWindow()
    qtbot.addWidget(window)
    titles = [a.text().replace("&", "") for a in window.menuBar().actions()]
    assert titles == APOSS_MENUS


def test_manual_shortcuts_are_bound(qtbot):
    """DG 2380-2391 / ide-spec 2.4, 1.39: Execute is F5, Syntax Check is F4, Command List is F12."""
    window = MainWindow()
    qtbot.addWidget(window)
    shortcuts = {name: window.actions_by_text[name].shortcut().toString()
                 for name in ("Execute", "Syntax Check", "Command List...", "Singlestep")}
    assert shortcuts == {"Execute": "F5", "Syntax Check": "F4", "Command List...": "F12", "Singlestep": "F9"}


def test_open_file_shows_text_and_cursor_position(qtbot, tmp_path):
    """ide-spec 1.5: the status bar shows line:column."""
    program = tmp_path / "hello.m"
    program.write_text("DIM a[2]\nPRINT \"hello\"\n", encoding="utf-8")
    window = MainWindow()
    qtbot.addWidget(window)
    editor = window.open_file(program)
    assert editor.toPlainText().startswith("DIM a[2]")
    assert window.tabs.tabText(window.tabs.currentIndex()) == "hello.m"
    cursor = editor.textCursor()
    cursor.movePosition(cursor.MoveOperation.Down)
    cursor.movePosition(cursor.MoveOperation.Right)
    editor.setTextCursor(cursor)
    assert window.cursor_label.text() == "2:2"


def test_screenshot_command_writes_png(tmp_path):
    """`motiontool --screenshot PATH` paints the window, writes a PNG and exits 0."""
    out = tmp_path / "window.png"
    proc = subprocess.run([sys.executable, "-m", "motiontool", "--screenshot", str(out)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert out.stat().st_size > 5000  # a real picture, not an empty image


def test_without_display_the_gui_explains_what_to_do(tmp_path):
    """`make run` without a display: a clear message and the headless alternatives, exit 1."""
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}
    proc = subprocess.run([sys.executable, "-m", "motiontool"], capture_output=True, text=True,
                          timeout=60, env=env)
    assert proc.returncode == 1
    assert "no display" in proc.stderr and "offscreen" in proc.stderr and "check" in proc.stderr
