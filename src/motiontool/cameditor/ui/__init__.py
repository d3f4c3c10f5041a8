"""The CAM editor's Qt user interface (CamEditor window).  Tools → CAM-Editor calls open_cam_editor."""

from __future__ import annotations

from PySide6.QtCore import QEventLoop, Qt
from PySide6.QtWidgets import QApplication


def open_cam_editor(bridge, *, parent=None):
    """A CAM-Editor window [DG L3513-3519] whose Read/Write to controller use the controller of `bridge` (the
    APOSS window's session, ui/bridge.py): its current link and ID, its `waiting`. One per APOSS window is
    ui/tool_windows.py's rule."""
    # the first opening imports the curve maths and builds four panes (0.3-2 s): show that the IDE is busy
    QApplication.setOverrideCursor(Qt.CursorShape.WaitCursor)
    QApplication.processEvents(QEventLoop.ProcessEventsFlag.ExcludeUserInputEvents)  # the cursor, now
    try:
        from motiontool.cameditor.ui.window import CamEditor

        editor = CamEditor(link_provider=lambda: bridge.link, parent=parent,
                           controller=lambda: getattr(bridge, "controller_id", None), wait=bridge.waiting,
                           prompts=getattr(bridge, "prompts", None))
        editor.setWindowFlag(Qt.WindowType.Window, True)
        editor.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose, True)
    finally:
        QApplication.restoreOverrideCursor()
    return editor
