"""The IDE's session without Qt (issue 27 item 5): the interfaces and controllers it can reach and which one a
window is connected to, with plain-Python events; the Qt windows in `ui/` are its adapters (decision I35)."""
