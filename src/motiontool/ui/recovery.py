"""Autosave and crash recovery (decisions R8). The .m files are never touched.

Each running IDE keeps its autosaves in its own session folder ``recovery/session-PID-RANDOM/`` and holds a lock
on it (``flock``/``msvcrt.locking``, released by the operating system when the process ends, however it ends). A
modified buffer is copied there a couple of seconds after the last keystroke (at the latest every 30 s while typing
goes on) and its copy lives until the buffer is saved or discarded. At start-up only sessions whose lock can be
taken are offered: their IDE is gone. Another running instance's autosaves are never offered or deleted. Restored
buffers are autosaved into the new session before the old copies are removed, so a second crash loses nothing.
"""

from __future__ import annotations

import json
import os
import secrets
import shutil
from dataclasses import dataclass
from pathlib import Path

from PySide6.QtCore import QElapsedTimer, QObject, QTimer

from motiontool.fileio import MiB, atomic_write_text, read_text

AUTOSAVE_AFTER_MS = 2_000    # after the last keystroke
AUTOSAVE_AT_LEAST_MS = 30_000  # while typing goes on without a pause
_FORMAT = 2
_PROPERTY = "recovery_file"


@dataclass
class Buffer:
    """An autosaved buffer of an abandoned session."""

    original: str   # the program's path, "" for an unsaved one
    text: str
    file: Path


def _try_lock(fd: int) -> bool:
    try:
        if os.name == "nt":
            import msvcrt

            msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)
        else:
            import fcntl

            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        return False
    return True


def _number(path: Path) -> tuple[int, str]:
    digits = "".join(c for c in path.stem if c in "0123456789")
    return (int(digits) if digits else 0, path.name)


class Session:
    """A session folder and, while we hold it, its lock."""

    def __init__(self, folder: Path):
        self.folder = folder
        self._fd: int | None = None

    def lock(self) -> bool:
        """Take the lock; False when a living IDE holds it."""
        try:
            fd = os.open(self.folder / "lock", os.O_RDWR | os.O_CREAT, 0o600)
        except OSError:
            return False
        if not _try_lock(fd):
            os.close(fd)
            return False
        self._fd = fd
        return True

    def release(self) -> None:
        if self._fd is not None:
            os.close(self._fd)  # closing the descriptor releases the lock
            self._fd = None

    def buffers(self) -> list[Buffer]:
        found = []
        for path in sorted(self.folder.glob("buffer-*.json"), key=_number):
            try:
                data = json.loads(read_text(path, 64 * MiB, "recovery file"))
                found.append(Buffer(str(data["original"]), str(data["text"]), path))
            except (OSError, ValueError, KeyError, TypeError):
                continue  # an unreadable recovery file is skipped, never fatal
        return found

    def remove(self) -> None:
        self.release()
        shutil.rmtree(self.folder, ignore_errors=True)


