"""DPL front-end driver: file → tokens → program → checks, with GCC-style diagnostics exactly like the APOSS
compiler's (``path:line:col: error: message``). Used by `motiontool check`, `motiontool run` and the IDE."""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import TextIO

from motiontool.dpl import ast
from motiontool.dpl.check import Symbols, check_program
from motiontool.dpl.image import MAX_SOURCE_BYTES
from motiontool.dpl.lexer import tokenize
from motiontool.dpl.parser import MAX_NESTING, parse
from motiontool.language.diagnostics import CompileError, Diagnostic, DiagnosticSink, Location
from motiontool.language.source import read_source

SUFFIX = ".dpl"
# The recursive-descent parser spends some 12 frames per parenthesis: 90 of them (under MAX_NESTING) overran
# Python's default limit of 1000. Python-to-Python calls use no C stack (3.11+), so a higher limit is safe.
_FRAMES = MAX_NESTING * 16 + 1000


def _room_for_nesting() -> None:
    if sys.getrecursionlimit() < _FRAMES:  # raised once, never lowered: the IDE checks in several threads
        sys.setrecursionlimit(_FRAMES)


@dataclass
class CheckResult:
    program: ast.Program | None      # None when there are errors
    symbols: Symbols | None
    diagnostics: list[Diagnostic] = field(default_factory=list)
    source: str = ""

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.severity == "error"]

    @property
    def ok(self) -> bool:
        return not self.errors


def is_dpl(path: Path | str | None) -> bool:
    return path is not None and Path(path).suffix.lower() == SUFFIX


def check_source(text: str | None = None, path: Path | str | None = None) -> CheckResult:
    """Check a program given as text (named `path` in messages) or read from `path`."""
    label = str(path) if path is not None else "<input>"
    sink = DiagnosticSink()
    if text is None:
        try:
            text = read_source(label, MAX_SOURCE_BYTES, "DPL program")  # as APOSS reads them; never a device (R4)
        except OSError as exc:
            message = f"cannot read the file: {exc.strerror or exc}"
            return CheckResult(None, None, [Diagnostic("error", message, Location(label, 1, 1))])
    else:  # text from an editor: a BOM and CR line ends as in a file
        text = text.removeprefix("\ufeff").replace("\r\n", "\n").replace("\r", "\n")
    _room_for_nesting()
    try:
        program = parse(tokenize(text, label))
    except CompileError as exc:
        return CheckResult(None, None, [exc.diagnostic], text)
    except RecursionError:  # only beyond MAX_NESTING levels of something the parser does not count
        return CheckResult(None, None, [Diagnostic("error", "program nested too deeply", Location(label, 1, 1))],
                           text)
    try:
        symbols = check_program(program, sink)
    except RecursionError:
        sink.error("program nested too deeply", program.loc)
        symbols = None
    diagnostics = sorted(sink.items, key=lambda d: (d.loc.line, d.loc.col))
    ok = not any(d.severity == "error" for d in diagnostics)
    return CheckResult(program if ok else None, symbols if ok else None, diagnostics, text)


def check_files(files: list[Path], out: TextIO = sys.stdout) -> int:
    """`motiontool check FILE.dpl`: print the diagnostics; 1 if any file has an error."""
    failed = False
    for path in files:
        result = check_source(path=path)
        for d in result.diagnostics:
            print(d.format(), file=out)
        failed = failed or not result.ok
    return 1 if failed else 0
