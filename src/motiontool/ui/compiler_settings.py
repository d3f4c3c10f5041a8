"""Settings → Compiler's dialog (DG 3057-3085, ide-spec 1.45); the settings, kept in the settings file, and the
checks the IDE applies after the compiler are session/compiling.py's."""

from __future__ import annotations

from PySide6.QtWidgets import QCheckBox, QDialog, QDialogButtonBox, QFormLayout, QLabel, QSpinBox

from motiontool.session.compiling import NO_XREF, CompilerSettings

__all__ = ["NO_XREF", "CompilerSettings", "CompilerSettingsDialog", "edit_compiler_settings"]


class CompilerSettingsDialog(QDialog):
    def __init__(self, settings: CompilerSettings, parent=None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Compiler Options")
        form = QFormLayout(self)
        self.max_variables = _spin(1, 100_000, settings.max_variables)
        self.max_executable = _spin(1000, 100_000_000, settings.max_executable)
        self.max_executable.setSuffix(" bytes")
        self.stack_size = _spin(10, 100_000, settings.stack_size)
        self.preprocessor = QCheckBox("Enable Preprocessor")
        self.preprocessor.setChecked(settings.preprocessor)
        self.cross_reference = QCheckBox("Generate Cross Reference")
        self.cross_reference.setChecked(settings.cross_reference)
        form.addRow("Max number variables:", self.max_variables)
        form.addRow("Max executable size:", self.max_executable)
        form.addRow("Stack size:", self.stack_size)
        form.addRow(self.preprocessor)
        form.addRow(self.cross_reference)
        note = QLabel("An array counts as one variable. Older controllers take at most 65000 bytes. Cross "
                      "references are needed by the Watch and the debugger.")
        note.setWordWrap(True)
        form.addRow(note)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def settings(self) -> CompilerSettings:
        return CompilerSettings(self.max_variables.value(), self.max_executable.value(), self.stack_size.value(),
                                self.preprocessor.isChecked(), self.cross_reference.isChecked())


def _spin(low: int, high: int, value: int) -> QSpinBox:
    box = QSpinBox()
    box.setRange(low, high)
    box.setValue(value)
    return box


def edit_compiler_settings(w) -> bool:
    dialog = CompilerSettingsDialog(CompilerSettings.load(w.settings), w)
    if not dialog.exec():
        return False
    dialog.settings().save(w.settings)
    w.messages.ide("Compiler options saved: they apply from the next compile")
    return True
