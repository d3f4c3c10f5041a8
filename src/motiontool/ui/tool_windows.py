"""The tool windows of an APOSS window (Tools ▸ CAM-Editor, Oscilloscope, Array Editor; a .cam, .zbo or .zba
opened): each is given the window's session as its bridge (ui/bridge.py: link, controller ID, signals, waiting,
connect_default, prompts), never the main window, which only parents and keeps them: one CAM editor and one
Array Editor per APOSS window, any number of oscilloscopes."""

from __future__ import annotations

from PySide6.QtWidgets import QWidget


def cam_editor(w) -> QWidget:
    """Tools ▸ CAM-Editor [DG L3513-3519]: a second call raises the window's editor."""
    from motiontool.cameditor.ui import open_cam_editor

    editor = getattr(w, "cam_editor", None)
    if editor is None:
        editor = open_cam_editor(w.bridge, parent=w)
        editor.destroyed.connect(lambda *_: setattr(w, "cam_editor", None))
        w.cam_editor = editor
    editor.show()
    editor.raise_()
    editor.activateWindow()
    return editor


def oscilloscope(w, variant: str = "free_run") -> QWidget:
    """Tools ▸ Oscilloscope (DG 5265-5273): a new one on the window's controller."""
    from motiontool.scope.ui import open_scope

    return keep_scope(w, open_scope(w.bridge, variant, parent=w, settings=w.settings))


def keep_scope(w, window: QWidget) -> QWidget:
    w._scopes = [s for s in getattr(w, "_scopes", []) if s.isVisible()] + [window]
    return window


def array_editor(w) -> QWidget:
    """Tools ▸ Array Editor (ide-spec 5.5): the window's editor, reading its controller at once."""
    from motiontool.arrayeditor.ui.editor import open_array_editor

    editor = getattr(w, "_array_editor", None)
    if editor is None:
        editor = w._array_editor = open_array_editor(w.bridge, parent=w)
    editor.show()
    editor.raise_()
    if w.bridge.connect_default():
        editor.read_controller()
    return editor
