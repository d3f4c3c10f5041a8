"""Controller menu (ide-spec 2.15-2.30, DG 2613-2980): Programs, Parameters ▸ Save to file / Restore from file,
Reset ▸, Memory ▸, Diagnostic Report. The commands are the window session's (session/controller_commands.py, issue
27 item 5); this holds their dialogs: which controller and sets to restore, the table of stored programs."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import (
    QAbstractItemView,
    QCheckBox,
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QHBoxLayout,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
)

from motiontool.comms.client import ProgramInfo
from motiontool.session.controller_commands import (  # noqa: F401 - the menus' entries and the report, as before
    MEMORY_ENTRIES,
    PROGRAM_NUMBERS,
    RESET_ENTRIES,
    ControllerCommands,
    StoredPrograms,
    config_io,
    diagnostic_report_text,
)
from motiontool.session.controllers import SIMULATED_IDS
from motiontool.ui.link_jobs import waiting

SET_LABELS = {"global": "Global parameters", "axis": "Axis parameters", "user": "User parameters",
              "drive": "FC 300 drive parameters", "arrays": "Arrays"}
AUTOSTART_MARK = "\u2299"  # ⊙, DG 2727


def commands(w) -> ControllerCommands:
    """The window session's Controller menu commands: requests off the GUI thread, questions through the window's
    prompts, what happened in the Communication pane."""
    return ControllerCommands(w.connection.session, w.prompts, w.messages.ide,
                              lambda doing, work: waiting(w, doing, work))


def save_parameters(w, path: Path | None = None) -> bool:
    """Parameters → Save to file (DG 2884-2892)."""
    return commands(w).save_parameters(path)

class RestoreDialog(QDialog):
    """Pick the controller and the sets to load; Restore overwrites them (DG 2894-2900)."""

    def __init__(self, parent, path: Path, controller_id: int) -> None:
        super().__init__(parent)
        self.setWindowTitle(f"Restore from file — {path.name}")
        self.controller = QComboBox()
        connection = parent.connection   # the controllers of this window's interface (DG 2894-2900)
        iface = parent.controllers.interfaces.get(connection.interface_key or "")
        for cid in iface.found if iface else SIMULATED_IDS:
            self.controller.addItem(f"Controller {cid}: {connection.interface_description}", cid)
        self.controller.setCurrentIndex(max(0, self.controller.findData(controller_id)))
        self.checks = {name: QCheckBox(SET_LABELS[name]) for name in config_io()[0].SETS}
        form = QFormLayout(self)
        form.addRow("Load into", self.controller)
        for check in self.checks.values():
            check.setChecked(True)
            form.addRow(check)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Cancel)
        self.restore_button = buttons.addButton("Restore", QDialogButtonBox.ButtonRole.AcceptRole)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def sets(self) -> tuple[str, ...]:
        return tuple(name for name, check in self.checks.items() if check.isChecked())

    def controller_id(self) -> int:
        return int(self.controller.currentData())


def restore_parameters(w, path: Path | None = None, controller_id: int | None = None,
                       sets: tuple[str, ...] | None = None) -> bool:
    """Parameters → Restore from file: an Open dialog, then the target controller and the sets."""
    def choose(chosen: Path) -> tuple[int, tuple[str, ...]] | None:
        dialog = RestoreDialog(w, chosen, w.bridge.controller_id)
        return (dialog.controller_id(), dialog.sets()) if dialog.exec() else None

    return commands(w).restore_parameters(path, controller_id, sets, choose=choose)


def reset(w, what: str, ask: bool = True) -> bool:
    """Controller → Reset ▸ (DG 2948-2980)."""
    return commands(w).reset(what, ask)


def memory(w, what: str, *, ask: bool = True) -> bool:
    """Controller → Memory ▸ (DG 2908-2946)."""
    return commands(w).memory(what, ask=ask)


class ProgramsDialog(QDialog):
    """Controller → Programs (DG 2627-2794): the programs stored on the controller; Save / Save as compile the
    current editor into permanent memory (with Include Sourcecode also its source and include files), Upload
    brings a stored source back, Start runs the selected one, Delete / Delete all remove them."""

    def __init__(self, w) -> None:
        super().__init__(w)
        self.w = w
        self.setWindowTitle(f"Programs — controller {w.bridge.controller_id}")
        self.table = QTableWidget(0, 4)
        self.table.setHorizontalHeaderLabels(["No.", "Name", "Autostart", "Source"])
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.verticalHeader().hide()
        self.table.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.table.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        buttons = QHBoxLayout()
        self.buttons = {}
        for text, slot in (("Save", self.save), ("Save as...", self.save_as), ("Start", self.start),
                           ("Autostart on", lambda: self.autostart(True)),
                           ("Autostart off", lambda: self.autostart(False)),
                           ("Upload...", self.upload), ("Delete", self.delete), ("Delete all", self.delete_all),
                           ("Close", self.accept)):
            button = QPushButton(text)
            button.clicked.connect(lambda *_, s=slot: s())
            buttons.addWidget(button)
            self.buttons[text] = button
        self.include_source = QCheckBox("Include Sourcecode")
        self.include_source.setToolTip("Save also stores the program's source and its include files, so Upload can "
                                       "bring them back (DG 2643-2669)")
        layout = QVBoxLayout(self)
        layout.addWidget(self.table)
        layout.addWidget(self.include_source)
        layout.addLayout(buttons)
        self.resize(640, 340)
        self.refresh()

    @property
    def commands(self) -> StoredPrograms:
        """The session's Programs commands; what they ask is shown over this dialog (issue 27 item 2: requests
        off the GUI thread while the window paints)."""
        w = self.w
        return StoredPrograms(w.connection.session, w.prompts.within(self), w.messages.ide,
                              lambda doing, work: waiting(w, doing, work))

    def programs(self) -> list[ProgramInfo]:
        return self.commands.programs()

    def refresh(self) -> None:
        rows = self.programs()
        self.table.setRowCount(len(rows))
        for r, p in enumerate(rows):
            self.table.setItem(r, 0, QTableWidgetItem(str(p.number)))
            self.table.setItem(r, 1, QTableWidgetItem(p.name))
            # the manual's mark (DG 2727) is in the common fonts; "⦿" was not and showed as a missing glyph
            mark = QTableWidgetItem(AUTOSTART_MARK if p.autostart else "")
            mark.setToolTip("started when the controller is powered on" if p.autostart else "")
            self.table.setItem(r, 2, mark)
            source = QTableWidgetItem("✓" if p.source else "")
            source.setToolTip(f"stored {p.stored_at}" if p.stored_at else "stored without its source")
            self.table.setItem(r, 3, source)

    def selected_number(self) -> int | None:
        row = self.table.currentRow()
        return int(self.table.item(row, 0).text()) if row >= 0 else None

    def _build(self):
        """The current editor's program compiled (its errors marked there), or None."""
        outcome = self.w.development.compile_current()
        return outcome.result if outcome is not None else None

    def _storing(self) -> dict:
        """Save's settings: Settings ▸ Compiler's stack size, the files Include Sourcecode stores with it."""
        return {"stack_size": self.w.development.compiler_settings().stack_size,
                "source": self._source if self.include_source.isChecked() else None}

    def _stored(self, ok: bool) -> bool:
        if ok:
            self.refresh()
        return ok

    def store(self, *, number: int | None = None, name: str | None = None) -> bool:
        """Compile the current program into permanent memory: the next free number unless one is given."""
        return self._stored(self.commands.store(self._build, number=number, name=name, **self._storing()))

    def save(self) -> bool:
        return self._stored(self.commands.save(self._build, self._default_name(), **self._storing()))

    def save_as(self) -> bool:
        return self._stored(self.commands.save_as(self._build, self._default_name(), **self._storing()))

    def _default_name(self) -> str:
        """DG 2655: "confirm the file name suggested": the program's file name (a sample's, an unsaved one's tab
        name) without its extension, upper case and cut to the 8 characters a stored name has."""
        editor = self.w.current_editor()
        return Path(self.w.program_label(editor)).stem.upper()[:8] if editor is not None else ""

    def _source(self, result) -> dict[str, str]:
        """The program (first) and the include files it read, by file name."""
        editor = self.w.current_editor()
        files = {Path(self.w.program_label(editor)).name: editor.toPlainText()}
        for included in result.files[1:]:
            try:
                files[Path(included).name] = Path(included).read_text(encoding="utf-8")
            except OSError:
                continue  # a file it read a moment ago and cannot read now is left out, not fatal
        return files

    def upload(self, *, folder: Path | None = None) -> Path | None:
        """Upload (DG 2671-2675): the selected program opens in a new tab."""
        number = self.selected_number()
        if number is None:
            return None
        target = self.commands.upload(number, folder=folder)
        if target is not None:
            self.w.open_file(target)
        return target

    def start(self) -> bool:
        number = self.selected_number()
        return number is not None and self.commands.start(number)

    def autostart(self, on: bool) -> None:
        """Autostart on / off (DG 2719-2727)."""
        number = self.selected_number()
        if number is None:
            return
        self.commands.autostart(number, on)
        self.refresh()

    def delete(self) -> None:
        number = self.selected_number()
        if number is not None:
            self.commands.delete(number)
            self.refresh()

    def delete_all(self) -> None:
        self.commands.delete_all()
        self.refresh()


def show_programs(w) -> None:
    if w.development.connect_default():
        ProgramsDialog(w).exec()


def diagnostic_report(w, path: Path | None = None) -> bool:
    """Controller → Diagnostic Report (DG 3029-3031)."""
    return commands(w).diagnostic_report(path)
