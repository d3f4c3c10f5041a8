"""Find / Replace dialog (ide-spec 1.32-1.35) and Find in Files dialog (ide-spec 1.36) for a CodeEditor.

Both are non-modal. The search syntax is chosen in a combo box: plain text (default), the manual's pattern
syntax (``search.translate_pattern``, DG L2308-2324) or a Python regular expression.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDialog,
    QFormLayout,
    QGridLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QRadioButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from motiontool.qtjobs.prompts import QtPrompts
from motiontool.ui.editor import search
from motiontool.ui.editor.search import PatternError, SearchOptions

if TYPE_CHECKING:
    from motiontool.session.prompts import Prompts
    from motiontool.ui.editor.code_editor import CodeEditor

SYNTAXES = (("Plain text", "plain"), ("Pattern (manual syntax: ? + * [ ] | ( ))", "pattern"),
            ("Python regular expression", "regex"))


class _OptionsBox(QGroupBox):
    """Match case, whole word, syntax; shared by both dialogs."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Options", parent)
        self.match_case = QCheckBox("Match &case")
        self.whole_word = QCheckBox("Match &whole word only")
        self.syntax = QComboBox()
        for text, mode in SYNTAXES:
            self.syntax.addItem(text, mode)
        layout = QVBoxLayout(self)
        layout.addWidget(self.match_case)
        layout.addWidget(self.whole_word)
        layout.addWidget(self.syntax)

    def options(self, *, backward: bool = False, wrap: bool = True) -> SearchOptions:
        return SearchOptions(self.syntax.currentData(), self.match_case.isChecked(), self.whole_word.isChecked(),
                             backward, wrap)

    def set_mode(self, mode: str) -> None:
        self.syntax.setCurrentIndex(max(0, self.syntax.findData(mode)))


class FindReplaceDialog(QDialog):
    """Find Next, Mark All, Replace, Replace All (one undo step) and Close for `editor`."""

    def __init__(self, editor: CodeEditor, parent: QWidget | None = None) -> None:
        super().__init__(parent or editor)
        self.editor = editor
        self.setWindowTitle("Find")
        self.find_edit = QLineEdit()
        self.replace_edit = QLineEdit()
        self.replace_label = QLabel("Re&place with:")
        self.replace_label.setBuddy(self.replace_edit)
        form = QFormLayout()
        find_label = QLabel("Fi&nd what:")
        find_label.setBuddy(self.find_edit)
        form.addRow(find_label, self.find_edit)
        form.addRow(self.replace_label, self.replace_edit)
        self.options_box = _OptionsBox()
        direction = QGroupBox("Direction")
        self.up = QRadioButton("&Up")
        self.down = QRadioButton("&Down")
        self.down.setChecked(True)
        self.wrap = QCheckBox("Wra&p around")
        self.wrap.setChecked(True)
        d_layout = QVBoxLayout(direction)
        for w in (self.up, self.down, self.wrap):
            d_layout.addWidget(w)
        self.status = QLabel()
        self.status.setObjectName("status")
        self.find_button = QPushButton("&Find Next")
        self.find_button.setDefault(True)
        self.mark_button = QPushButton("&Mark All")
        self.replace_button = QPushButton("&Replace")
        self.replace_all_button = QPushButton("Replace &All")
        self.close_button = QPushButton("Close")
        buttons = QVBoxLayout()
        for b in (self.find_button, self.mark_button, self.replace_button, self.replace_all_button,
                  self.close_button):
            buttons.addWidget(b)
        buttons.addStretch(1)
        grid = QGridLayout(self)
        grid.addLayout(form, 0, 0, 1, 2)
        grid.addWidget(self.options_box, 1, 0)
        grid.addWidget(direction, 1, 1)
        grid.addWidget(self.status, 2, 0, 1, 2)
        grid.addLayout(buttons, 0, 2, 3, 1)
        self.find_button.clicked.connect(self.find_next)
        self.mark_button.clicked.connect(self.mark_all)
        self.replace_button.clicked.connect(self.replace)
        self.replace_all_button.clicked.connect(self.replace_all)
        self.close_button.clicked.connect(self.close)
        self.find_edit.textChanged.connect(lambda _t: self.status.clear())

    def open_for(self, *, replace: bool = False) -> None:
        """Show the dialog (as Find or as Replace) with the selected word as the search text."""
        self.set_replace_mode(replace)
        word = self.editor.search.word_under_caret() if self.editor.textCursor().hasSelection() else ""
        if word and "\u2029" not in word:
            self.find_edit.setText(word)
        elif not self.find_edit.text():
            self.find_edit.setText(self.editor.search.search_text)
        self.show()
        self.raise_()
        self.activateWindow()
        self.find_edit.setFocus()
        self.find_edit.selectAll()

    def set_replace_mode(self, replace: bool) -> None:
        self.setWindowTitle("Replace" if replace else "Find")
        for w in (self.replace_label, self.replace_edit, self.replace_button, self.replace_all_button):
            w.setVisible(replace)

    def options(self) -> SearchOptions:
        return self.options_box.options(backward=self.up.isChecked(), wrap=self.wrap.isChecked())

    def _run(self, action) -> object:
        self.status.clear()
        try:
            return action()
        except PatternError as exc:
            self.status.setText(f"<span style='color:#c00'>{exc}</span>")
            return None

    def find_next(self) -> bool:
        found = self._run(lambda: self.editor.search.find(text=self.find_edit.text(), options=self.options()))
        if found is False:
            self.status.setText(f"Cannot find \u201c{self.find_edit.text()}\u201d.")
        elif found and self.editor.search.last_hit is not None and self.editor.search.last_hit.wrapped:
            self.status.setText("Passed the end of the program; continued at the other end.")
        return bool(found)

    def mark_all(self) -> int:
        count = self._run(lambda: self.editor.search.mark_all(self.find_edit.text(), options=self.options()))
        if count is not None:
            self.status.setText(f"{count} line(s) bookmarked; F2 walks through them.")
        return count or 0

    def replace(self) -> bool:
        done = self._run(lambda: self.editor.search.replace(self.find_edit.text(), self.replace_edit.text(),
                                                     options=self.options()))
        if done is not None and not self.editor.textCursor().hasSelection():
            self.status.setText("No more occurrences.")
        return bool(done)

    def replace_all(self) -> int:
        count = self._run(lambda: self.editor.search.replace_all(self.find_edit.text(), self.replace_edit.text(),
                                                          options=self.options()))
        if count is not None:
            self.status.setText(f"{count} replacement(s).")
        return count or 0


