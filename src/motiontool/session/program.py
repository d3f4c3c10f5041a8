"""Execute, Break, Continue and Execute now on a session's controller, without Qt (issue 27 item 5; DG 2054-2062,
2380-2391).

Execute's steps are the manual's: connect, ask whether the controller runs a program (and, if it does, whether to
stop it), compile, download to temporary memory, start. What the steps send runs through the session's `run` (the
IDE: off the GUI thread, I34), what they ask through its Prompts, what they say through `say`. The compiling is
the caller's (`build`: the IDE compiles its editor's text and marks the errors there), and so is the header's
test set-up (`test_setup`: the Test-settings and Test-inputs the user chose to apply).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

from motiontool.comms.client import ArrayInfo
from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError
from motiontool.program_header import TestSettings
from motiontool.session.prompts import Prompts
from motiontool.session.session import Runner, Session, run_here


class Image(Protocol):
    """A program as it is downloaded: an APOSS image, or a DPL program's source for the APC."""

    name: str

    def to_bytes(self) -> bytes: ...


@dataclass
class Program:
    image: Image
    stack_size: int | None = None                                  # None: the controller's own (DPL)
    dims: Sequence[tuple[str, Sequence[int]]] = ()                  # the program's DIM arrays, in order
    origin: object = None                                          # where it came from (the IDE: its editor)
    listing: object = None                                         # what Error History reads offsets from

    @property
    def file_name(self) -> str:
        return Path(self.image.name).name


@dataclass
class ProgramCommands:
    session: Session
    prompts: Prompts
    say: Callable[[str], None]
    run: Runner = run_here
    ran: dict[int, object] = field(default_factory=dict)       # controller ID -> origin of the program last started
    images: dict[int, object] = field(default_factory=dict)    # controller ID -> its listing (Error History)

    def _controller(self) -> tuple[int, Link]:
        link = self.session.link
        if link is None:
            raise LinkError("not connected")
        return self.session.controller_id, link

    def _wait(self, doing: str, work: Callable[[], Any]) -> Any:
        return self.run(f"Controller {self.session.controller_id}: {doing} …", work)

    def execute(self, build: Callable[[], Program | None], test_setup: Callable[[], TestSettings | None], *,
                ask: bool = True) -> bool:
        """F5 (DG 2380-2391). A failure is said, not raised; False when nothing was started."""
        if not self.session.connect_default(run=self.run):
            return False
        try:
            cid, link = self._controller()
            state = self._wait("asking its state", lambda: link.status().program_state)
            if state == "running":
                if ask and not self.prompts.confirm("Execute", "The controller is executing a program. Stop it?"):
                    return False
                self._wait("stopping its program", link.break_program)
            program = build()
            if program is None or not self._arrays_fit(link, program, ask=ask):
                return False
            test = test_setup()
            if test is None:
                return False

            def send() -> None:
                for key, value in test.settings:
                    link.write_parameter(key, value)
                link.download(program.image.to_bytes(), name=program.file_name, stack_size=program.stack_size)

            self._wait(f"downloading {program.file_name}", send)
            # noted before the start: its first events (an error's DIM line) arrive while the start is answered
            self.ran[cid] = program.origin
            self.images[cid] = program.listing
            self._wait("starting", lambda: link.start(inputs=test.inputs))
        except LinkError as exc:
            self.say(f"Controller {self.session.controller_id}: {exc}")
            return False
        self.say(f"Executing {program.file_name} on controller {cid}")
        return True

    def _arrays_fit(self, link: Link, program: Program, *, ask: bool) -> bool:
        """The controller keeps its DIM arrays for every program and a size never changes (CR 1042-1049), so a
        program whose DIM differs from an earlier one's stops with error 176 (170 when it skips one) before its
        first statement, and the error stays pending. Execute does not delete arrays behind the user's back (a
        program may rely on them, as sample 13 does; DG 2380-2391 names no such step): it says what clashes and
        offers Reset ▸ Arrays first (decision I20)."""
        if not program.dims:
            return True
        arrays = self._wait("reading its arrays", link.list_arrays)
        clash = dim_clash(arrays, program.dims)
        if clash is None or not ask:
            return True
        chosen = self.prompts.choose(
            "Execute", f"{clash}\n\nThe controller keeps DIM arrays for all programs and an array's size cannot "
            "change, so the program would stop with error 176 \"Array size wrong\". Delete the controller's arrays "
            "(Controller ▸ Reset ▸ Arrays) and execute?", ["Reset Arrays and Execute", "Execute Anyway"])
        if chosen == "Reset Arrays and Execute":
            self._wait("deleting its arrays", lambda: link.reset("arrays"))
            self.say(f"Controller {self.session.controller_id}: arrays deleted (Reset ▸ Arrays)")
            return True
        return chosen == "Execute Anyway"

    def break_program(self) -> None:
        """Esc (DG 2054-2062): without a controller it connects; with one it aborts the running program."""
        if not self.session.connected:
            self.session.connect_default(run=self.run)
            return
        self._request("stopping its program", lambda link: link.break_program())

    def continue_program(self) -> None:
        if self.session.connect_default(run=self.run):
            self._request("continuing", lambda link: link.continue_program())

    def execute_line(self, image: Image) -> None:
        """Command List ▸ Execute now: the line, compiled by the caller, runs as a one-line temporary program."""
        def run_once(link: Link) -> None:
            link.download(image.to_bytes(), name="command")
            link.start()

        if self.session.connect_default(run=self.run):
            self._request("executing the command", run_once)

    def _request(self, doing: str, action: Callable[[Link], Any]) -> None:
        try:
            _cid, link = self._controller()
            self._wait(doing, lambda: action(link))
        except LinkError as exc:
            self.say(f"Controller {self.session.controller_id}: {exc}")


def dim_clash(arrays: Sequence[ArrayInfo], dims: Sequence[tuple[str, Sequence[int]]]) -> str | None:
    """What in a program's DIM does not fit the controller's arrays (C:1024-1041: a prefix of the stored arrays
    with the same sizes, new ones appended), or None."""
    for k, (name, shape) in enumerate(dims):
        size = shape[0] * (shape[1] if len(shape) > 1 else 1)
        if k < len(arrays) and int(arrays[k].size) != size:
            return (f"This program's DIM {name}{''.join(f'[{d}]' for d in shape)} ({size} elements) is array "
                    f"{k + 1}, which the controller already has with {arrays[k].size} elements "
                    f"(\"{arrays[k].name}\", DIMmed by an earlier program).")
    return None