class Recovery:
    """The recovery folder of the IDE: our own locked session, and the sessions of IDEs that are gone."""

    def __init__(self, folder: Path):
        self.folder = Path(folder)
        self.session: Session | None = None
        self._abandoned: list[Session] | None = None
        self._count = 0

    # --- our own session ------------------------------------------------------------------------------------
    def _own(self) -> Session:
        if self.session is None:
            folder = self.folder / f"session-{os.getpid()}-{secrets.token_hex(4)}"
            folder.mkdir(parents=True)
            session = Session(folder)
            session.lock()
            self.session = session
        return self.session

    def store(self, editor, original: str, text: str) -> None:
        """Copy a buffer into our session; raises OSError when the folder cannot be written."""
        name = editor.property(_PROPERTY)
        if not name:
            self._count += 1
            name = f"buffer-{self._count}.json"
            editor.setProperty(_PROPERTY, name)
        atomic_write_text(self._own().folder / name, json.dumps({"version": _FORMAT, "original": original,
                                                                 "text": text}))

    def stored(self, editor) -> Path | None:
        name = editor.property(_PROPERTY)
        return self.session.folder / name if name and self.session is not None else None

    def discard(self, editor) -> None:
        path = self.stored(editor)
        if path is not None:
            path.unlink(missing_ok=True)

    def close(self) -> None:
        """A clean exit: every buffer was saved or discarded, so the session goes."""
        if self.session is not None:
            self.session.remove()
            self.session = None

    # --- sessions of IDEs that are gone -----------------------------------------------------------------------
    def abandoned(self) -> list[Session]:
        """Sessions whose IDE no longer runs (we now hold their locks), and loose files of older versions."""
        if self._abandoned is None:
            self._abandoned = []
            own = self.session.folder if self.session is not None else None
            for folder in sorted(self.folder.glob("session-*")):
                if folder == own or not folder.is_dir():
                    continue
                session = Session(folder)
                if session.lock():
                    self._abandoned.append(session)
            if any(self.folder.glob("buffer-*.json")):  # motiontool before sessions: no one else owns them
                self._abandoned.append(_Loose(self.folder))
        return self._abandoned

    def pending(self) -> list[Buffer]:
        return [b for s in self.abandoned() for b in s.buffers()]

    def forget_abandoned(self, delete: bool) -> None:
        """Delete the abandoned sessions (the user discarded them) or let go of them (offered again next time)."""
        for session in self.abandoned():
            session.remove() if delete else session.release()
        self._abandoned = None


class _Loose(Session):
    """Autosaves of a motiontool before sessions, directly in the recovery folder."""

    def lock(self) -> bool:
        return True

    def remove(self) -> None:
        for path in self.folder.glob("buffer-*.json"):
            path.unlink(missing_ok=True)


class Autosave(QObject):
    """Autosaves the window's modified buffers a moment after typing stops (and at least every 30 s)."""

    def __init__(self, window, recovery: Recovery):
        super().__init__(window)
        self.window = window
        self.recovery = recovery
        self.failed: str | None = None  # the last failure, said once in the Messages pane
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(AUTOSAVE_AFTER_MS)
        self._timer.timeout.connect(self.run)
        self._since = QElapsedTimer()  # the first change not yet autosaved

    def changed(self) -> None:
        if not self._since.isValid():
            self._since.start()
        if self._since.elapsed() >= AUTOSAVE_AT_LEAST_MS:
            self.run()
        else:
            self._timer.start()

    def run(self) -> None:
        self._timer.stop()
        self._since.invalidate()
        for editor in self.window.editors():
            try:
                if editor.document().isModified():
                    self.recovery.store(editor, editor.property("path") or "", editor.toPlainText())
                else:
                    self.recovery.discard(editor)
            except OSError as exc:
                message = f"Autosave failed: {exc.strerror or exc} ({self.recovery.folder})"
                if message != self.failed:
                    self.window.messages.ide(message)
                self.failed = message
                return
        self.failed = None


def offer_recovery(window) -> int:
    """At start-up: offer the buffers of IDEs that ended without closing (Restore, Discard, or Not now: offered
    again at the next start). Returns how many buffers were restored."""
    buffers = window.recovery.pending()
    if not buffers:
        window.recovery.forget_abandoned(delete=False)
        return 0
    names = ", ".join(Path(b.original).name if b.original else "an unsaved program" for b in buffers[:5])
    more = f" and {len(buffers) - 5} more" if len(buffers) > 5 else ""
    answer = window.prompts.decide(
        "Recovery", f"motiontool was not closed properly. {len(buffers)} program(s) had unsaved changes: "
        f"{names}{more}.", yes="Restore", no="Discard", cancel="Not now",
        detail="Restore them? Discard deletes the copies; Not now keeps them for the next start.")
    if answer:
        return window.recover()
    window.recovery.forget_abandoned(delete=answer is False)
    return 0


__all__ = ["AUTOSAVE_AFTER_MS", "Autosave", "Buffer", "Recovery", "offer_recovery"]
