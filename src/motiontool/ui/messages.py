"""The Communication pane (ide-spec 1.2, 1.43): IDE messages and the controller's PRINT output, each
controller line prefixed with its ID ("[01] text"); optional log file with cached writes."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtGui import QFontDatabase, QTextCursor
from PySide6.QtWidgets import QPlainTextEdit, QWidget

MAX_LINES = 20_000  # keep the pane light during long runs; the log file keeps everything


class MessagesPane(QPlainTextEdit):
    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.setReadOnly(True)
        self.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
        self.setMaximumBlockCount(MAX_LINES)
        self.setLineWrapMode(QPlainTextEdit.LineWrapMode.NoWrap)
        self._log = None
        self._pending: list[str] = []

    def ide(self, text: str) -> None:
        """A message of the IDE itself (compiler output, connection)."""
        self._append(text)

    def controller(self, controller_id: int, text: str) -> None:
        """A line from a controller (PRINT output, errors), prefixed with its ID."""
        self._append(f"[{controller_id:02d}] {text}")

    def _append(self, line: str) -> None:
        self.appendPlainText(line)
        self.moveCursor(QTextCursor.MoveOperation.End)
        if self._log is not None:
            self._pending.append(line)
            if len(self._pending) >= 100:
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
            self._log.write("\n".join(self._pending) + "\n")
            self._log.flush()
            self._pending.clear()

    def stop_log(self) -> None:
        if self._log is not None:
            self.update_log()
            self._log.close()
            self._log = None
