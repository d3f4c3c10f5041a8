"""Tools menu (DG L3513-3519 CAM-Editor, L5265-5273 Oscilloscope): each entry opens its window on the
APOSS window's controller."""

from motiontool.cameditor.ui.window import CamEditor
from motiontool.scope.ui.window import ScopeWindow


def test_tools_cam_editor_opens_once_and_uses_the_windows_link(window):
    window.actions_by_text["CAM-Editor"].trigger()
    editor = window.cam_editor
    assert isinstance(editor, CamEditor) and editor.isVisible()
    window.actions_by_text["CAM-Editor"].trigger()  # a second call raises the same editor
    assert window.cam_editor is editor
    editor.close()


def test_tools_oscilloscope_connects_the_default_controller(window):
    window.actions_by_text["Oscilloscope"].trigger()
    scopes = window._scopes
    assert len(scopes) == 1 and isinstance(scopes[0], ScopeWindow) and scopes[0].isVisible()
    assert window.bridge.connected
    for scope in scopes:
        scope.close()
