"""Controller menu (ide-spec 2.15-2.30, DG 2613-2980): Programs, Parameters ▸ Save to file / Restore from file,
Reset ▸.  Every action goes through a comms Link of the window's controller registry."""

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
from motiontool.comms.protocol import LinkError
from motiontool.session.controllers import SIMULATED_IDS
from motiontool.ui.link_jobs import waiting

SET_LABELS = {"global": "Global parameters", "axis": "Axis parameters", "user": "User parameters",
              "drive": "FC 300 drive parameters", "arrays": "Arrays"}
RESET_ENTRIES = (("Parameter", "parameters", "global and axis parameters go back to their defaults"),
                 ("Arrays", "arrays", "all arrays in the controller are deleted (like DELETE ARRAYS)"),
                 ("User Parameters", "user", "the user parameters 19-xx go back to their defaults"),
                 ("Complete", "all", "parameters, arrays and stored programs: an immediate factory reset"))
AUTOSTART_MARK = "\u2299"  # ⊙, DG 2727
PROGRAM_NUMBERS = range(0, 91)  # DG 2627-2639: up to 91 programs, numbers 0-90
# Memory ▸ (DG 2908-2946): the older controllers' Save RAM / Delete EPROM and the MCO 305's four entries
MEMORY_ENTRIES = (("Save RAM", "ram", "programs, parameters and arrays are copied from RAM to the EPROM (like "
                   "SAVEPROM)"),
                  ("Delete EPROM", "delete", "the EPROM is erased: the controller starts with its factory settings "
                   "at the next power on. Back up the programs and the configuration first (Parameters → Save to "
                   "file)"),
                  ("User Parameters → EPROM", "user", "the user parameters 19-xx are saved in the EPROM"),
                  ("Arrays → EPROM", "arrays", "the arrays are saved in the EPROM"),
                  ("All App. Data → EPROM", "app", "parameters and arrays are saved in the EPROM"),
                  ("Option Parameters → EPROM", "option", "the option's parameters 32-xx and 33-xx are saved in "
                   "the EPROM"))


def _config_io():
    """The .zbc reader/writer and the transfer, imported on first use: they pull in the curve maths (scipy),
    which would add about a second to the IDE's start."""
    from motiontool.cameditor import transfer
    from motiontool.formats import zbc

    return transfer, zbc



def _link(w, controller_id: int | None = None):
    if controller_id is None:
        return w.bridge.link if w.development.connect_default() else None
    return w.controllers.link(controller_id, interface=w.connection.interface_key)


def _write_failed(w, title: str, path: Path, exc: OSError) -> None:
    from motiontool.fileio import write_error
    from motiontool.ui.file_errors import save_failed

    w.messages.ide(f"{title}: {write_error(path, exc)}")
    save_failed(w, title, path, exc, "Nothing on the controller was changed.")


def save_parameters(w, path: Path | None = None) -> bool:
    """Parameters → Save to file (DG 2884-2892): global, axis and user parameters, the FC 300's changed
    parameters (C19) and all arrays → .zbc."""
    link = _link(w)
    if link is None:
        return False
    if path is None:
        path = w.prompts.save_path("Save to file", "controller.zbc", "Configuration (*.zbc *.cnf)")
        if path is None:
            return False
    transfer, zbc = _config_io()
    try:
        config = waiting(w, f"Controller {w.bridge.controller_id}: reading its configuration …",
                         lambda: transfer.upload_config(link))
        zbc.write_config(path, config)
    except OSError as exc:
        _write_failed(w, "Save to file", path, exc)
        return False
    except (LinkError, zbc.ConfigError) as exc:
        w.messages.ide(f"Save to file: {exc}")
        return False
    w.messages.ide(f"Controller {w.bridge.controller_id}: configuration saved to {path}")
    return True


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
        self.checks = {name: QCheckBox(SET_LABELS[name]) for name in _config_io()[0].SETS}
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
    if path is None:
        path = w.prompts.open_path("Restore from file", "", "Configuration (*.zbc *.cnf)")
        if path is None:
            return False
    transfer, zbc = _config_io()
    try:
        config = zbc.read_config(path)
    except zbc.ConfigError as exc:  # the file is refused with its line; the controller is untouched
        w.messages.ide(f"Restore from file: {exc}")
        return False
    if controller_id is None or sets is None:
        dialog = RestoreDialog(w, path, w.bridge.controller_id)
        if not dialog.exec():
            return False
        controller_id, sets = dialog.controller_id(), dialog.sets()
    try:
        waiting(w, f"Controller {controller_id}: restoring {', '.join(sets) or 'nothing'} …", lambda: transfer.
                download_config(w.controllers.link(controller_id, interface=w.connection.interface_key), config, sets))
    except (LinkError, zbc.ConfigError, ValueError) as exc:
        w.messages.ide(f"Restore from file: controller {controller_id}: {exc}")
        return False
    w.messages.ide(f"Controller {controller_id}: restored {', '.join(sets) or 'nothing'} from {path}")
    return True


