"""The Curve Selection List's context menu (DG 4850-4876): properties, axis side and sharing, reload,
delete, Display ALL as Value, Show/Hide ALL. Functions of the ScopeWindow they act on."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QMenu

from motiontool.scope.ui.curve_list import NAME
from motiontool.scope.ui.testsetp_load import reload_recording


def show_list_menu(self, pos) -> None:
    """Right-click on a Name (DG 4850-4876); `self` is the ScopeWindow."""
    item = self.list.itemAt(pos)
    name = item.data(NAME, Qt.UserRole) if item is not None else None
    menu = QMenu(self)
    if name:
        title = menu.addAction(name)
        title.setEnabled(False)
        menu.addAction("Properties…", lambda: self.edit_properties(name))
        menu.addAction("Left axis", lambda: _set_side(self, name, "left"))
        menu.addAction("Right axis", lambda: _set_side(self, name, "right"))
        menu.addAction("Share the left axis", lambda: _share(self, name))
        reload_action = menu.addAction("Reload & Redisplay", lambda: reload_recording(self, name))
        reload_action.setEnabled(self.scope.curve(name).source.method == "testsetp" and self.link is not None)
        menu.addAction("Delete", lambda: _delete(self, name))
    menu.addAction("Display ALL as Value", lambda: _all_values(self))
    menu.addAction("Show ALL", lambda: _show_all(self, True))
    menu.addAction("Hide ALL", lambda: _show_all(self, False))
    menu.popup(self.list.viewport().mapToGlobal(pos))


def _set_side(self, name: str, side: str) -> None:
    setattr(self.chart, f"{side}_curve", name)
    self.redraw()


def _share(self, name: str) -> None:
    if self.chart.left_curve and self.chart.left_curve != name:
        self.scope.curve(name).axis.share = self.chart.left_curve
        self.zoom_reset()


def _delete(self, name: str) -> None:
    self.scope.remove_curve(name)
    self.list.rebuild()
    self.redraw()


def _all_values(self) -> None:
    for c in self.scope.curves:
        c.interpolation = "values"
    self.redraw()


def _show_all(self, on: bool) -> None:
    for c in self.scope.curves:
        c.visible = on
    self.list.rebuild()
    self.redraw()
