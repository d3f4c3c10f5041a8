"""Window menu (DG 3240-3250, ide-spec 1.49): Cascade, Tile vertically, Tile horizontally and the list of open
windows with their controller binding ("1 print3.m [Controller: 1 …]").

The manual's APOSS is one frame with child windows; here each program is a tab of an APOSS window and the
CAM-Editor, oscilloscopes and Array Editor are windows of their own. Cascade and Tile arrange all of them —
every APOSS window and every tool window — on the screen; the list names each program tab and tool window, and
choosing one brings it to the front (decision I15)."""

from __future__ import annotations

from PySide6.QtWidgets import QMainWindow, QMenu, QWidget

MARGIN = 30   # cascade step, pixels


def ide_windows(w) -> list[QWidget]:
    """The visible top-level windows of this IDE session: APOSS windows first, then their tool windows."""
    apos = [x for x in getattr(w.controllers, "windows", [w]) if x.isVisible()] or [w]
    tools = []
    for main in apos:
        for child in main.findChildren(QMainWindow):
            if child.isWindow() and child.isVisible() and child not in tools:
                tools.append(child)
    return apos + tools


def _area(w):
    screen = w.screen() or w.window().screen()
    return screen.availableGeometry()


def cascade(w) -> list[QWidget]:
    windows = ide_windows(w)
    area = _area(w)
    width, height = int(area.width() * 0.7), int(area.height() * 0.7)
    for k, window in enumerate(windows):
        window.showNormal()
        offset = MARGIN * (k % 10)
        window.setGeometry(area.x() + offset, area.y() + offset, width, height)
        window.raise_()
    return windows


def tile(w, *, vertically: bool) -> list[QWidget]:
    """Tile vertically: side by side (each the full height); horizontally: one above the other."""
    windows = ide_windows(w)
    area = _area(w)
    n = max(1, len(windows))
    for k, window in enumerate(windows):
        window.showNormal()
        if vertically:
            step = area.width() // n
            window.setGeometry(area.x() + k * step, area.y(), step, area.height())
        else:
            step = area.height() // n
            window.setGeometry(area.x(), area.y() + k * step, area.width(), step)
    return windows


def window_entries(w) -> list[tuple[str, object]]:
    """(label, thing to bring to the front) for every program tab and tool window."""
    entries = []
    apos = [x for x in getattr(w.controllers, "windows", [w]) if x.isVisible()] or [w]
    for main in apos:
        binding = main.connection.title_suffix(error=False) if hasattr(main, "connection") else ""
        for editor in main.editors():
            tab = main.tabs.tabText(main.tabs.indexOf(editor))
            entries.append((f"{tab}{binding}", (main, editor)))
    for window in ide_windows(w)[len(apos):]:
        entries.append((window.windowTitle(), (window, None)))
    return entries


def bring_to_front(target) -> None:
    window, editor = target
    if editor is not None:
        window.tabs.setCurrentWidget(editor)
        editor.setFocus()
    window.showNormal()
    window.raise_()
    window.activateWindow()


def fill(w, menu: QMenu, fixed: int) -> None:
    """Rebuild the list part of the Window menu (the entries after the first `fixed` ones)."""
    for action in menu.actions()[fixed:]:
        menu.removeAction(action)
    entries = window_entries(w)
    if entries:
        menu.addSeparator()
    for number, (text, target) in enumerate(entries, 1):
        action = menu.addAction(f"&{number} {text}" if number < 10 else text)
        action.triggered.connect(lambda *_, t=target: bring_to_front(t))
