"""File → Open in the APOSS window opens each file in the window that handles it (issue 16, 2d): a .zbc was
opened as program text before."""

import pytest

from motiontool.arrayeditor.ui.editor import ArrayEditor
from motiontool.cameditor.ui.window import CamEditor
from motiontool.scope.ui.window import ScopeWindow
from motiontool.ui.editor.code_editor import CodeEditor
from tests.modal import answering, file_reply
from tests.ui.sample_files import Files


def open_by_menu(window, qtbot, path):
    tabs = window.tabs.count()
    with answering(qtbot, file_reply(path)):
        window.actions_by_text["Open..."].trigger()
    return tabs


@pytest.mark.parametrize(("name", "kind"), [("walk.zbc", CamEditor), ("walk.zbo", ScopeWindow),
                                            ("walk.zba", ArrayEditor), ("walk.txt", ScopeWindow),
                                            ("notes.txt", CodeEditor), ("walk.m", CodeEditor)])
def test_file_open_puts_each_file_in_its_window(window, qtbot, tmp_path, name, kind):
    """DG 3483 (.zbc in the CAM-Editor), 5349-5376 (.zbo and old Testrun files in the oscilloscope), 4515
    (.zba in the Array Editor); a program or any other text in an edit tab."""
    Files(tmp_path)
    tabs = open_by_menu(window, qtbot, tmp_path / name)
    if kind is CodeEditor:
        assert window.tabs.count() == tabs + 1 and window.tabs.tabText(window.tabs.currentIndex()) == name
        return
    assert window.tabs.count() == tabs  # no program tab for it
    if kind is CamEditor:
        editor = window.cam_editor
        assert editor.isVisible() and editor.curve().name == "walk" and editor.path.name == name
        editor.close()
    elif kind is ScopeWindow:
        scope = window._scopes[-1]
        assert scope.isVisible() and scope.path.name == name and scope.link is None
        assert all(curve.raw()[0].size == 3 for curve in scope.scope.curves)
        scope.close()
    else:
        editor = window._array_editor
        assert editor.isVisible() and editor.path.name == name and editor.data_list.selections() == ["All", "User",
                                                                                                     "0"]
        editor.close()


def test_a_broken_file_is_reported_and_nothing_opens(window, qtbot, tmp_path):
    broken = tmp_path / "broken.zbo"
    broken.write_text("{not json", encoding="utf-8")
    from PySide6.QtWidgets import QMessageBox

    from tests.modal import button_reply

    with answering(qtbot, file_reply(broken), button_reply(QMessageBox.StandardButton.Ok)):
        window.actions_by_text["Open..."].trigger()
    assert "broken.zbo" in window.messages.toPlainText()
    assert not [s for s in getattr(window, "_scopes", []) if s.isVisible()]
