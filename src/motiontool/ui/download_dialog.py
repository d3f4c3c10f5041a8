"""Development → Download all (DG 2520-2524, 3276-3336; ide-spec 2.10, 2.33-2.35): one program to several
controllers of the window's interface, each in turn:

1. stop a running program, 2. compile, 3. delete all programs, 4. download and save as program 0 under the
given name, 5. Verify: read it back and compare (a mismatch stops this controller), 6. Set Autostart, 7. Save
in EPROM, 8. Restart (power on). An error stops only the current controller; the summary names those that
failed ("Failed for controllers: 2"). With Verify on and Download off nothing is written: the program on the
controller is only compared."""

from __future__ import annotations

import re
from functools import partial
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

from motiontool import __version__
from motiontool.aposs.driver import compile_source
from motiontool.comms.protocol import LinkError
from motiontool.ui.link_jobs import waiting
from motiontool.ui.parameter_dialogs import controller_link

_RANGE = re.compile(r"^\s*(\d+)\s*(?:-\s*(\d+))?\s*$")


def parse_ids(text: str) -> list[int]:
    """"1-5,7,9,15-20" → the IDs in that order without repeats; ValueError names a bad part."""
    ids: list[int] = []
    for part in text.split(","):
        m = _RANGE.match(part)
        if not m:
            raise ValueError(f"controllers: {part.strip()!r} is not an ID or a range like 1-5")
        first, last = int(m.group(1)), int(m.group(2) or m.group(1))
        if last < first:
            raise ValueError(f"controllers: the range {first}-{last} runs backwards")
        ids += [n for n in range(first, last + 1) if n not in ids]
    return ids


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
        self._stopping = False
        self.failed: list[int] = []
        self.succeeded: list[int] = []
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
        self._stopping = True

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

    def _ask(self, cid: int, doing: str, work):
        """One exchange with a controller on a thread; the window paints and says what it waits for."""
        return waiting(self.w, f"Controller {cid}: {doing} …", work)

    def _start(self) -> bool:
        self._stopping, self.failed, self.succeeded = False, [], []
        self.log.clear()
        self.say(f"motiontool {__version__} — Download Mode")
        try:
            ids = parse_ids(self.controllers.text())
        except ValueError as exc:
            self.say(str(exc))
            return False
        path = Path(self.file.text().strip())
        name = self.name.text().strip()[:8] or path.stem[:8]
        try:
            source = path.read_text(encoding="utf-8")
        except OSError as exc:
            self.say(f"{path}: {exc.strerror or exc}")
            return False
        result = compile_source(source, str(path), name=name)
        if not result.ok:
            for d in result.errors:
                self.say(d.format())
            self.say("Compilation failed: nothing downloaded")
            return False
        image = result.image.to_bytes()
        self.say(f"Compiled {path.name}: {len(image)} bytes")
        if self.options["download"].isChecked() and not self.confirm_deletion(ids, name):
            self.say("Cancelled: no program was deleted")
            return False
        for cid in ids:
            if self._stopping:
                self.say("Stopped")
                break
            (self.succeeded if self.process(cid, image, name) else self.failed).append(cid)
        if self.succeeded:
            self.say(f"Done for controllers: {', '.join(map(str, self.succeeded))}")
        if self.failed:
            self.say(f"Failed for controllers: {', '.join(map(str, self.failed))}")
        return not self.failed

    def confirm_deletion(self, ids: list[int], name: str) -> bool:
        """Download deletes every stored program first (DG 3316): the user sees which, and may cancel, before any
        is gone. A controller that cannot be asked is left to fail in its turn."""
        stored = []
        for cid in ids:
            try:
                link = self._ask(cid, "connecting", partial(controller_link, self.w, cid))
                programs = self._ask(cid, "listing its programs", link.list_programs)
            except (LinkError, ValueError):
                continue
            if programs:
                names = ", ".join(f"{p.number} {p.name}" for p in programs)
                stored.append(f"Controller {cid}: {names}")
        if not stored:
            return True
        return self.w.prompts.within(self).choose(
            "Download all", f"Download deletes all programs stored on the controllers before it saves \"{name}\" "
            "as program 0:", ["Delete and Download"], detail="\n".join(stored), warning=True,
            destructive=True) is not None

    def process(self, cid: int, image: bytes, name: str) -> bool:
        opt = {key: box.isChecked() for key, box in self.options.items()}
        ask = self._ask
        stack = self.w.development.compiler_settings().stack_size
        try:
            link = ask(cid, "connecting", partial(controller_link, self.w, cid))
            if opt["download"]:
                if ask(cid, "asking its state", lambda: link.status().program_state) in ("running", "break"):
                    ask(cid, "stopping its program", link.break_program)
                    self.say(f"Controller {cid}: program stopped")
                self.say(f"Controller {cid}: deleting programs")
                ask(cid, "deleting programs", lambda: [link.delete_program(p.number) for p in link.list_programs()])
                ask(cid, f"downloading {name}", lambda: link.download(image, number=0, name=name, stack_size=stack))
                self.say(f"Controller {cid}: saved as \"{name}\" (program 0)")
            if opt["verify"]:
                stored = ask(cid, "verifying", lambda: link.upload_program(0))
                if stored != image:
                    self.say(f"Controller {cid}: verify failed: program 0 differs from {self.file.text()}")
                    return False
                self.say(f"Controller {cid}: verify ok")
            if opt["download"]:
                if opt["autostart"]:
                    ask(cid, "setting Autostart", lambda: link.set_autostart(0))
                    self.say(f"Controller {cid}: Autostart set")
                if opt["eprom"]:
                    ask(cid, "saving RAM", lambda: link.save_memory("ram"))
                    self.say(f"Controller {cid}: saving RAM")
                if opt["restart"]:
                    ask(cid, "restarting", link.power_on)
                    self.say(f"Controller {cid}: restarted")
        except (LinkError, ValueError) as exc:
            self.say(f"Controller {cid}: {exc}")
            return False
        return True


def download_all(w) -> DownloadDialog:
    """Download all: the dialog with the current program's file filled in."""
    editor = w.current_editor()
    path = editor.property("path") if editor is not None else None
    dialog = DownloadDialog(w, Path(path) if path else None)
    dialog.exec()
    return dialog
