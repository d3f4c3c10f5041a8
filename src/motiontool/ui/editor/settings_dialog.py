"""Settings → Editor dialog (ide-spec 1.44, DG L3117-3150): a colour per element, tab size, convert tabs.

The first seven elements are the manual's (Comment, Keyword, Number, Operator, String, Text, Window); the
others are editor extras. A small CodeEditor shows a preview of the chosen colours.
"""

from __future__ import annotations

from dataclasses import fields, replace

from PySide6.QtCore import Qt
from PySide6.QtGui import QColor, QIcon, QPixmap
from PySide6.QtWidgets import (
    QCheckBox,
    QColorDialog,
    QDialog,
    QDialogButtonBox,
    QGridLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from motiontool.ui.editor.code_editor import CodeEditor
from motiontool.ui.editor.settings import MIN_TAB_SIZE, EditorColors, EditorSettings

_ROLE = Qt.ItemDataRole.UserRole
PREVIEW = """// preview
#define TARGET 0x1F40
SET KPROP 120
/* move */ POSA (TARGET + 2.5)
PRINT "done"
"""


def _label(name: str) -> str:
    return name.replace("_", " ").capitalize()


class EditorSettingsDialog(QDialog):
    def __init__(self, settings: EditorSettings | None = None, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Editor Settings")
        self._settings = settings or EditorSettings()
        self._colors = self._settings.colors.to_dict()
        self.elements = QListWidget()
        for f in fields(EditorColors):
            item = QListWidgetItem(_label(f.name))
            item.setData(_ROLE, f.name)
            self.elements.addItem(item)
        self.color_button = QPushButton("Color...")
        self.color_button.clicked.connect(self._pick)
        self.tab_size = QSpinBox()
        self.tab_size.setRange(MIN_TAB_SIZE, 16)  # "This can be set to 2 or more" [DG L3146]
        self.tab_size.setValue(self._settings.tab_size)
        self.convert = QCheckBox("Convert tabs to spaces while typing")
        self.convert.setChecked(self._settings.convert_tabs_while_typing)
        self.preview = CodeEditor(settings=self._settings)
        self.preview.setPlainText(PREVIEW)
        self.preview.setReadOnly(True)
        self.preview.setMinimumSize(320, 140)
        colors_box = QGroupBox("Colors")
        grid = QGridLayout(colors_box)
        grid.addWidget(QLabel("Text:"), 0, 0)
        grid.addWidget(self.elements, 1, 0, 2, 1)
        grid.addWidget(self.color_button, 1, 1)
        grid.addWidget(self.preview, 3, 0, 1, 2)
        tabs_box = QGroupBox("Tab Settings")
        tabs = QVBoxLayout(tabs_box)
        row = QHBoxLayout()
        row.addWidget(QLabel("Tab Size:"))
        row.addWidget(self.tab_size)
        row.addStretch(1)
        tabs.addLayout(row)
        tabs.addWidget(self.convert)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addWidget(colors_box)
        layout.addWidget(tabs_box)
        layout.addWidget(buttons)
        self.tab_size.valueChanged.connect(self._update_preview)
        self.convert.toggled.connect(self._update_preview)
        self.elements.setCurrentRow(0)
        self._update_preview()

    def current_element(self) -> str:
        return self.elements.currentItem().data(_ROLE)

    def set_color(self, element: str, color: str) -> None:
        """Set the colour of `element` (an EditorColors field) to '#rrggbb'."""
        self._colors[element] = QColor(color).name()
        self._update_preview()

    def _pick(self) -> None:
        element = self.current_element()
        color = QColorDialog.getColor(QColor(self._colors[element]), self, f"Color of {_label(element)}")
        if color.isValid():
            self.set_color(element, color.name())

    def _update_preview(self, *_args) -> None:
        for row in range(self.elements.count()):
            item = self.elements.item(row)
            swatch = QPixmap(14, 14)
            swatch.fill(QColor(self._colors[item.data(_ROLE)]))
            item.setIcon(QIcon(swatch))
        self.preview.apply_settings(self.settings())

    def settings(self) -> EditorSettings:
        """The settings as chosen in the dialog."""
        return replace(self._settings, tab_size=self.tab_size.value(),
                       convert_tabs_while_typing=self.convert.isChecked(),
                       colors=EditorColors.from_dict(self._colors))
