"""Compiler driver: file → preprocess → parse → check → code → ProgramImage, with all diagnostics.

Used by `motiontool check` / `compile`, the IDE's syntax check (F4) and `motiontool run`.
"""

from __future__ import annotations

import gc
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import TextIO

from motiontool.aposs.check import check_program
from motiontool.aposs.codegen import CodeGen
from motiontool.aposs.image import ProgramImage
from motiontool.aposs.parser import parse
from motiontool.aposs.preprocess import Preprocessor
from motiontool.language.diagnostics import CompileError, Diagnostic, DiagnosticSink
from motiontool.resources import resources_path


@dataclass
class CompileResult:
    image: ProgramImage | None          # None when there are errors
    diagnostics: list[Diagnostic] = field(default_factory=list)
    files: list[str] = field(default_factory=list)

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.severity == "error"]

    @property
    def ok(self) -> bool:
        return not self.errors


def system_include_dirs(extra: list[Path] | None = None) -> list[Path]:
    """Where #include <file> looks: the bundled resources/include, then the user's directories."""
    return [resources_path("include"), *(extra or [])]


def _parameter_lookup(name: str) -> int | None:
    from motiontool.paramdb import ParameterError, database

    try:
        parameter = database().get(name)
    except ParameterError:
        return None
    return parameter.index if parameter.name else None


def compile_source(text: str | None = None, path: Path | str | None = None, *, include_dirs=None,
                   debug: bool = False, name: str | None = None, cancelled=None) -> CompileResult:
    """Compile a program given as text (named `path` for messages and includes) or read from `path`.

    ``cancelled``: a callable polled on the way (per line, statement); when it says True the compilation stops with
    diagnostics.Cancelled (the IDE's live check after a newer edit)."""
    # The compiler makes some 10^5 tokens and nodes and no garbage cycles worth collecting on the way; the
    # cyclic collector's passes over them took a third of the compile time (benchmarks/compile_speed.py).
    collecting = gc.isenabled()
    gc.disable()
    try:
        return _compile(text, path, include_dirs, debug, name, cancelled)
    finally:
        if collecting:
            gc.enable()


def _compile(text, path, include_dirs, debug, name, cancelled) -> CompileResult:
    sink = DiagnosticSink()
    pre = Preprocessor(system_include_dirs(include_dirs))
    pre.cancelled = cancelled
    label = str(path) if path is not None else "<input>"
    files: list[str] = []
    try:
        result = pre.run_text(text, label) if text is not None else pre.run_file(Path(label))
        files = [f.path for f in result.files]
        for w in result.warnings:
            sink.add(w)
        program = parse(result.tokens, parameter_lookup=_parameter_lookup, cancelled=cancelled,
                        warnings=sink.items)
    except CompileError as exc:
        files = files or [f.path for f in pre.result.files]
        sink.add(exc.diagnostic)
        sink.items.extend(pre.result.warnings)
        return CompileResult(None, _ordered(sink.items), files)
    try:
        check_program(program, sink)
        codegen = CodeGen(program, sink, name or Path(label).stem, debug, files)
        codegen.cancelled = cancelled
        image = codegen.generate()
    except RecursionError:
        sink.error("program nested too deeply", program.loc)
        image = None
    return CompileResult(None if sink.errors else image, _sorted(_ordered(sink.items), files), files)


def _sorted(items: list[Diagnostic], files: list[str]) -> list[Diagnostic]:
    """Diagnostics in file order (as the files were read), then line and column."""
    rank = {name: i for i, name in enumerate(files)}
    return sorted(items, key=lambda d: (rank.get(d.loc.file, len(rank)), d.loc.line, d.loc.col))


def _ordered(items: list[Diagnostic]) -> list[Diagnostic]:
    seen, out = set(), []
    for d in items:
        key = (d.severity, d.message, d.loc)
        if key not in seen:
            seen.add(key)
            out.append(d)
    return out


def check_files(files: list[Path], include_dirs: list[Path] | None = None, out: TextIO = sys.stdout) -> int:
    """`motiontool check`: print GCC-style diagnostics; 1 if any file has an error."""
    failed = False
    for path in files:
        result = compile_source(path=path, include_dirs=include_dirs)
        for d in result.diagnostics:
            print(d.format(), file=out)
        failed = failed or not result.ok
    return 1 if failed else 0


def compile_file(path: Path, output: Path, include_dirs: list[Path] | None = None, debug: bool = False,
                 out: TextIO = sys.stdout) -> int:
    """`motiontool compile`: write the program image atomically; 1 on errors (a bad output path is found before the
    compilation: ``cannot write PATH: reason``)."""
    from motiontool.fileio import atomic_write_bytes, check_writable, write_error

    try:
        check_writable(output)
        result = compile_source(path=path, include_dirs=include_dirs, debug=debug)
        for d in result.diagnostics:
            print(d.format(), file=out)
        if not result.ok:
            return 1
        assert result.image is not None  # compile_source leaves it None only with an error
        atomic_write_bytes(output, result.image.to_bytes())
    except OSError as exc:
        print(f"motiontool compile: {write_error(output, exc)}", file=sys.stderr)
        return 1
    return 0
