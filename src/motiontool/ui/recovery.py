"""Autosave with crash recovery: modified buffers are copied to a recovery folder every 30 s and removed
when saved or closed; after a crash the next start offers them again. The .m files are never touched."""

from __future__ import annotations

import json
from pathlib import Path

from motiontool.fileio import atomic_write_text


class Recovery:
    def __init__(self, folder: Path):
        self.folder = Path(folder)

    def _file(self, editor) -> Path:
        return self.folder / f"buffer-{id(editor):x}.json"

    def store(self, editor, original: str, text: str) -> None:
        self.folder.mkdir(parents=True, exist_ok=True)
        atomic_write_text(self._file(editor), json.dumps({"version": 1, "original": original, "text": text}))

    def discard(self, editor) -> None:
        self._file(editor).unlink(missing_ok=True)

    def pending(self) -> list[tuple[str, str]]:
        found = []
        for path in sorted(self.folder.glob("buffer-*.json")):
            try:
                data = json.loads(path.read_text(encoding="utf-8"))
                found.append((str(data["original"]), str(data["text"])))
            except (OSError, ValueError, KeyError):
                continue  # an unreadable recovery file is skipped, never fatal
        return found

    def clear(self) -> None:
        for path in self.folder.glob("buffer-*.json"):
            path.unlink(missing_ok=True)
