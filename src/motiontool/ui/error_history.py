"""Controller → Error History (DG 2982-3027, ide-spec 2.31): the controller's last 50 errors, newest first, as
the manual's table — #, Time (the controller's clock), Age (seconds since the error, recomputed on Refresh),
Error, Message, Data, Offset (in the compiled program), Line, and Program: the file of the program that raised
it, as the IDE noted when the error arrived (the controller does not record it). Refresh reads it again, Write
saves a tab-separated text file a spreadsheet imports, Clear empties it; a double-click closes the dialog and
shows the line in that program, its tab brought to the front or its file opened (I19; "The IDE cannot check
that the source matches")."""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

from PySide6.QtWidgets import (
    QAbstractItemView,
    QDialog,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
)

from motiontool.comms.client import ErrorRecord
from motiontool.comms.protocol import LinkError
from motiontool.ui.link_jobs import waiting

COLUMNS = ("#", "Time", "Age", "Error", "Message", "Data", "Offset", "Line", "Program")


@dataclass(frozen=True)
class Entry:
    """One row: the controller's record and what the IDE adds to it."""
    error: ErrorRecord
    age_s: float
    offset: int | None
    program: tuple[object, str] | None        # (editor or None, label) of the program that raised it


def statement_offset(image, line: int | None) -> int | None:
    """The offset of the first instruction of `line` in the program image the IDE downloaded (decision I14)."""
    if image is None or not line:
        return None
    return next((entry.pc for entry in image.lines if entry.file == 0 and entry.line == line), None)


class ErrorHistoryDialog(QDialog):
    def __init__(self, w, controller_id: int) -> None:
        super().__init__(w)
        self.w = w
        self.controller_id = controller_id
        self.entries: list[Entry] = []
        self.read_at = ""
        self.setWindowTitle(f"Error History — controller {controller_id}")
        self.header = QLabel()
        self.table = QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(COLUMNS)
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.verticalHeader().hide()
        self.table.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.table.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        for column, width in enumerate((36, 80, 60, 50, 200, 120, 60, 44)):
            self.table.setColumnWidth(column, width)
        self.table.cellDoubleClicked.connect(lambda row, _column: self.jump(row))
        buttons = QHBoxLayout()
        self.buttons = {}
        for text, slot in (("Refresh", self.refresh), ("Write...", self.write_dialog), ("Clear", self.clear),
                           ("Close", self.reject)):
            button = QPushButton(text)
            button.clicked.connect(lambda *_, s=slot: s())
            buttons.addWidget(button)
            self.buttons[text] = button
        layout = QVBoxLayout(self)
        layout.addWidget(self.header)
        layout.addWidget(self.table)
        layout.addLayout(buttons)
        self.resize(900, 380)
        self.refresh()

    def link(self):
        return self.w.controllers.link(self.controller_id, interface=self.w.connection.interface_key)

    def refresh(self) -> bool:
        """Read the list; Age counts from the controller's clock now."""
        def read():
            link = self.link()
            return link.error_history(), link.status().time_ms

        self.header.setText(f"Controller {self.controller_id}: reading the error history …")
        try:
            history, now = waiting(self.w, f"Controller {self.controller_id}: reading its error history …", read)
        except (LinkError, ValueError) as exc:
            self.header.setText(f"Controller {self.controller_id}: {exc}")
            return False
        image = self.w.development.images.get(self.controller_id)
        self.entries = []
        for e in reversed(history):  # newest first (DG 2996)
            self.entries.append(Entry(e, max(0, now - e.time_ms) / 1000, statement_offset(image, e.line),
                                      self.program_of(e)))
        self.read_at = time.strftime("%Y-%m-%d %H:%M:%S")
        self.header.setText(f"Controller {self.controller_id}, read {self.read_at}: {len(self.entries)} error(s)")
        self.table.setRowCount(len(self.entries))
        for row, e in enumerate(self.entries):
            for column, value in enumerate(self.row_values(row, e)):
                self.table.setItem(row, column, QTableWidgetItem(value))
            program = self.table.item(row, COLUMNS.index("Program"))
            program.setToolTip(e.program[1] if e.program else "Not started from this window: the program "
                               "is not known")
        return True

    def program_of(self, e: ErrorRecord) -> tuple[object, str] | None:
        """(editor, label) of the program that raised the error; the label follows a tab saved since."""
        noted = self.w.development.error_program(self.controller_id, e.time_ms, e.number)
        if noted is None:
            return None
        editor, label = noted
        return (editor, self.w.program_label(editor)) if editor in self.w.editors() else (None, label)

    @staticmethod
    def row_values(row: int, e: Entry) -> list[str]:
        error = e.error
        return [str(row + 1), str(error.time_ms), f"{e.age_s:.1f}", str(error.number), error.text,
                error.detail or "", "" if e.offset is None else str(e.offset),
                "" if not error.line else str(error.line),
                Path(e.program[1]).name if e.program else ""]

    def write(self, path: Path) -> None:
        """Write (DG 3025): an ASCII text file, tab-separated, that a spreadsheet can import."""
        from motiontool.fileio import atomic_write_text

        lines = [f"Error History, controller {self.controller_id}, read {self.read_at}", "\t".join(COLUMNS)]
        lines += ["\t".join(self.row_values(row, e)) for row, e in enumerate(self.entries)]
        atomic_write_text(path, "\n".join(lines) + "\n")

    def write_dialog(self) -> bool:
        chosen = self.w.prompts.within(self).save_path("Write error history", "errors.txt", "Text (*.txt)")
        if chosen is None:
            return False
        try:
            self.write(chosen)
        except OSError as exc:
            self.header.setText(f"Not written: {chosen}: {exc.strerror or exc}")
            return False
        self.w.messages.ide(f"Error history of controller {self.controller_id} written to {chosen}")
        return True

    def clear(self) -> None:
        try:
            waiting(self.w, f"Controller {self.controller_id}: clearing its error history …",
                    lambda: self.link().clear_error_history())
        except (LinkError, ValueError) as exc:
            self.header.setText(f"Controller {self.controller_id}: {exc}")
            return
        self.refresh()

    def jump(self, row: int) -> bool:
        """Double-click (DG 3021-3023): close the dialog and show the line in the program that raised the error:
        its tab, else its file opened; never a line of whichever program happens to be in front."""
        entry = self.entries[row] if 0 <= row < len(self.entries) else None
        line, program = (entry.error.line, entry.program) if entry is not None else (None, None)
        if not line:
            self.header.setText("This error has no program line")
            return False
        if program is None:
            self.header.setText(f"Line {line}: the program was not started from this window, its file is not known")
            return False
        editor, label = program
        if editor is None:
            path = Path(label)
            if not path.is_file():
                self.header.setText(f"Line {line} of {label}: that program is no longer open")
                return False
            try:
                editor = self.w.open_file(path)
            except OSError as exc:
                self.header.setText(f"Cannot open {label}: {exc.strerror or exc}")
                return False
        self.accept()
        self.w.tabs.setCurrentWidget(editor)
        editor.goto_line(int(line), col=1)
        editor.setFocus()
        return True


def show_error_history(w) -> None:
    if w.development.connect_default():
        ErrorHistoryDialog(w, w.bridge.controller_id).exec()
