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
    QPushButton,
    QSplitter,
    QTextBrowser,
    QTreeWidget,
    QTreeWidgetItem,
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


class _FilterField(QLineEdit):
    """Enter chooses the first command shown instead of reaching the dialog's default button (Insert), and Down
    goes on into the list, as in a search field."""

    def __init__(self, dialog: CommandListDialog) -> None:
        super().__init__()
        self.dialog = dialog

    def keyPressEvent(self, event) -> None:  # noqa: N802 - Qt override
        if event.key() in (Qt.Key.Key_Return, Qt.Key.Key_Enter):
            self.dialog.first_shown()
            event.accept()
        elif event.key() == Qt.Key.Key_Down:
            self.dialog.list.setFocus()
            event.accept()
        else:
            super().keyPressEvent(event)


class CommandListDialog(QDialog):
    insert_requested = Signal(str)
    execute_requested = Signal(str)

    def __init__(self, parent: QWidget | None = None, can_execute: bool = True):
        super().__init__(parent)
        self.setWindowTitle("Command List")
        self.resize(760, 460)
        self.commands = sorted((c for c in command_table() if c.kind in ("command", "sysvar", "function")
                                and (c.statement or c.returns != "none")), key=lambda c: c.name)
        # two columns, not "NAME<16 spaces>syntax" in one: padding with spaces aligns nothing in a proportional font
        self.list = QTreeWidget()
        self.list.setHeaderLabels(["Command", "Syntax"])
        self.list.setRootIsDecorated(False)
        self.list.setUniformRowHeights(True)
        self.list.addTopLevelItems([QTreeWidgetItem([c.name, c.syntax]) for c in self.commands])
        self.list.resizeColumnToContents(0)
        self.list.currentItemChanged.connect(lambda item, _previous: self._select(self.list.indexOfTopLevelItem(item))
                                             if item is not None else None)
        self.filter = _FilterField(self)
        self.filter.setPlaceholderText("Filter: part of a command's name or syntax")
        self.filter.setClearButtonEnabled(True)
        self.filter.textChanged.connect(self._filter)
        left = QWidget()
        column = QVBoxLayout(left)
        column.setContentsMargins(0, 0, 0, 0)
        column.addWidget(self.filter)
        column.addWidget(self.list, 1)
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
        splitter.addWidget(left)
        splitter.addWidget(fields_box)
        splitter.setSizes([340, 420])
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
        self.list.setCurrentItem(self.list.topLevelItem(0))
        self.filter.setFocus()

    def select_command(self, name: str) -> None:
        for i, c in enumerate(self.commands):
            if c.name == name.upper():
                self.list.setCurrentItem(self.list.topLevelItem(i))
                return

    def current(self) -> Command:
        return self.commands[max(self.list.indexOfTopLevelItem(self.list.currentItem()), 0)]

    def shown(self) -> list[str]:
        """The command names the filter leaves in the list, in order."""
        return [self.list.topLevelItem(i).text(0) for i in range(self.list.topLevelItemCount())
                if not self.list.topLevelItem(i).isHidden()]

    def _filter(self, text: str) -> None:
        needle = text.strip().upper()
        for i, c in enumerate(self.commands):
            self.list.topLevelItem(i).setHidden(bool(needle) and needle not in c.name
                                                and needle not in c.syntax.upper())
        current = self.list.currentItem()
        if current is None or current.isHidden():
            self.first_shown()

    def first_shown(self) -> None:
        """Enter in the filter (or a filter that hid the selected command): the first command still shown."""
        for i in range(self.list.topLevelItemCount()):
            item = self.list.topLevelItem(i)
            if not item.isHidden():
                self.list.setCurrentItem(item)
                self.list.scrollToItem(item)
                return

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
