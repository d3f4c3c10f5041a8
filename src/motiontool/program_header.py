"""What a program's comment header asks of the controller before it runs (the samples' `// Test-inputs:` and
`// Test-settings:` lines, tests/test_samples.py): the inputs and parameters `motiontool run --input/--set` would
give. The IDE offers to apply them when such a program is executed (ui/io_panel.py). Qt-free.

    // Test-inputs: 1=1@500 1=0@1500     input N to V, T ms after the program's start (as --input N=V@T)
    // Test-settings: JERKMIN=200        a parameter written before the start (as --set NAME=V)

The header is the leading run of `// Key: value` lines (blank lines and bare `//` between them included).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import TypeVar

from motiontool.cliargs import BadNumber, parse_input, parse_setting, shown

_HEADER = re.compile(r"^//\s*([A-Za-z][A-Za-z-]*):\s?(.*)$")


class HeaderError(ValueError):
    """A Test-inputs/Test-settings entry that is not N=V@T / NAME=V; the text names the file and line."""


@dataclass
class TestSettings:
    inputs: list[tuple[int, int, int]] = field(default_factory=list)   # (input, value, ms after the start)
    settings: list[tuple[str, int]] = field(default_factory=list)      # (parameter, value)

    def __bool__(self) -> bool:
        return bool(self.inputs or self.settings)

    def describe(self) -> str:
        """One line, in the header's own notation."""
        parts = []
        if self.inputs:
            parts.append("inputs " + " ".join(f"{n}={v}@{t}" for n, v, t in self.inputs))
        if self.settings:
            parts.append("settings " + " ".join(f"{k}={v}" for k, v in self.settings))
        return "; ".join(parts)


def read_test_settings(text: str, name: str = "program") -> TestSettings:
    """The Test-inputs and Test-settings of the header of `text`; HeaderError naming `name` and the line."""
    found = TestSettings()
    for number, line in enumerate(text.splitlines()[:200], start=1):  # a header is short; a long file is not read
        m = _HEADER.match(line.strip())
        if not m:
            if line.strip() in ("", "//"):
                continue
            break
        key, value = m.group(1).lower(), m.group(2)
        if key not in ("test-inputs", "test-settings"):
            continue
        for spec in value.split():
            place = f"{name} line {number}: {m.group(1)} entry {shown(spec)}"
            try:
                if key == "test-inputs":
                    found.inputs.append(_given(parse_input(spec), place, "N=V@T (input, value, ms)"))
                else:
                    found.settings.append(_given(parse_setting(spec), place, "NAME=V (parameter, value)"))
            except BadNumber as exc:
                raise HeaderError(f"{place}: {str(exc).split(': ', 1)[-1]}") from None  # not the CLI's option name
    return found


T = TypeVar("T")


def _given(parsed: T | None, place: str, form: str) -> T:
    if parsed is None:
        raise HeaderError(f"{place}: give {form}")
    return parsed
