"""Tools ▸ CAM-Editor from the IDE (issue 23 item 10): the first opening shows a busy cursor while it imports
the curve maths and builds its panes, and the toolbar's Read / Write buttons say which way and which controller
("Read from controller", "Write to controller" as DG 3524, 3579 name them) instead of two bare arrows that were
reversed from the download convention (down = to the controller)."""

from __future__ import annotations

from PySide6.QtCore import QRect, Qt, QTimer
from PySide6.QtWidgets import QApplication, QMessageBox, QStyle, QToolButton

from tests.modal import answering, button_reply
from tests.shots import shot_path


def _same_icon(icon, pixmap: QStyle.StandardPixmap) -> bool:
    standard = QApplication.style().standardIcon(pixmap)
    return icon.pixmap(16, 16).toImage() == standard.pixmap(16, 16).toImage()


def test_the_cam_editor_opens_with_a_busy_cursor_and_named_read_write_buttons(window, qtbot):
    window.development.connect_default()  # as the IDE does at start (ui/app.py)
    seen: list[object] = []

    def look() -> None:  # runs while the editor is being built, as the user looks at the screen
        cursor = QApplication.overrideCursor()
        seen.append(cursor.shape() if cursor is not None else None)

    QTimer.singleShot(0, look)
    window.actions_by_text["CAM-Editor"].trigger()
    editor = window.cam_editor
    qtbot.waitExposed(editor)
    assert seen == [Qt.CursorShape.WaitCursor]
    assert QApplication.overrideCursor() is None  # and it is back once the window is there

    buttons = {b.defaultAction(): b for b in editor.findChildren(QToolButton) if b.defaultAction() is not None}
    read, write = buttons[editor.actions_by_name["read"]], buttons[editor.actions_by_name["write"]]
    assert (read.text(), write.text()) == ("Read from controller 1", "Write to controller 1")
    assert read.toolButtonStyle() == write.toolButtonStyle() == Qt.ToolButtonStyle.ToolButtonTextBesideIcon
    assert _same_icon(write.icon(), QStyle.StandardPixmap.SP_ArrowDown)  # down to the controller, as a download
    assert _same_icon(read.icon(), QStyle.StandardPixmap.SP_ArrowUp)
    assert read.isVisible() and write.isVisible() and write.x() > read.x()

    bar = read.parentWidget()  # the toolbars' two rows
    editor.grab(QRect(0, 0, editor.width(), bar.geometry().bottom() + 1)).save(
        str(shot_path("cam_editor_buttons.png")))

    with answering(qtbot, button_reply(QMessageBox.StandardButton.Yes)) as answers:  # the buttons work
        qtbot.mouseClick(write, Qt.MouseButton.LeftButton)
    assert answers.seen == ["QMessageBox 'CAM-Editor'"]
    assert editor.message_line.text() == "Parameters and arrays written to the controller"
    qtbot.mouseClick(read, Qt.MouseButton.LeftButton)
    assert "failed" not in editor.message_line.text()
    editor.modified = False
    editor.close()


def test_the_ide_imports_the_curve_maths_off_the_gui_thread_and_nothing_qt():
    """The first opening waited 1.9-2.3 s, most of it importing scipy; the IDE now imports the curve maths on a
    worker thread after it starts (ui/app.py), and only Qt-free modules there."""
    import subprocess
    import sys

    script = ("import sys, threading\n"
              "from motiontool.ui.app import _preload_curve_maths\n"
              "before = set(sys.modules)\n"
              "_preload_curve_maths()\n"
              "[t.join() for t in threading.enumerate() if t.name == 'preload curve maths']\n"
              "new = set(sys.modules) - before\n"
              "print('motiontool.camcurve.layout' in new, 'motiontool.cameditor.apcconvert' in new,"
              " sorted(m for m in new if m.startswith(('PySide6', 'shiboken6', 'pyqtgraph'))))\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.stdout.split("\n")[0] == "True True []", done.stdout + done.stderr
