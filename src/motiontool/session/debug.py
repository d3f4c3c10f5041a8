"""The debugger's state and requests on a session's controller, without Qt (issue 27 item 5; DG L2432-2450,
L3364-3382, L3440-3459).

A debug run is a program compiled with statement stops, downloaded and started stopped before its first
statement; Go runs to the next breakpoint, Singlestep one statement, End Debug stops the program and clears the
controller's breakpoints. This holds which image is being debugged and which of its lines can stop; the IDE's
Debugger shows it in the editor (the yellow line, the marks). Requests run through `run` (the IDE: off the GUI
thread, I34); a refused request is said through `say`, not raised.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError
from motiontool.session.prompts import Prompts
from motiontool.session.session import Runner, Session, run_here


def stop_lines(image: Any) -> frozenset[int]:
    """The lines of the program's own file where it can stop (the image's line table)."""
    return frozenset(e.line for e in image.lines if e.file == 0)


@dataclass
class DebugSession:
    session: Session
    say: Callable[[str], None]
    run: Runner = run_here
    prompts: Prompts | None = None         # asks before a running program is stopped; without it, it is not
    image: Any = None                      # the debug image on the controller, None outside a debug run
    lines: frozenset[int] = frozenset()

    @property
    def active(self) -> bool:
        return self.image is not None

    def _wait(self, doing: str, work: Callable[[], Any]) -> Any:
        return self.run(f"Controller {self.session.controller_id}: {doing} …", work)

    def _report(self, exc: Exception) -> None:
        self.say(f"Controller {self.session.controller_id}: {exc}")

    def prepare(self, image: Any, stack_size: int, loaded: Callable[[frozenset[int]], Sequence[int]]) -> bool:
        """Prepare Singlestep's requests: stop a running program if the user agrees (as Execute asks, DG 2385),
        download `image`, then (after `loaded` was told the stop lines and gave the breakpoints among them) set the
        breakpoints and start it stopped. False, with the controller as it was, when the user keeps the program."""
        link = self.session.link
        if link is None:
            self._report(LinkError("not connected"))
            return False
        size = len(image.to_bytes())
        try:
            running = self._wait("asking its state", lambda: link.status().program_state) == "running"
        except LinkError as exc:
            self._report(exc)
            return False
        if running:
            if self.prompts is None:
                self._report(LinkError("it is executing a program: stop it first"))
                return False
            if not self.prompts.confirm("Prepare Singlestep", "The controller is executing a program. Stop it?"):
                return False

        def send() -> None:
            if running:
                link.break_program()
            link.download(image.to_bytes(), name=image.name, stack_size=stack_size)

        try:
            self._wait(f"downloading {Path(image.name).name} for debugging", send)
            self.say(f"Loading {size} bytes ok")
            marks = list(loaded(stop_lines(image)))

            def start() -> None:
                link.set_breakpoints(marks)
                link.start(step=True)

            self._wait("starting it before its first statement", start)
        except LinkError as exc:
            self._report(exc)
            return False
        self.image, self.lines = image, stop_lines(image)
        return True

    def go(self) -> None:
        """Go (DG L2436-2438): run to the next breakpoint."""
        self.request("running to the next breakpoint", lambda link: link.continue_program())

    def step(self) -> None:
        """Singlestep (DG L2440-2442): run the current statement, stop before the next one."""
        self.request("stepping", lambda link: link.step())

    def set_breakpoints(self, lines: Sequence[int]) -> None:
        marks = [n for n in lines if n in self.lines]
        self.request("setting the breakpoints", lambda link: link.set_breakpoints(marks))

    def end(self) -> None:
        """End Debug's requests (DG L2448-2450): stop the program, clear the controller's breakpoints."""
        self.image, self.lines = None, frozenset()
        link = self.session.link
        if link is None:
            return

        def stop() -> None:
            if link.status().program_state in ("running", "break"):
                link.break_program()
            link.set_breakpoints([])

        try:
            self._wait("ending the debug session", stop)
        except LinkError as exc:
            self._report(exc)

    def request(self, doing: str, action: Callable[[Link], Any]) -> None:
        link = self.session.link
        if link is None:
            self._report(LinkError("not connected"))
            return
        try:
            self._wait(doing, lambda: action(link))
        except LinkError as exc:
            self._report(exc)

    def read_value(self, name: str) -> Any:
        """A variable's value for the editor's popup; None when it cannot be read (not a variable, no link)."""
        link = self.session.link
        if link is None:
            return None
        try:
            return self._wait(f"reading {name}", lambda: link.read_variables([name])[0])
        except LinkError:
            return None

    def write_value(self, name: str, value: int | float) -> bool:
        link = self.session.link
        if link is None:
            self._report(LinkError("not connected"))
            return False
        try:
            self._wait(f"writing {name}", lambda: link.write_variable(name, value))
        except LinkError as exc:
            self._report(exc)
            return False
        return True
