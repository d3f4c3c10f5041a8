"""Compiling a program of the window, without Qt (issue 27 item 5): the compiler for its language, then the IDE's
checks of Settings → Compiler (DG 3057-3085, ide-spec 1.45): Max number of variables (500; an array counts as
one), Max executable size (65000 bytes), Stack size (200), Enable Preprocessor, Generate Cross Reference. A
program over a limit gets an error at its first line, a preprocessor directive with the preprocessor off an error
at its line; the stack size travels with the download; without the cross reference Syntax Check writes no .ad$
and the debugger and the Watch explain that they need it (DG 3083-3085). The settings dialog is ui/compiler_settings.py.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

from motiontool.aposs.driver import CompileResult, compile_source
from motiontool.dpl.driver import CheckResult, check_source
from motiontool.language.diagnostics import Diagnostic, Location

_DIRECTIVE = re.compile(r"^\s*#\s*(define|undef|if|ifdef|ifndef|elif|else|endif|pragma)\b")
NO_XREF = ("Settings → Compiler → Generate Cross Reference is off: the debugger and the Watch need the cross "
           "reference (DG 3083-3085)")


@dataclass
class CompilerSettings:
    max_variables: int = 500
    max_executable: int = 65000
    stack_size: int = 200
    preprocessor: bool = True
    cross_reference: bool = True

    @classmethod
    def load(cls, settings: Any) -> CompilerSettings:
        """From the IDE's settings store (a QSettings or anything with its `value(key, default, type=)`)."""
        defaults = cls()
        values = {}
        for f in fields(cls):
            default = getattr(defaults, f.name)
            try:
                values[f.name] = settings.value(f"compiler/{f.name}", default, type=type(default))
            except (TypeError, ValueError):  # a damaged settings file: the default
                values[f.name] = default
        return cls(**values)

    def save(self, settings: Any) -> None:
        for f in fields(self):
            settings.setValue(f"compiler/{f.name}", getattr(self, f.name))


def check(settings: CompilerSettings, result: CompileResult, source: str, label: str) -> list[Diagnostic]:
    """The IDE's checks of the compiler options on a compiled program (`result` a CompileResult)."""
    found = []
    if not settings.preprocessor:
        for number, line in enumerate(source.splitlines(), 1):
            m = _DIRECTIVE.match(line)
            if m:
                found.append(Diagnostic("error", f"#{m.group(1)}: the preprocessor is switched off (Settings → "
                                                 "Compiler → Enable Preprocessor)", Location(label, number, 1)))
    image = result.image
    if image is not None:
        variables = sum(1 for v in image.globals if not v.name.startswith("$")) + len(image.arrays) + len(image.dims)
        if variables > settings.max_variables:
            found.append(Diagnostic("error", f"the program has {variables} variables (arrays count as one); "
                                             f"Settings → Compiler allows {settings.max_variables}",
                                    Location(label, 1, 1)))
        size = len(image.to_bytes())
        if size > settings.max_executable:
            found.append(Diagnostic("error", f"the program is {size} bytes; Settings → Compiler allows "
                                             f"{settings.max_executable} (Max executable size)", Location(label, 1, 1)))
    return found


@dataclass
class CheckOutcome:
    result: CompileResult | CheckResult    # CheckResult for a DPL program (the APC's language)
    first_error: tuple[int, int] | None    # (line, column) of the first error


def compile_program(source: str, path: str | None, name: str, *, dpl: bool, debug: bool = False,
                    settings: CompilerSettings | None = None) -> CheckOutcome:
    """Compile (APOSS) or check (DPL) a window's program: `path` where it is saved (None: unsaved), `name` what
    the window calls it (a sample's name, "Untitled.m")."""
    label = path or name
    result: CompileResult | CheckResult
    if dpl:
        result = check_source(source, label)
    else:
        result = compile_source(source, label, debug=debug, name=Path(name).stem)
        result.diagnostics += check(settings or CompilerSettings(), result, source, label)
    first = next(((d.loc.line, d.loc.col) for d in result.errors), None)
    return CheckOutcome(result, first)
