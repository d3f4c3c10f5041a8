"""The CAM editor's Qt user interface (CamEditor window).  Tools → CAM-Editor calls open_cam_editor."""

from __future__ import annotations

from PySide6.QtCore import Qt


def open_cam_editor(main_window):
    """Open a CAM-Editor window for ``main_window`` [DG L3513-3519]; Read/Write to controller use the main
    window's current link (``main_window.bridge.link``).  One editor per main window: a second call raises it."""
    from motiontool.cameditor.ui.window import CamEditor

    editor = getattr(main_window, "cam_editor", None)
    if editor is None:
        editor = CamEditor(link_provider=lambda: main_window.bridge.link, parent=main_window)
        editor.setWindowFlag(Qt.WindowType.Window, True)
        editor.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose, True)
        editor.destroyed.connect(lambda *_: setattr(main_window, "cam_editor", None))
        main_window.cam_editor = editor
    editor.show()
    editor.raise_()
    editor.activateWindow()
    return editor
