"""The Communication pane (ide-spec 1.2, 1.43): IDE messages and the controller's PRINT output, each
controller line prefixed with its ID ("[01] text"); optional log file with cached writes. A click or a
double-click on a message that names a program line (a compiler message `file:line:col: error: …`, a
controller error `[01] error 71: … (line 6)`) asks the window to show that line (DG 2479-2483, 2993).
Long lines wrap, so no message is hidden sideways; Ctrl+C copies the selection and a selection survives new
messages; the context menu adds Clear (decision I18)."""

from __future__ import annotations

import contextlib
import re
from pathlib import Path

from PySide6.QtCore import QEvent, Qt, Signal
from PySide6.QtGui import (
    QContextMenuEvent,
    QFontDatabase,
    QKeyEvent,
    QKeySequence,
    QMouseEvent,
    QTextCursor,
    QTextOption,
)
from PySide6.QtWidgets import QMenu, QPlainTextEdit, QWidget

MAX_LINES = 20_000  # keep the pane light during long runs; the log file keeps everything
COMPILER_MESSAGE = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<col>\d+): (?:error|warning|note):")
CONTROLLER_MESSAGE = re.compile(r"^\[(?P<cid>\d+)\] .*\(line (?P<line>\d+)\)\s*$")


def message_location(text: str) -> tuple[str, int, int, int | None] | None:
    """(file, line, column, controller ID) named by a message line, or None. A compiler message names its
    file; a controller error names the controller (file "")."""
    m = COMPILER_MESSAGE.match(text)
    if m:
        return m["file"], int(m["line"]), int(m["col"]), None
    m = CONTROLLER_MESSAGE.match(text)
    if m:
        return "", int(m["line"]), 1, int(m["cid"])
    return None


class MessagesPane(QPlainTextEdit):
    locationActivated = Signal(str, int, int, object)  # file ("" = the controller's program), line, column, ID

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.setReadOnly(True)
        self.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
        self.setMaximumBlockCount(MAX_LINES)
        # wrapped: with NoWrap one long line scrolled the view sideways and cut the start off every later one
        self.setLineWrapMode(QPlainTextEdit.LineWrapMode.WidgetWidth)
        self.setWordWrapMode(QTextOption.WrapMode.WrapAtWordBoundaryOrAnywhere)
        self._log = None
        self._pending: list[str] = []

    # --- a click on a message with a place ---------------------------------------------------------------
    def location_at(self, pos) -> tuple[str, int, int, int | None] | None:
        return message_location(self.cursorForPosition(pos).block().text())

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:  # noqa: N802 (Qt override)
        super().mouseReleaseEvent(event)
        if event.button() == Qt.MouseButton.LeftButton and not self.textCursor().hasSelection():
            self._activate(event)

    def mouseDoubleClickEvent(self, event: QMouseEvent) -> None:  # noqa: N802 (Qt override)
        super().mouseDoubleClickEvent(event)
        self._activate(event)

    def _activate(self, event: QMouseEvent) -> None:
        place = self.location_at(event.position().toPoint())
        if place is not None:
            self.locationActivated.emit(*place)

    # --- Ctrl+C, Select All and the context menu's Clear -------------------------------------------------
    def event(self, event: QEvent) -> bool:
        # the window's Edit ▸ Copy (Ctrl+C) copies from the program editor: in this pane the pane's own copy wins
        if (event.type() == QEvent.Type.ShortcutOverride and isinstance(event, QKeyEvent)
                and any(event.matches(k) for k in (QKeySequence.StandardKey.Copy, QKeySequence.StandardKey.SelectAll))):
            event.accept()
            return True
        return super().event(event)

    def keyPressEvent(self, event: QKeyEvent) -> None:  # noqa: N802 (Qt override)
        if event.matches(QKeySequence.StandardKey.Copy):
            self.copy()
        elif event.matches(QKeySequence.StandardKey.SelectAll):
            self.selectAll()
        else:
            super().keyPressEvent(event)

    def build_context_menu(self, pos) -> QMenu:
        """Qt's Copy / Select All, then Clear (the log file keeps what it has)."""
        menu = self.createStandardContextMenu(pos)
        menu.addSeparator()
        clear = menu.addAction("Clear")
        clear.setEnabled(not self.document().isEmpty())
        clear.triggered.connect(self.clear)
        return menu

    def contextMenuEvent(self, event: QContextMenuEvent) -> None:  # noqa: N802 (Qt override)
        menu = self.build_context_menu(event.pos())
        menu.exec(event.globalPos())
        menu.deleteLater()

    def ide(self, text: str) -> None:
        """A message of the IDE itself (compiler output, connection)."""
        self._append(text)

    def controller(self, controller_id: int, text: str) -> None:
        """A line from a controller (PRINT output, errors), prefixed with its ID."""
        self._append(f"[{controller_id:02d}] {text}")

    def controller_lines(self, controller_id: int, texts: list[str]) -> None:
        """Several lines of one controller in one append (a PRINT burst costs one layout, not one per line)."""
        if texts:
            self._append("\n".join(f"[{controller_id:02d}] {text}" for text in texts))

    def _append(self, line: str) -> None:
        selecting = self.textCursor().hasSelection()
        self.appendPlainText(line)
        if not selecting:  # follow the output, but never take away a selection the user is about to copy
            self.moveCursor(QTextCursor.MoveOperation.End)
        if self._log is not None:
            self._pending.append(line)
            if len(self._pending) >= 100 or "\n" in line:
                self.update_log()

    # --- Messages ▸ Log file / Stop logging / Update Log file --------------------------------------------
    @property
    def logging(self) -> bool:
        return self._log is not None

    def start_log(self, path: Path) -> None:
        self.stop_log()
        self._log = open(path, "a", encoding="utf-8")  # noqa: SIM115 - kept open while logging

    def update_log(self) -> None:
        if self._log is not None and self._pending:
            try:
                self._log.write("\n".join(self._pending) + "\n")
                self._log.flush()
            except OSError as exc:  # a full disk or a share gone: stop logging, say so, keep the pane going
                log, self._log = self._log, None
                with contextlib.suppress(OSError):
                    log.close()
                self._append(f"Log file stopped: cannot write {log.name}: {exc.strerror or exc}")
            self._pending.clear()

    def stop_log(self) -> None:
        if self._log is not None:
            self.update_log()
        if self._log is not None:
            with contextlib.suppress(OSError):
                self._log.close()
            self._log = None
