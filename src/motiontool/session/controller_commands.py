"""The Controller menu's commands on a session's controller, without Qt (issue 27 item 5; DG 2627-2794, 2884-2980,
3029-3031): Parameters ▸ Save to file / Restore from file, Reset ▸, Memory ▸, Diagnostic Report and the Programs
dialog's Save, Save as, Upload, Start, Autostart, Delete and Delete all.

As in session/program.py, what a command sends runs through the session's `run` (the IDE: off the GUI thread, I34),
what it asks through its Prompts, what it says through `say`. The dialogs (which controller and which sets to
restore, the table of stored programs and its selection) are the caller's.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any, cast

from motiontool.comms.client import ProgramInfo
from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError
from motiontool.fileio import atomic_write_text, reason, write_error
from motiontool.session.prompts import Prompts
from motiontool.session.session import Runner, Session, run_here

RESET_ENTRIES = (("Parameter", "parameters", "global and axis parameters go back to their defaults"),
                 ("Arrays", "arrays", "all arrays in the controller are deleted (like DELETE ARRAYS)"),
                 ("User Parameters", "user", "the user parameters 19-xx go back to their defaults"),
                 ("Complete", "all", "parameters, arrays and stored programs: an immediate factory reset"))
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
CONFIG_FILTER = "Configuration (*.zbc *.cnf)"


def config_io() -> tuple[ModuleType, ModuleType]:
    """The .zbc reader/writer and the transfer, imported on first use: they pull in the curve maths (scipy),
    which would add about a second to the IDE's start."""
    from motiontool.cameditor import transfer
    from motiontool.formats import zbc

    return transfer, zbc


@dataclass
class _Commands:
    session: Session
    prompts: Prompts
    say: Callable[[str], None]
    run: Runner = run_here

    def _wait(self, doing: str, work: Callable[[], Any], controller_id: int | None = None) -> Any:
        cid = self.session.controller_id if controller_id is None else controller_id
        return self.run(f"Controller {cid}: {doing} …", work)

    def _held(self) -> Link:
        """The window's controller, which the command's dialog was opened for."""
        if self.session.link is None:
            raise LinkError("not connected")
        return self.session.link


