"""The CAM editor's Qt user interface (CamEditor window).  Tools → CAM-Editor calls open_cam_editor."""

from __future__ import annotations

from PySide6.QtCore import QEventLoop, Qt
from PySide6.QtWidgets import QApplication


def open_cam_editor(main_window):
    """Open a CAM-Editor window for ``main_window`` [DG L3513-3519]; Read/Write to controller use the main
    window's current link (``main_window.bridge.link``).  One editor per main window: a second call raises it."""
    editor = getattr(main_window, "cam_editor", None)
    if editor is None:
        # the first opening imports the curve maths and builds four panes (0.3-2 s): show that the IDE is busy
        QApplication.setOverrideCursor(Qt.CursorShape.WaitCursor)
        QApplication.processEvents(QEventLoop.ProcessEventsFlag.ExcludeUserInputEvents)  # the cursor, now
        try:
            from motiontool.cameditor.ui.window import CamEditor

            editor = CamEditor(link_provider=lambda: main_window.bridge.link, parent=main_window,
                               controller=lambda: getattr(main_window.bridge, "controller_id", None),
                               wait=main_window.bridge.waiting)
            editor.setWindowFlag(Qt.WindowType.Window, True)
            editor.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose, True)
            editor.destroyed.connect(lambda *_: setattr(main_window, "cam_editor", None))
            main_window.cam_editor = editor
        finally:
            QApplication.restoreOverrideCursor()
    editor.show()
    editor.raise_()
    editor.activateWindow()
    return editor
