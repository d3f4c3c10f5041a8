"""Development → Command List (F12, DG 2554-2607): pick a command, fill its fields, see the preview, insert
it at the caret or execute it now. Values are deliberately not range-checked (ide-spec 1.42)."""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QPushButton,
    QSplitter,
    QTextBrowser,
    QVBoxLayout,
    QWidget,
)

from motiontool.aposs.commands import Command, command_table

_FIELD_NAMES = {"expr": "Value", "var": "Variable", "array": "Array", "string": "Text", "param": "Parameter",
                "word": "Choice", "print": "Items"}


def preview_line(command: Command, values: list[str], comment: str = "") -> str:
    """The program line for a command and its field values (empty optional fields are left out)."""
    parts = [command.name]
    for spec, value in zip(command.args, values, strict=False):
        value = value.strip()
        if not value:
            continue
        if spec.kind == "string" and not value.startswith('"'):
            value = f'"{value}"'
        parts.append(value)
    line = " ".join(parts)
    if comment.strip():
        line += f"  // {comment.strip()}"
    return line


class CommandListDialog(QDialog):
    insert_requested = Signal(str)
    execute_requested = Signal(str)

    def __init__(self, parent: QWidget | None = None, can_execute: bool = True):
        super().__init__(parent)
        self.setWindowTitle("Command List")
        self.resize(760, 460)
        self.commands = sorted((c for c in command_table() if c.kind in ("command", "sysvar", "function")
                                and (c.statement or c.returns != "none")), key=lambda c: c.name)
        self.list = QListWidget()
        for c in self.commands:
            self.list.addItem(f"{c.name:<16} {c.syntax}")
        self.list.setFont(self.font())
        self.list.currentRowChanged.connect(self._select)
        self.form = QFormLayout()
        self.fields: list[QLineEdit | QComboBox] = []
        self.comment = QLineEdit()
        self.comment.setPlaceholderText("optional comment")
        self.comment.textChanged.connect(self._update_preview)
        self.preview = QLabel()
        self.preview.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.preview.setStyleSheet("font-family: monospace; padding: 4px; border: 1px solid palette(mid);")
        self.help = QTextBrowser()
        fields_box = QWidget()
        right = QVBoxLayout(fields_box)
        right.addLayout(self.form)
        right.addWidget(QLabel("Comment"))
        right.addWidget(self.comment)
        right.addWidget(QLabel("Preview"))
        right.addWidget(self.preview)
        right.addWidget(self.help, 1)
        splitter = QSplitter()
        splitter.addWidget(self.list)
        splitter.addWidget(fields_box)
        splitter.setSizes([300, 460])
        buttons = QDialogButtonBox()
        self.insert_button = QPushButton("Insert")
        self.execute_button = QPushButton("Execute now")
        self.execute_button.setEnabled(can_execute)
        buttons.addButton(self.insert_button, QDialogButtonBox.ButtonRole.ActionRole)
        buttons.addButton(self.execute_button, QDialogButtonBox.ButtonRole.ActionRole)
        buttons.addButton(QDialogButtonBox.StandardButton.Close)
        buttons.rejected.connect(self.reject)
        self.insert_button.clicked.connect(lambda: self.insert_requested.emit(self.line()))
        self.execute_button.clicked.connect(lambda: self.execute_requested.emit(self.line()))
        layout = QVBoxLayout(self)
        layout.addWidget(splitter, 1)
        row = QHBoxLayout()
        row.addWidget(buttons)
        layout.addLayout(row)
        self.list.setCurrentRow(0)

    def select_command(self, name: str) -> None:
        for i, c in enumerate(self.commands):
            if c.name == name.upper():
                self.list.setCurrentRow(i)
                return

    def current(self) -> Command:
        return self.commands[max(self.list.currentRow(), 0)]

    def _select(self, row: int) -> None:
        while self.form.rowCount():
            self.form.removeRow(0)
        self.fields = []
        command = self.commands[row]
        for n, spec in enumerate(command.args, 1):
            if spec.kind == "word":
                field = QComboBox()
                field.addItems(([""] if spec.optional else []) + list(spec.words))
                field.currentTextChanged.connect(self._update_preview)
            else:
                field = QLineEdit()
                field.textChanged.connect(self._update_preview)
            label = _FIELD_NAMES.get(spec.kind, spec.kind) + (" (optional)" if spec.optional else "")
            self.form.addRow(f"{n}. {label}", field)
            self.fields.append(field)
        self.help.setHtml(f"<p><b>{command.syntax}</b></p><p>{command.help}</p>"
                          f"<p><small>Group {command.group} · {command.src}</small></p>")
        self._update_preview()

    def values(self) -> list[str]:
        return [f.currentText() if isinstance(f, QComboBox) else f.text() for f in self.fields]

    def line(self) -> str:
        return preview_line(self.current(), self.values(), self.comment.text())

    def _update_preview(self) -> None:
        self.preview.setText(self.line())
