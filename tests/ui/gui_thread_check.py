"""The link scheme of the GUI-thread rule tests (test_link_off_gui_thread*.py, issue 27 item 2): each of its
controllers is an embedded simulator whose every request (and the opening of the link, and the scan of the interface)
notes whether it ran on the GUI thread; `HOLD` keeps a request on the line as long as a test wants (a slow line).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass

import pytest
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QApplication

from motiontool.comms import links
from motiontool.comms.link import Link
from motiontool.comms.links import open_link, register_link_scheme
from motiontool.session.controllers import InterfaceConfig

SCHEME = "gui-thread-check"
PROGRAM = "x = 1\nPRINT \"ran \", x\n"


class Recorder:
    """The link requests made, in order, each with whether it ran on the GUI thread."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self.requests: list[tuple[str, bool]] = []

    def note(self, op: str) -> None:
        with self._lock:
            self.requests.append((op, threading.current_thread() is threading.main_thread()))

    def clear(self) -> None:
        with self._lock:
            self.requests.clear()

    def taken(self) -> list[tuple[str, bool]]:
        with self._lock:
            return list(self.requests)


RECORD = Recorder()
HOLD: dict[str, tuple[threading.Event, threading.Event]] = {}   # op → (it arrived, let it through)


class RecordingLink(Link):
    """An embedded simulator whose requests are noted (every typed request ends in `call`, then `request`)."""

    def __init__(self, inner: Link) -> None:
        super().__init__()
        self.inner = inner
        self.kind = inner.kind
        self.status_interval_s = inner.status_interval_s

    def request(self, request):
        RECORD.note(request.op)
        if (hold := HOLD.pop(request.op, None)) is not None:   # a slow line, as long as the test wants
            arrived, through = hold
            arrived.set()
            through.wait(30)
        return self.inner.request(request)

    def close(self) -> None:
        self.inner.close()

    @property
    def alive(self) -> bool:
        return getattr(self.inner, "alive", True)

    @property
    def virtual_time(self) -> bool:
        return self.inner.virtual_time

    def flush_events(self) -> None:
        self.inner.flush_events()

    def subscribe(self, callback) -> None:
        self.inner.subscribe(callback)

    def unsubscribe(self, callback) -> None:
        self.inner.unsubscribe(callback)


def _open(_spec) -> Link:
    RECORD.note("open")
    return RecordingLink(open_link("sim,realtime=50"))


def _scan(_spec, ids) -> list[int]:
    RECORD.note("scan")
    return list(ids)


def checking(window):
    """For a fixture `checked`: the window with this scheme as its default interface (controllers 1 and 2),
    nothing connected yet."""
    register_link_scheme(SCHEME, _open, f"{SCHEME}:NAME", "test: notes the thread of each request", scan=_scan)
    window.controllers.set_default(InterfaceConfig(kind=SCHEME, port="here", first=1, last=2))
    RECORD.clear()
    yield window
    links._SCHEMES.pop(SCHEME, None)   # other tests list the schemes (--help texts): this one is not theirs


def click(qtbot, widget) -> None:
    qtbot.mouseClick(widget, Qt.MouseButton.LeftButton)


def connect(qtbot, w) -> None:
    """Setup for the actions on a connected controller: Esc connects to the default one (DG 2054-2062)."""
    w.actions_by_text["Break"].trigger()
    qtbot.waitUntil(lambda: w.bridge.connected, timeout=20_000)


def program(w, tmp_path) -> None:
    editor = w.current_editor() or w.new_file()
    editor.setPlainText(PROGRAM)
    w.save(editor=editor, path=tmp_path / "ran.m")


def said(qtbot, w, text: str) -> None:
    qtbot.waitUntil(lambda: text in w.messages.toPlainText(), timeout=20_000)



@dataclass(frozen=True)
class Case:
    action: Callable
    todo: str = ""          # why it still runs on the GUI thread (xfail), "" when it does not


def params(cases: dict[str, Case]):
    for name, case in cases.items():
        marks = [pytest.mark.xfail(strict=True, reason=case.todo)] if case.todo else []
        yield pytest.param(name, id=name, marks=marks)


def no_request_on_the_gui_thread(name: str) -> None:
    QApplication.processEvents()
    taken = RECORD.taken()
    assert taken, f"{name}: no link request at all (the case tests nothing)"
    on_gui = [op for op, gui in taken if gui]
    assert not on_gui, f"{name}: requests on the GUI thread: {', '.join(dict.fromkeys(on_gui))}"