@dataclass
class ControllerCommands(_Commands):
    """Parameters ▸, Reset ▸, Memory ▸ and Diagnostic Report; each connects first (DG 2054-2062)."""

    def _link(self) -> Link | None:
        return self.session.link if self.session.connect_default(run=self.run) else None

    def _write_failed(self, title: str, path: Path, exc: OSError) -> None:
        self.say(f"{title}: {write_error(path, exc)}")
        self.prompts.warn(title, f"Cannot write {path}:\n{reason(exc)}.",
                          detail="Nothing on the controller was changed.", critical=True)

    def save_parameters(self, path: Path | None = None) -> bool:
        """Parameters ▸ Save to file (DG 2884-2892): global, axis and user parameters, the FC 300's changed
        parameters (C19) and all arrays → .zbc."""
        transfer, zbc = config_io()
        return self._to_file("Save to file", path, ("controller.zbc", CONFIG_FILTER), "reading its configuration",
                             transfer.upload_config, zbc.write_config, "configuration saved to")

    def _to_file(self, title: str, path: Path | None, offer: tuple[str, str], doing: str,
                 read: Callable[[Link], Any], write: Callable[[Path, Any], None], done: str) -> bool:
        """A command that writes what it reads from the controller into a file: connect, ask where (`offer`:
        the suggested name and the filters), read off the caller's thread, write; a file not written is said
        with a warning, a refused read in the Communication pane."""
        link = self._link()
        if link is None:
            return False
        if path is None:
            path = self.prompts.save_path(title, *offer)
            if path is None:
                return False
        zbc = config_io()[1]
        try:
            write(path, self._wait(doing, lambda: read(link)))
        except OSError as exc:
            self._write_failed(title, path, exc)
            return False
        except (LinkError, zbc.ConfigError) as exc:
            self.say(f"{title}: {exc}")
            return False
        self.say(f"Controller {self.session.controller_id}: {done} {path}")
        return True

    def restore_parameters(self, path: Path | None = None, controller_id: int | None = None,
                           sets: tuple[str, ...] | None = None, *,
                           choose: Callable[[Path], tuple[int, tuple[str, ...]] | None] | None = None) -> bool:
        """Parameters ▸ Restore from file (DG 2894-2900): an Open dialog, then the target controller and the sets
        (`choose`, the caller's dialog; without one the session's controller and every set)."""
        if path is None:
            path = self.prompts.open_path("Restore from file", "", CONFIG_FILTER)
            if path is None:
                return False
        transfer, zbc = config_io()
        try:
            config = zbc.read_config(path)
        except zbc.ConfigError as exc:  # the file is refused with its line; the controller is untouched
            self.say(f"Restore from file: {exc}")
            return False
        if controller_id is None or sets is None:
            if choose is None:
                controller_id, sets = self.session.controller_id, tuple(transfer.SETS)
            else:
                chosen = choose(path)
                if chosen is None:
                    return False
                controller_id, sets = chosen
        cid, names = controller_id, sets
        registry, key = self.session.registry, self.session.interface_key
        try:
            self._wait(f"restoring {', '.join(names) or 'nothing'}",
                       lambda: transfer.download_config(registry.link(cid, interface=key), config, names), cid)
        except (LinkError, zbc.ConfigError, ValueError) as exc:
            self.say(f"Restore from file: controller {cid}: {exc}")
            return False
        self.say(f"Controller {cid}: restored {', '.join(names) or 'nothing'} from {path}")
        return True

    def reset(self, what: str, ask: bool = True) -> bool:
        """Reset ▸ (DG 2948-2980): each entry acts immediately after one confirmation."""
        title, _key, effect = next(e for e in RESET_ENTRIES if e[1] == what)
        link = self._link()
        if link is None:
            return False
        if ask and not self.prompts.confirm(f"Reset {title}", f"Reset {title}: {effect}. Continue?"):
            return False
        try:
            self._wait(f"reset {title.lower()}", lambda: link.reset(what))
        except LinkError as exc:
            self.say(f"Reset {title}: {exc}")
            return False
        self.say(f"Controller {self.session.controller_id}: reset {title.lower()} done")
        return True

    def memory(self, what: str, *, ask: bool = True) -> bool:
        """Memory ▸ (DG 2908-2946): each entry after one confirmation."""
        title, _key, effect = next(e for e in MEMORY_ENTRIES if e[1] == what)
        link = self._link()
        if link is None:
            return False
        if ask and not self.prompts.confirm(title, f"{title}: {effect}. Continue?"):
            return False
        try:
            self._wait(title, link.delete_eprom if what == "delete" else lambda: link.save_memory(what))
        except LinkError as exc:
            self.say(f"{title}: {exc}")
            return False
        self.say(f"Controller {self.session.controller_id}: {title} done"
                 + (" (takes effect at the next power on)" if what == "delete" else ""))
        return True

    def diagnostic_report(self, path: Path | None = None) -> bool:
        """Diagnostic Report (DG 3029-3031) into a text file."""
        cid = self.session.controller_id
        return self._to_file("Diagnostic Report", path, ("diagnostic-report.txt", "Text (*.txt)"),
                             "reading its state for the report", lambda link: diagnostic_report_text(link, cid),
                             atomic_write_text, "diagnostic report written to")


