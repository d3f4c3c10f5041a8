"""Development → Download all (DG 2520-2524, 3276-3336; ide-spec 2.10, 2.33-2.35): the Download Mode dialog. Its
steps (per controller: stop, delete, download, verify, autostart, EPROM, restart; the confirmation; the log's
sentences) are the window session's (session/download_all.py, issue 27 item 5); this shows the fields, the check
boxes and the log."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import (
    QApplication,
    QCheckBox,
    QDialog,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPlainTextEdit,
    QPushButton,
    QVBoxLayout,
)

from motiontool.session.download_all import DownloadAll, parse_ids  # noqa: F401 - parse_ids: as before
from motiontool.ui.link_jobs import waiting


class DownloadDialog(QDialog):
    def __init__(self, w, path: Path | None = None) -> None:
        super().__init__(w)
        self.w = w
        self.setWindowTitle("Download Mode")
        self.file = QLineEdit(str(path) if path else "")
        browse = QPushButton("Browse...")
        browse.setAutoDefault(False)  # Return in a field must not open the file dialog (nor start a download)
        browse.clicked.connect(lambda *_: self.browse())
        row = QHBoxLayout()
        row.addWidget(self.file, 1)
        row.addWidget(browse)
        self.interface = QLabel(w.connection.interface_description)
        self.controllers = QLineEdit(str(w.bridge.controller_id))
        self.controllers.setToolTip("IDs and ranges, e.g. 1-5,7,9,15-20")
        self.name = QLineEdit((Path(path).stem if path else "")[:8].upper())
        self.name.setMaxLength(8)
        self.options = {}
        form = QFormLayout()
        form.addRow("File:", row)
        form.addRow("Interface:", self.interface)
        form.addRow("Controllers:", self.controllers)
        form.addRow("Program Name:", self.name)
        checks = QHBoxLayout()
        for key, text, on in (("download", "Download", True), ("verify", "Verify", True),
                              ("autostart", "Set Autostart", False), ("eprom", "Save in EPROM", False),
                              ("restart", "Restart", False)):
            box = QCheckBox(text)
            box.setChecked(on)
            self.options[key] = box
            checks.addWidget(box)
        form.addRow(checks)
        self.log = QPlainTextEdit()
        self.log.setReadOnly(True)
        buttons = QHBoxLayout()
        self.buttons = {}
        for text, slot in (("Start", self.start), ("Stop", self.stop), ("Save Log...", self.save_log_dialog),
                           ("Close", self.reject)):
            button = QPushButton(text)
            button.setAutoDefault(False)
            button.clicked.connect(lambda *_, s=slot: s())
            buttons.addWidget(button)
            self.buttons[text] = button
        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addWidget(self.log, 1)
        layout.addLayout(buttons)
        self.steps = DownloadAll(w.connection.session, w.prompts.within(self), self.say,
                                 lambda doing, work: waiting(w, doing, work))
        self.resize(640, 460)

    # --- helpers ---------------------------------------------------------------------------------------------
    def browse(self) -> None:
        chosen = self.w.prompts.within(self).open_path("Program to download", self.file.text(), "APOSS programs (*.m)")
        if chosen is not None:
            self.file.setText(str(chosen))
            if not self.name.text():
                self.name.setText(chosen.stem[:8].upper())

    def say(self, text: str) -> None:
        self.log.appendPlainText(text)
        QApplication.processEvents()  # the log shows the progress; Stop can be pressed between controllers

    def stop(self) -> None:
        self.steps.stopping = True

    @property
    def failed(self) -> list[int]:
        return self.steps.failed

    @property
    def succeeded(self) -> list[int]:
        return self.steps.succeeded

    def save_log(self, path: Path) -> None:
        from motiontool.fileio import atomic_write_text

        atomic_write_text(path, self.log.toPlainText() + "\n")

    def save_log_dialog(self) -> bool:
        chosen = self.w.prompts.within(self).save_path("Save Log", "download.log", "Log files (*.log *.txt)")
        if chosen is not None:
            self.save_log(chosen)
        return chosen is not None

    # --- processing --------------------------------------------------------------------------------------------
    def start(self) -> bool:
        """Start: disabled until the run ends (the log's processEvents lets Stop be pressed, and Start too)."""
        self.buttons["Start"].setEnabled(False)
        try:
            return self._start()
        finally:
            self.buttons["Start"].setEnabled(True)

    def _start(self) -> bool:
        self.log.clear()
        self.steps.stack_size = self.w.development.compiler_settings().stack_size
        return self.steps.start(self.file.text(), self.controllers.text(), self.name.text(),
                                lambda: {key: box.isChecked() for key, box in self.options.items()})


def download_all(w) -> DownloadDialog:
    """Download all: the dialog with the current program's file filled in."""
    editor = w.current_editor()
    path = editor.property("path") if editor is not None else None
    dialog = DownloadDialog(w, Path(path) if path else None)
    dialog.exec()
    return dialog
