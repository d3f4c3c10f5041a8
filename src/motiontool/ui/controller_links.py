"""The controllers of a window's interface and their links, for the dialogs that act on one controller at a time
(Parameters ▸ Global / Axis / Name / Drive, Download all)."""

from __future__ import annotations


def interface_controllers(w) -> list[int]:
    """The controller IDs of the window's interface."""
    iface = w.controllers.interface(key=w.connection.interface_key)
    return list(iface.found) or [w.bridge.controller_id]


def controller_link(w, controller_id: int):
    return w.controllers.link(controller_id, interface=w.connection.interface_key)