def diagnostic_report_text(link: Link, controller_id: int) -> str:
    """Controller ▸ Diagnostic Report (DG 3029-3031): the controller's entire current state as text for
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
    lines += ["", "[configuration]", config_text(config_io()[0].upload_config(link))]
    return "\n".join(lines) + "\n"


@dataclass
class StoredPrograms(_Commands):
    """Controller ▸ Programs (DG 2627-2794): the programs stored on the window's controller. The caller's dialog
    shows them and says which one is selected; the IDE gives it prompts over the dialog."""

    def programs(self) -> list[ProgramInfo]:
        link = self.session.link
        return self._wait("listing its programs", link.list_programs) if link is not None else []

    def store(self, build: Callable[[], Any], *, number: int | None = None, name: str | None = None,
              source: Callable[[Any], dict[str, str]] | None = None, stack_size: int | None = None) -> bool:
        """Compile (`build`: a compile result or None) into permanent memory: the next free number unless one is
        given; `source`: the files Include Sourcecode stores with it (DG 2643-2669)."""
        result = build()
        if result is None or not result.ok:
            self.say("Programs: the program has errors and was not saved")
            return False
        used = {p.number for p in self.programs()}
        if number is None:
            number = next((n for n in PROGRAM_NUMBERS if n not in used), None)
            if number is None:
                self.say("Programs: all 91 program numbers are used")
                return False
        image = result.image
        files = source(result) if source is not None else None
        slot = number
        try:
            link = self._held()
            self._wait(f"saving program {slot}", lambda: link.download(
                image.to_bytes(), number=slot, name=(name or image.name)[:8], source=files, stack_size=stack_size))
        except LinkError as exc:
            self.say(f"Programs: {exc}")
            return False
        return True

    def save(self, build: Callable[[], Any], default_name: str, **store: Any) -> bool:
        """Save (DG 2643-2655): the name asked, the next free number."""
        name = self.prompts.text("Save", "Program name (8 characters):", default=default_name)
        return name is not None and self.store(build, name=name, **store)

    def save_as(self, build: Callable[[], Any], default_name: str, **store: Any) -> bool:
        """Save as: the name and the number asked."""
        name = self.prompts.text("Save as", "Program name (8 characters):", default=default_name)
        if name is None:
            return False
        number = self.prompts.integer("Save as", "Program number (0-90):", 0, 0, 90)
        return number is not None and self.store(build, number=number, name=name, **store)

    def upload(self, number: int, *, folder: Path | None = None) -> Path | None:
        """Upload (DG 2671-2675): only for a program stored with its source; the suggested name carries the time
        it was stored. Its include files are written beside it; the caller opens the program."""
        try:
            link = self._held()
            stored = self._wait(f"uploading program {number}", lambda: link.upload_source(number))
        except LinkError as exc:
            self.say(f"Upload: {exc}")
            return None
        main = Path(stored.main)
        stamp = stored.stored_at.replace(":", "").replace("-", "").replace(" ", "_")
        suggested = f"{main.stem}_{stamp}{main.suffix or '.m'}"
        if folder is None:
            chosen = self.prompts.save_path("Upload program", suggested, "APOSS programs (*.m)")
            if chosen is None:
                return None
            target = chosen
        else:
            target = Path(folder) / suggested
        try:
            for name, text in stored.files.items():
                path = target if name == stored.main else target.parent / Path(name).name
                if path != target and path.exists() and path.read_text(encoding="utf-8") != text:
                    path = path.with_name(f"{path.stem}_{stamp}{path.suffix}")  # the user's own file stays
                    self.say(f"Upload: {name} differs from the file beside it: written as {path.name}")
                atomic_write_text(path, text)
        except OSError as exc:
            self.say(f"Upload: {target}: {exc.strerror or exc}")
            return None
        self.say(f"Program {number} uploaded to {target}")
        return target

    def start(self, number: int) -> bool:
        try:
            link = self._held()
            self._wait(f"starting program {number}", lambda: link.start(number))
        except LinkError as exc:
            self.say(f"Programs: {exc}")
            return False
        return True

    def autostart(self, number: int, on: bool) -> None:
        """Autostart on / off (DG 2719-2727): one program at most carries the mark."""
        current = next((p.number for p in self.programs() if p.autostart), None)
        if on or current == number:
            link = self._held()
            self._wait("setting Autostart", lambda: link.set_autostart(number if on else None))

    def delete(self, number: int) -> None:
        link = self._held()
        self._wait(f"deleting program {number}", lambda: link.delete_program(number))

    def delete_all(self) -> None:
        # every listed number is sent, as before the move: the APC's one unnumbered DPL program too
        numbers, link = [cast(int, p.number) for p in self.programs()], self.session.link

        def delete() -> None:
            for n in numbers:   # none when the link is gone: the programs() above listed none
                if link is not None:
                    link.delete_program(n)

        self._wait("deleting its programs", delete)
