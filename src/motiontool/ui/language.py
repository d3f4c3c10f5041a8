"""Settings → Language (DG 3113-3115): "the chosen language takes effect only after a restart". The IDE's own
texts are English; a language chosen here translates Qt's standard texts (buttons, file dialogs, messages)
with the translations Qt ships, loaded when the IDE starts."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QLibraryInfo, QLocale, QTranslator
from PySide6.QtWidgets import QComboBox, QDialog, QDialogButtonBox, QLabel, QVBoxLayout

SETTING = "ui/language"


def available() -> list[str]:
    """Language codes with a Qt translation ("de", "fr", "pt_BR" …), English first."""
    folder = Path(QLibraryInfo.path(QLibraryInfo.LibraryPath.TranslationsPath))
    found = sorted(p.stem.removeprefix("qtbase_") for p in folder.glob("qtbase_*.qm"))
    return ["en"] + [code for code in found if code != "en"]


def label(code: str) -> str:
    locale = QLocale(code)
    return f"{locale.nativeLanguageName() or code} ({code})"


def install(app, settings) -> QTranslator | None:
    """At start-up: the chosen language's Qt translation, if any (kept alive by the caller)."""
    code = settings.value(SETTING, "en")
    if not code or code == "en":
        return None
    translator = QTranslator(app)
    if translator.load(f"qtbase_{code}", QLibraryInfo.path(QLibraryInfo.LibraryPath.TranslationsPath)):
        app.installTranslator(translator)
        return translator
    return None


class LanguageDialog(QDialog):
    def __init__(self, current: str, parent=None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Language")
        self.choice = QComboBox()
        for code in available():
            self.choice.addItem(label(code), code)
        self.choice.setCurrentIndex(max(0, self.choice.findData(current)))
        note = QLabel("The language takes effect after a restart. It translates Qt's standard texts (buttons, "
                      "file dialogs); the IDE's own texts are English.")
        note.setWordWrap(True)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addWidget(self.choice)
        layout.addWidget(note)
        layout.addWidget(buttons)

    def code(self) -> str:
        return self.choice.currentData()


def choose_language(w) -> bool:
    dialog = LanguageDialog(w.settings.value(SETTING, "en"), w)
    if not dialog.exec():
        return False
    w.settings.setValue(SETTING, dialog.code())
    w.messages.ide(f"Language {label(dialog.code())}: takes effect when motiontool starts again")
    return True
