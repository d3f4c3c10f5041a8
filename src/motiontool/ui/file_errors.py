"""What the IDE says when a file cannot be written: one modal message naming the file and the reason, and what
happened to the user's work (decisions R7). Nothing is lost: the caller keeps its buffer and its window open."""

from __future__ import annotations

from pathlib import Path

from motiontool.fileio import reason


def save_failed(w, title: str, path: Path | str, exc: OSError, kept: str) -> None:
    """Said through the window `w`'s prompts, over it. ``kept``: a sentence on what the user still has, e.g.
    "The program is still open in the editor"."""
    w.prompts.warn(title, f"Cannot write {path}:\n{reason(exc)}.", detail=kept, critical=True)
