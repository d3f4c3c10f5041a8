"""Source locations and compiler diagnostics (GCC style: ``path:line:col: error: message``)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple


class Location(NamedTuple):
    """A place in a source file; line and column are 1-based. A NamedTuple: every token carries one, and a
    tuple is made twice as fast as a frozen dataclass."""

    file: str
    line: int
    col: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


class Cancelled(Exception):  # noqa: N818 - a request, not an error
    """The caller no longer wants this compilation (the IDE's live check after a newer edit)."""


@dataclass(frozen=True)
class Diagnostic:
    severity: str  # "error" | "warning" | "note"
    message: str
    loc: Location
    # Where a macro expansion came from, innermost first: shown as notes.
    notes: tuple[tuple[str, Location], ...] = ()

    def format(self) -> str:
        lines = [f"{self.loc}: {self.severity}: {self.message}"]
        lines += [f"{loc}: note: {text}" for text, loc in self.notes]
        return "\n".join(lines)


class CompileError(Exception):
    """Raised when compilation cannot go on; carries the diagnostic that stopped it."""

    def __init__(self, message: str, loc: Location, notes: tuple[tuple[str, Location], ...] = ()):
        super().__init__(f"{loc}: error: {message}")
        self.diagnostic = Diagnostic("error", message, loc, notes)


@dataclass
class DiagnosticSink:
    """Collects diagnostics in order; errors make the compilation fail."""

    items: list[Diagnostic] = field(default_factory=list)

    def error(self, message: str, loc: Location) -> None:
        self.items.append(Diagnostic("error", message, loc))

    def warning(self, message: str, loc: Location) -> None:
        self.items.append(Diagnostic("warning", message, loc))

    def add(self, diagnostic: Diagnostic) -> None:
        self.items.append(diagnostic)

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self.items if d.severity == "error"]

    @property
    def warnings(self) -> list[Diagnostic]:
        return [d for d in self.items if d.severity == "warning"]
