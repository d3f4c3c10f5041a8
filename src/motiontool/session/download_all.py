"""Development ▸ Download all's steps, without Qt (issue 27 item 5; DG 2520-2524, 3276-3336): one program to
several controllers of the session's interface, each in turn:

1. stop a running program, 2. compile, 3. delete all programs, 4. download and save as program 0 under the
given name, 5. Verify: read it back and compare (a mismatch stops this controller), 6. Set Autostart, 7. Save
in EPROM, 8. Restart (power on). An error stops only the current controller; the summary names those that
failed ("Failed for controllers: 2"). With Verify on and Download off nothing is written: the program on the
controller is only compared.

What a step sends runs through `run` (the IDE: off the GUI thread, I34), the confirmation is asked through the
Prompts, the log is written through `say` (the IDE's dialog lets Stop be pressed between controllers there).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

from motiontool import __version__
from motiontool.aposs.driver import compile_source
from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError
from motiontool.session.prompts import Prompts
from motiontool.session.session import Runner, Session, run_here

_RANGE = re.compile(r"^\s*(\d+)\s*(?:-\s*(\d+))?\s*$")
OPTIONS = ("download", "verify", "autostart", "eprom", "restart")


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


@dataclass
class DownloadAll:
    session: Session
    prompts: Prompts
    say: Callable[[str], None]
    run: Runner = run_here
    stack_size: int | None = None                  # Settings ▸ Compiler's
    stopping: bool = False                         # Stop: no further controller is begun
    failed: list[int] = field(default_factory=list)
    succeeded: list[int] = field(default_factory=list)

    def _ask(self, cid: int, doing: str, work: Callable[[], Any]) -> Any:
        return self.run(f"Controller {cid}: {doing} …", work)

    def _link(self, cid: int) -> Link:
        return self.session.registry.link(cid, interface=self.session.interface_key)

    def start(self, file: str, controllers: str, name: str, options: Callable[[], Mapping[str, bool]]) -> bool:
        """Start (DG 3316-3336): `file` and `controllers` as typed, `name` the Program Name, `options` the check
        boxes by OPTIONS' keys as they are now (read again for each controller, as the dialog did before the
        move). True when no controller failed."""
        self.stopping, self.failed, self.succeeded = False, [], []
        self.say(f"motiontool {__version__} — Download Mode")
        try:
            ids = parse_ids(controllers)
        except ValueError as exc:
            self.say(str(exc))
            return False
        path = Path(file.strip())
        name = name.strip()[:8] or path.stem[:8]
        try:
            source = path.read_text(encoding="utf-8")
        except OSError as exc:
            self.say(f"{path}: {exc.strerror or exc}")
            return False
        result = compile_source(source, str(path), name=name)
        if not result.ok or result.image is None:   # an image only without errors
            for d in result.errors:
                self.say(d.format())
            self.say("Compilation failed: nothing downloaded")
            return False
        image = result.image.to_bytes()
        self.say(f"Compiled {path.name}: {len(image)} bytes")
        if options()["download"] and not self.confirm_deletion(ids, name):
            self.say("Cancelled: no program was deleted")
            return False
        for cid in ids:
            if self.stopping:
                self.say("Stopped")
                break
            (self.succeeded if self.process(cid, image, name, options(), file) else self.failed).append(cid)
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
                link = self._ask(cid, "connecting", partial(self._link, cid))
                programs = self._ask(cid, "listing its programs", link.list_programs)
            except (LinkError, ValueError):
                continue
            if programs:
                names = ", ".join(f"{p.number} {p.name}" for p in programs)
                stored.append(f"Controller {cid}: {names}")
        if not stored:
            return True
        return self.prompts.choose(
            "Download all", f"Download deletes all programs stored on the controllers before it saves \"{name}\" "
            "as program 0:", ["Delete and Download"], detail="\n".join(stored), warning=True,
            destructive=True) is not None

    def process(self, cid: int, image: bytes, name: str, opt: Mapping[str, bool], file: str) -> bool:
        """One controller's steps; an error stops this controller only (DG 3334)."""
        ask, stack = self._ask, self.stack_size
        try:
            link = ask(cid, "connecting", partial(self._link, cid))
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
                    self.say(f"Controller {cid}: verify failed: program 0 differs from {file}")
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
