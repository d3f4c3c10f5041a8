"""Settings → Compiler (DG 3057-3085, ide-spec 1.45): Max number of variables (500; an array counts as one),
Max executable size (65000 bytes), Stack size (200), Enable Preprocessor, Generate Cross Reference. Kept in the
settings file. The IDE applies them after the compiler: a program over a limit gets an error at its first
line, a preprocessor directive with the preprocessor off an error at its line; the stack size travels with
the download; without the cross reference Syntax Check writes no .ad$ and the debugger and the Watch explain
that they need it (DG 3083-3085)."""

from __future__ import annotations

import re
from dataclasses import dataclass, fields

from PySide6.QtWidgets import QCheckBox, QDialog, QDialogButtonBox, QFormLayout, QLabel, QSpinBox

from motiontool.language.diagnostics import Diagnostic, Location

_DIRECTIVE = re.compile(r"^\s*#\s*(define|undef|if|ifdef|ifndef|elif|else|endif|pragma)\b")
NO_XREF = ("Settings → Compiler → Generate Cross Reference is off: the debugger and the Watch need the cross "
           "reference (DG 3083-3085)")


@dataclass
class CompilerSettings:
    max_variables: int = 500
    max_executable: int = 65000
    stack_size: int = 200
    preprocessor: bool = True
    cross_reference: bool = True

    @classmethod
    def load(cls, settings) -> CompilerSettings:
        defaults = cls()
        values = {}
        for f in fields(cls):
            default = getattr(defaults, f.name)
            try:
                values[f.name] = settings.value(f"compiler/{f.name}", default, type=type(default))
            except (TypeError, ValueError):  # a damaged settings file: the default
                values[f.name] = default
        return cls(**values)

    def save(self, settings) -> None:
        for f in fields(self):
            settings.setValue(f"compiler/{f.name}", getattr(self, f.name))


def check(settings: CompilerSettings, result, source: str, label: str) -> list[Diagnostic]:
    """The IDE's checks of the compiler options on a compiled program (`result` a CompileResult)."""
    found = []
    if not settings.preprocessor:
        for number, line in enumerate(source.splitlines(), 1):
            m = _DIRECTIVE.match(line)
            if m:
                found.append(Diagnostic("error", f"#{m.group(1)}: the preprocessor is switched off (Settings → "
                                                 "Compiler → Enable Preprocessor)", Location(label, number, 1)))
    image = result.image
    if image is not None:
        variables = sum(1 for v in image.globals if not v.name.startswith("$")) + len(image.arrays) + len(image.dims)
        if variables > settings.max_variables:
            found.append(Diagnostic("error", f"the program has {variables} variables (arrays count as one); "
                                             f"Settings → Compiler allows {settings.max_variables}",
                                    Location(label, 1, 1)))
        size = len(image.to_bytes())
        if size > settings.max_executable:
            found.append(Diagnostic("error", f"the program is {size} bytes; Settings → Compiler allows "
                                             f"{settings.max_executable} (Max executable size)", Location(label, 1, 1)))
    return found


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
