"""The live syntax check off the GUI thread (decisions R9): after a pause in typing the program is compiled by a
worker thread; a newer edit cancels the older compilation (the compiler polls a flag per line and statement), and
a result is shown only while it still belongs to the editor's text. So a big or pathological program never
freezes typing, and no stale diagnostics appear."""

from __future__ import annotations

import queue
import threading
from dataclasses import dataclass, field

from PySide6.QtCore import QObject, Signal

from motiontool.aposs.driver import CompileResult, compile_source
from motiontool.dpl.driver import check_source
from motiontool.language.diagnostics import Cancelled


@dataclass
class _Job:
    editor: object
    text: str
    path: str
    dpl: bool  # a DPL program is checked by the DPL checker (fast, one pass: not cancellable)
    cancel: threading.Event = field(default_factory=threading.Event)
    result: CompileResult | None = None


class LiveCheck(QObject):
    """One worker thread per window; ``request(editor, path)`` replaces whatever check is pending or running."""

    _done = Signal(object)  # emitted in the worker, delivered queued in the GUI thread

    def __init__(self, window, show) -> None:
        super().__init__(window)
        self._show_result = show  # show(editor, CompileResult) in the GUI thread
        self._newest: _Job | None = None
        self.finished = 0   # compilations whose result was shown
        self.cancelled = 0  # compilations stopped because a newer edit came
        self._jobs: queue.SimpleQueue = queue.SimpleQueue()
        self._done.connect(self._deliver)
        self._thread = threading.Thread(target=self._work, args=(self._jobs, self._done), name="live-check",
                                        daemon=True)
        self._thread.start()
        jobs = self._jobs
        window.destroyed.connect(lambda *_: jobs.put(None))  # ends the worker with its window

    @property
    def busy(self) -> bool:
        job = self._newest
        return job is not None and job.result is None and not job.cancel.is_set()

    def newest_text(self) -> str | None:
        """The text of the newest check asked for (None before the first)."""
        return None if self._newest is None else self._newest.text

    def request(self, editor, path: str) -> None:
        if self._newest is not None:
            self._newest.cancel.set()
        self._newest = job = _Job(editor, editor.toPlainText(), path, getattr(editor, "language", "") == "dpl")
        self._jobs.put(job)

    def _work(self, jobs: queue.SimpleQueue, done) -> None:
        while (job := jobs.get()) is not None:
            if job.cancel.is_set():
                self.cancelled += 1
                continue
            try:
                job.result = check_source(job.text, job.path) if job.dpl else \
                    compile_source(job.text, job.path, cancelled=job.cancel.is_set)
            except Cancelled:
                self.cancelled += 1
                continue
            try:
                done.emit(job)
            except RuntimeError:  # the window is gone
                return

    def _deliver(self, job: _Job) -> None:
        if job is not self._newest or job.cancel.is_set():
            return
        try:
            current = job.editor.toPlainText()
        except RuntimeError:  # the editor was closed meanwhile
            return
        if current == job.text:
            self._show_result(job.editor, job.result)
            self.finished += 1