def reset(w, what: str, ask: bool = True) -> bool:
    """Controller → Reset ▸ (DG 2948-2980): each entry acts immediately after one confirmation."""
    title, _key, effect = next(e for e in RESET_ENTRIES if e[1] == what)
    link = _link(w)
    if link is None:
        return False
    if ask and not w.prompts.confirm(f"Reset {title}", f"Reset {title}: {effect}. Continue?"):
        return False
    try:
        waiting(w, f"Controller {w.bridge.controller_id}: reset {title.lower()} …", lambda: link.reset(what))
    except LinkError as exc:
        w.messages.ide(f"Reset {title}: {exc}")
        return False
    w.messages.ide(f"Controller {w.bridge.controller_id}: reset {title.lower()} done")
    return True


def memory(w, what: str, *, ask: bool = True) -> bool:
    """Controller → Memory ▸ (DG 2908-2946): each entry after one confirmation."""
    title, _key, effect = next(e for e in MEMORY_ENTRIES if e[1] == what)
    link = _link(w)
    if link is None:
        return False
    if ask and not w.prompts.confirm(title, f"{title}: {effect}. Continue?"):
        return False
    try:
        waiting(w, f"Controller {w.bridge.controller_id}: {title} …",
                link.delete_eprom if what == "delete" else lambda: link.save_memory(what))
    except LinkError as exc:
        w.messages.ide(f"{title}: {exc}")
        return False
    w.messages.ide(f"Controller {w.bridge.controller_id}: {title} done"
                   + (" (takes effect at the next power on)" if what == "delete" else ""))
    return True


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
    def link(self):
        return self.w.bridge.link

    def _ask(self, doing: str, work):
        """One exchange on a thread; the window paints and says what it waits for (issue 27 item 2)."""
        return waiting(self.w, f"Controller {self.w.bridge.controller_id}: {doing} …", work)

    def programs(self) -> list[ProgramInfo]:
        link = self.link
        return self._ask("listing its programs", link.list_programs) if link is not None else []

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

    def store(self, *, number: int | None = None, name: str | None = None) -> bool:
        """Compile the current program into permanent memory: the next free number unless one is given."""
        outcome = self.w.development.compile_current()
        if outcome is None or not outcome.result.ok:
            self.w.messages.ide("Programs: the program has errors and was not saved")
            return False
        used = {p.number for p in self.programs()}
        if number is None:
            number = next((n for n in PROGRAM_NUMBERS if n not in used), None)
            if number is None:
                self.w.messages.ide("Programs: all 91 program numbers are used")
                return False
        image = outcome.result.image
        source = self._source(outcome.result) if self.include_source.isChecked() else None
        link, stack = self.link, self.w.development.compiler_settings().stack_size
        try:
            self._ask(f"saving program {number}", lambda: link.download(
                image.to_bytes(), number=number, name=(name or image.name)[:8], source=source, stack_size=stack))
        except LinkError as exc:
            self.w.messages.ide(f"Programs: {exc}")
            return False
        self.refresh()
        return True

    def save(self) -> bool:
        name = self.w.prompts.within(self).text("Save", "Program name (8 characters):", default=self._default_name())
        return name is not None and self.store(name=name)

    def save_as(self) -> bool:
        prompts = self.w.prompts.within(self)
        name = prompts.text("Save as", "Program name (8 characters):", default=self._default_name())
        if name is None:
            return False
        number = prompts.integer("Save as", "Program number (0-90):", 0, 0, 90)
        return number is not None and self.store(number=number, name=name)

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
        """Upload (DG 2671-2675): only for a program stored with its source; the suggested name carries the time
        it was stored. The program opens in a new tab; its include files are written beside it."""
        number = self.selected_number()
        if number is None:
            return None
        try:
            link = self.link
            stored = self._ask(f"uploading program {number}", lambda: link.upload_source(number))
        except LinkError as exc:
            self.w.messages.ide(f"Upload: {exc}")
            return None
        main = Path(stored.main)
        stamp = stored.stored_at.replace(":", "").replace("-", "").replace(" ", "_")
        suggested = f"{main.stem}_{stamp}{main.suffix or '.m'}"
        if folder is None:
            chosen = self.w.prompts.within(self).save_path("Upload program", suggested, "APOSS programs (*.m)")
            if chosen is None:
                return None
            target = chosen
        else:
            target = Path(folder) / suggested
        from motiontool.fileio import atomic_write_text

        try:
            for name, text in stored.files.items():
                path = target if name == stored.main else target.parent / Path(name).name
                if path != target and path.exists() and path.read_text(encoding="utf-8") != text:
                    path = path.with_name(f"{path.stem}_{stamp}{path.suffix}")  # the user's own file stays
                    self.w.messages.ide(f"Upload: {name} differs from the file beside it: written as {path.name}")
                atomic_write_text(path, text)
        except OSError as exc:
            self.w.messages.ide(f"Upload: {target}: {exc.strerror or exc}")
            return None
        self.w.messages.ide(f"Program {number} uploaded to {target}")
        self.w.open_file(target)
        return target

    def start(self) -> bool:
        number = self.selected_number()
        if number is None:
            return False
        try:
            link = self.link
            self._ask(f"starting program {number}", lambda: link.start(number))
        except LinkError as exc:
            self.w.messages.ide(f"Programs: {exc}")
            return False
        return True

    def autostart(self, on: bool) -> None:
        """Autostart on / off (DG 2719-2727): one program at most carries the mark."""
        number = self.selected_number()
        if number is None:
            return
        current = next((p.number for p in self.programs() if p.autostart), None)
        if on or current == number:
            link = self.link
            self._ask("setting Autostart", lambda: link.set_autostart(number if on else None))
        self.refresh()

    def delete(self) -> None:
        number = self.selected_number()
        if number is not None:
            link = self.link
            self._ask(f"deleting program {number}", lambda: link.delete_program(number))
            self.refresh()

    def delete_all(self) -> None:
        numbers, link = [p.number for p in self.programs()], self.link
        self._ask("deleting its programs", lambda: [link.delete_program(n) for n in numbers])
        self.refresh()


