"""Bookmark persistence and navigation (Qt-free; ide-spec 1.37).

Bookmarks are saved OUTSIDE the program file (DECISION of ide-spec 1.37): one JSON file, for example in the
application's config directory, maps the absolute path of each program to its bookmarked lines::

    {"version": 1, "files": {"/home/me/prog/print3.m": [3, 17, 42]}}
"""

from __future__ import annotations

import json
from bisect import bisect_left, bisect_right
from pathlib import Path

from motiontool.fileio import MiB, atomic_write_text, read_text

_VERSION = 1


def next_bookmark(lines: list[int], current: int, backward: bool = False) -> int | None:
    """The bookmark after (before, with `backward`) line `current`, wrapping around; None if there is none.

    Lines are 1-based; `lines` need not be sorted.
    """
    marks = sorted(set(lines))
    if not marks:
        return None
    if backward:
        i = bisect_left(marks, current)
        return marks[i - 1] if i > 0 else marks[-1]
    i = bisect_right(marks, current)
    return marks[i] if i < len(marks) else marks[0]


class BookmarkStore:
    """Bookmarked lines per program file, kept in the JSON file `path` (created on the first save)."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)

    @staticmethod
    def key(program: str | Path) -> str:
        """The key of a program file: its absolute path (symbolic links resolved)."""
        return str(Path(program).expanduser().resolve())

    def _read(self) -> dict[str, list[int]]:
        try:
            data = json.loads(read_text(self.path, 16 * MiB, "bookmarks file"))
        except (OSError, ValueError):
            return {}  # missing or damaged store: no bookmarks rather than an error at file open
        files = data.get("files") if isinstance(data, dict) else None
        if not isinstance(files, dict):
            return {}
        return {str(k): sorted({n for n in v if isinstance(n, int) and not isinstance(n, bool) and n > 0})
                for k, v in files.items() if isinstance(v, list)}

    def load(self, program: str | Path) -> list[int]:
        """The saved bookmarks (sorted 1-based lines) of `program`; [] if none."""
        return self._read().get(self.key(program), [])

    def save(self, program: str | Path, lines: list[int]) -> None:
        """Save the bookmarks of `program`; an empty list removes its entry. Written atomically."""
        files = self._read()
        key = self.key(program)
        marks = sorted({int(n) for n in lines if int(n) > 0})
        if marks:
            files[key] = marks
        elif files.pop(key, None) is None and not self.path.exists():
            return
        self.path.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(self.path, json.dumps({"version": _VERSION, "files": dict(sorted(files.items()))}, indent=1))

    def programs(self) -> list[str]:
        """The keys (absolute paths) of all programs with saved bookmarks."""
        return sorted(self._read())
