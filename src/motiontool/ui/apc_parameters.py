"""Parameters ▸ APC (Unidrive SP): the drive and SM-Applications parameters an APC program uses, by menu (1-6, 18,
19, 20, 81, 90, 91), with the APC user guide's names, units, ranges and defaults (apc/parameter_menus.py, decision
A75), read from and written to the simulated APC, the controller the IDE runs DPL programs on (A68).

As in Parameters ▸ Drive (FC 300) (ui/parameter_pages.py): reads and writes run off the GUI thread, a typed value
is checked at once and refused with the reason, OK writes only the changed values. Readouts (menu 90's encoder
views, 91.06 …) are greyed and read again with Refresh. Save to file writes the writable values shown; Restore
from file takes a file's values as changes to write with OK (docs/formats/apc-parameters.md): a bad file changes
nothing and says which line is wrong."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import QHBoxLayout, QLabel, QPushButton

from motiontool.apc.parameter_menus import MENUS, ApcParam, checked, dump, load
from motiontool.fileio import MiB, atomic_write_text, read_text, reason, write_error
from motiontool.session.controllers import APC_SIM, InterfaceConfig
from motiontool.ui.parameter_pages import ParameterPages, Row

COLUMNS = ("Par.", "Name", "Value", "Units", "Range", "Default")
FILTER = "APC parameters (*.apcpar);;All files (*)"
MAX_FILE = MiB   # a parameter file is a few kB: anything larger is not one
APC = InterfaceConfig(kind=APC_SIM, first=1, last=1)


def apc_link(w):
    """The simulated APC's link: the one the window runs DPL programs on (the interface is opened if need be)."""
    w.controllers.open_interface(config=APC)
    return w.controllers.link(1, interface=APC.key)


class ApcParametersDialog(ParameterPages):
    def __init__(self, w, parent=None) -> None:
        super().__init__(parent or w)
        self.w = w
        self.setWindowTitle("APC Parameters (Unidrive SP + SM-Applications)")
        self.link = apc_link(w)
        for title, params in MENUS:
            self.add_group(title, title, COLUMNS, [(p.label, p) for p in params], self._cells, self._tooltip)
        self.groups.setFixedWidth(self.groups.sizeHintForColumn(0) + 2 * self.groups.frameWidth() + 12)
        self.save_button, self.restore_button = QPushButton("Save to file..."), QPushButton("Restore from file...")
        self.save_button.clicked.connect(lambda: self.save_dialog())
        self.restore_button.clicked.connect(lambda: self.restore_dialog())
        top = QHBoxLayout()
        top.addWidget(QLabel("Controller 1: APC simulator"), 1)
        for button in (self.save_button, self.restore_button, self.refresh):
            top.addWidget(button)
        self.lay_out(top, 1060, 560)

    @staticmethod
    def _cells(p: ApcParam) -> tuple[str, ...]:
        rng = f"{p.low} .. {p.high}" if p.printed_range else "any (32-bit)"
        return p.label, p.name, "", p.units, rng, p.default

    @staticmethod
    def _tooltip(p: ApcParam) -> str:
        where = f"seed 004 {p.source}" if p.source.startswith("L") else p.source or "menu of the Unidrive SP"
        rng = "" if p.printed_range else "\nrange: the APC guide prints none; any signed 32-bit value (decision A75)"
        return f"#{p.label} {p.name}\nsource: {where}" + rng + ("\nread only" if p.read_only else "")

    def shown(self, p: ApcParam, raw: int) -> str:
        return str(raw)

    def parse(self, row: Row) -> int:
        return checked(row.p, row.item.text())

    def busy_widgets(self) -> list:
        return [self.ok, self.refresh, self.save_button, self.restore_button]

    # --- reading and writing (link-jobs thread) ----------------------------------------------------------------
    def read(self) -> None:
        link, labels = self.link, list(self.rows)
        self._busy("Controller 1: reading the APC's parameters …")
        self.jobs.run(lambda: {label: link.read_parameter(label) for label in labels},
                      lambda result: self._loaded(1, result))

    def accept(self) -> None:
        if self.refused():
            self.say("Not written: " + "; ".join(self.refused()), error=True)
            return
        values = self.pending()
        if not values:
            super().accept()
            return
        link, labels = self.link, list(self.rows)

        def work():
            for label, value in values.items():
                link.write_parameter(label, value)
            return {label: link.read_parameter(label) for label in labels}

        def done(result) -> None:
            self._loaded(1, result)
            if not isinstance(result, Exception):
                self.w.messages.ide("Controller 1 (APC): wrote " + ", ".join(f"#{k} = {v}" for k, v in values.items()))
                super(ApcParametersDialog, self).accept()

        self._busy("Controller 1: writing " + ", ".join(f"#{k}" for k in values) + " …")
        self.jobs.run(work, done)

    # --- file ----------------------------------------------------------------------------------------------------
    def shown_values(self) -> dict[str, int]:
        """The writable values as shown: a changed one as typed, else as read."""
        out = {}
        for label, row in self.rows.items():
            value = row.pending if row.pending is not None else row.current
            if value is not None and not row.p.read_only:
                out[label] = value
        return out

    def save_to(self, path: Path | str) -> bool:
        values = self.shown_values()
        try:
            atomic_write_text(path, dump(values))
        except OSError as exc:
            self.say(write_error(path, exc), error=True)
            return False
        self.say(f"Saved {len(values)} values to {path}")
        return True

    def restore_from(self, path: Path | str) -> bool:
        """The file's values become changes (OK writes them); a bad file changes nothing."""
        try:
            values = load(read_text(path, MAX_FILE, "APC parameter file"), str(path))
        except OSError as exc:
            self.say(f"cannot read {path}: {reason(exc)}", error=True)
            return False
        except UnicodeDecodeError:
            self.say(f"{path}: not a text file (UTF-8)", error=True)
            return False
        except ValueError as exc:
            self.say(str(exc), error=True)
            return False
        for label, value in values.items():
            self.set_pending(label, value)
        changed = sum(1 for label in values if self.rows[label].pending is not None)
        self.say(f"{path}: {len(values)} values, {changed} differ from the drive's: OK writes them")
        return True

    def save_dialog(self) -> bool:
        path = self.w.prompts.within(self).save_path("Save APC parameters", "apc.apcpar", FILTER)
        return path is not None and self.save_to(path)

    def restore_dialog(self) -> bool:
        path = self.w.prompts.within(self).open_path("Restore APC parameters", "", FILTER)
        return path is not None and self.restore_from(path)


def show_apc_parameters(w) -> None:
    """Controller ▸ Parameters ▸ APC (Unidrive SP)..."""
    dialog = ApcParametersDialog(w)
    dialog.exec()
    dialog.deleteLater()