def show_programs(w) -> None:
    if w.development.connect_default():
        ProgramsDialog(w).exec()


def diagnostic_report_text(link, controller_id: int) -> str:
    """Controller → Diagnostic Report (DG 3029-3031): the controller's entire current state as text for
    support: identity, status, error history, programs, every parameter and every array."""
    from motiontool.formats.zbc import config_text
    from motiontool.paramdb import database

    ident = link.identify()
    status = link.status()
    lines = [f"# motiontool diagnostic report, controller {controller_id}",
             f"product: {ident.product}", f"firmware: {ident.firmware}", f"protocol: {ident.protocol}",
             "", "[status]"]
    lines += [f"{key} = {value}" for key, value in status.to_dict().items()]
    lines += ["", "[error history]"]
    history = link.error_history()
    lines += [f"{e.time_ms} ms  error {e.number}: {e.text}" + (f" (line {e.line})" if e.line else "")
              for e in history] or ["none"]
    lines += ["", "[programs]"]
    lines += [f"{p.number}: {p.name}" for p in link.list_programs()] or ["none"]
    lines += ["", "[readouts]"]
    for p in database():
        if p.read_only:
            try:
                lines.append(f"{p.label} = {link.read_parameter(p.number)}")
            except LinkError as exc:
                lines.append(f"{p.label} = ? ({exc})")
    lines += ["", "[configuration]", config_text(_config_io()[0].upload_config(link))]
    return "\n".join(lines) + "\n"


def diagnostic_report(w, path: Path | None = None) -> bool:
    link = _link(w)
    if link is None:
        return False
    if path is None:
        path = w.prompts.save_path("Diagnostic Report", "diagnostic-report.txt", "Text (*.txt)")
        if path is None:
            return False
    from motiontool.fileio import atomic_write_text

    zbc = _config_io()[1]
    try:
        text = waiting(w, f"Controller {w.bridge.controller_id}: reading its state for the report …",
                       lambda: diagnostic_report_text(link, w.bridge.controller_id))
        atomic_write_text(path, text)
    except OSError as exc:
        _write_failed(w, "Diagnostic Report", path, exc)
        return False
    except (LinkError, zbc.ConfigError) as exc:
        w.messages.ide(f"Diagnostic Report: {exc}")
        return False
    w.messages.ide(f"Controller {w.bridge.controller_id}: diagnostic report written to {path}")
    return True
