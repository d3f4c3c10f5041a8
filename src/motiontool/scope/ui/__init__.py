"""The oscilloscope's Qt view (pyqtgraph, PySide6). `open_scope(bridge)` opens one on an APOSS window's session
(Tools → Oscilloscope, through ui/tool_windows.py); `open_scope_file(path)` opens a saved .zbo or an old Testrun
.txt."""

from __future__ import annotations

from PySide6.QtCore import Qt

from motiontool.scope.ui.window import ScopeWindow, open_scope_file

LIVE_KEY = "oscilloscope/live_window_s"

__all__ = ["ScopeWindow", "close_scopes", "open_scope", "open_scope_file"]


def open_scope(bridge, variant: str = "free_run", *, parent=None, settings=None) -> ScopeWindow:
    """Tools → Oscilloscope (DG 5265-5273): bind to the APOSS window's controller (`bridge`: its session's Qt
    face, ui/bridge.py), connecting the default controller first if there is none. `parent` keeps the window;
    `settings` keeps the live window's length between sessions."""
    bridge.connect_default()
    window = ScopeWindow(bridge, variant, parent=parent)
    if settings is not None:   # the live window is the user's setting, kept between sessions
        window.live_box.setValue(int(settings.value(LIVE_KEY, window.live_box.value(), type=int)))
        window.live_box.valueChanged.connect(lambda seconds: settings.setValue(LIVE_KEY, seconds))
    window.setWindowFlag(Qt.Window, True)  # a top-level window owned by its parent
    window.show()
    return window


def close_scopes(main_window) -> bool:
    """Close the main window's oscilloscopes before the IDE closes, each asking about an unsaved recording
    (Save / Discard / Cancel, issue 23 item 9); False when the user cancelled."""
    return all(window.close() for window in main_window.findChildren(ScopeWindow) if window.isVisible())