class FindInFilesDialog(QDialog):
    """Searches the files on disk below a folder; double-clicking a hit emits ``locationActivated``."""

    locationActivated = Signal(str, int, int)  # path, line, column (1-based)

    def __init__(self, root: str | Path, parent: QWidget | None = None, *, prompts: Prompts | None = None) -> None:
        super().__init__(parent)
        self.prompts = prompts.within(self) if prompts is not None else QtPrompts(self)   # its editor's, over it
        self.setWindowTitle("Find in Files")
        self.resize(720, 420)
        self.find_edit = QLineEdit()
        self.folder_edit = QLineEdit(str(root))
        browse = QPushButton("...")
        browse.setFixedWidth(32)
        browse.clicked.connect(self._browse)
        self.types_edit = QLineEdit("*.m")
        folder_row = QHBoxLayout()
        folder_row.addWidget(self.folder_edit)
        folder_row.addWidget(browse)
        form = QFormLayout()
        form.addRow("Fi&nd what:", self.find_edit)
        folder_label = QLabel("In &folder:")
        folder_label.setBuddy(self.folder_edit)
        form.addRow(folder_label, folder_row)
        form.addRow("File &types:", self.types_edit)
        self.options_box = _OptionsBox()
        self.results = QTreeWidget()
        self.results.setHeaderLabels(["File", "Line", "Text"])
        self.results.setRootIsDecorated(False)
        self.results.setColumnWidth(0, 220)
        self.results.setColumnWidth(1, 50)
        self.results.itemDoubleClicked.connect(self._activated)
        self.status = QLabel("Searches the saved files only; unsaved changes are not found.")
        self.find_button = QPushButton("&Find")
        self.find_button.setDefault(True)
        self.find_button.clicked.connect(self.run_search)
        close = QPushButton("Close")
        close.clicked.connect(self.close)
        top = QHBoxLayout()
        top.addLayout(form, 1)
        top.addWidget(self.options_box)
        side = QVBoxLayout()
        side.addWidget(self.find_button)
        side.addWidget(close)
        side.addStretch(1)
        top.addLayout(side)
        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addWidget(self.results, 1)
        layout.addWidget(self.status)

    def open_for(self, *, text: str = "") -> None:
        if text and "\u2029" not in text:
            self.find_edit.setText(text)
        self.show()
        self.raise_()
        self.find_edit.setFocus()
        self.find_edit.selectAll()

    def _browse(self) -> None:
        folder = self.prompts.folder("Folder", self.folder_edit.text())
        if folder is not None:
            self.folder_edit.setText(str(folder))

    def run_search(self) -> list[search.FileHit]:
        self.results.clear()
        root = Path(self.folder_edit.text()).expanduser()
        try:
            hits = search.find_in_files(root, self.find_edit.text(), self.types_edit.text().strip() or "*",
                                        self.options_box.options())
        except PatternError as exc:
            self.status.setText(str(exc))
            return []
        for hit in hits:
            shown = hit.path.relative_to(root) if hit.path.is_relative_to(root) else hit.path
            item = QTreeWidgetItem([str(shown), str(hit.line), hit.text.strip()])
            item.setData(0, Qt.ItemDataRole.UserRole, (str(hit.path), hit.line, hit.col))
            item.setTextAlignment(1, Qt.AlignmentFlag.AlignRight)
            self.results.addTopLevelItem(item)
        files = len({h.path for h in hits})
        self.status.setText(f"{len(hits)} hit(s) in {files} file(s). Double-click a hit to open it.")
        return hits

    def _activated(self, item: QTreeWidgetItem) -> None:
        path, line, col = item.data(0, Qt.ItemDataRole.UserRole)
        self.locationActivated.emit(path, line, col)
