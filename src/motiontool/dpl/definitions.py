"""The APC definitions (seed 004 §11.5, L7942-8199): the aliases a DPL program may write instead of numbers
(``APC_ENABLE`` = 2, ``APC_FB_POS`` = 48). One table, ``resources/dpl/definitions.csv``, feeds the checker,
the runtime, the editor and the read-parameter names of scope and watch."""

from __future__ import annotations

import csv
from dataclasses import dataclass
from functools import lru_cache

from motiontool.resources import resources_path


@dataclass(frozen=True)
class Definition:
    name: str       # upper case, as the manual prints it
    value: int
    group: str      # "read parameter", "reference select", "status", …
    line: int       # seed 004 line
    note: str = ""


@lru_cache(maxsize=1)
def definitions() -> dict[str, Definition]:
    """Every definition by name."""
    path = resources_path("dpl", "definitions.csv")
    with open(path, encoding="utf-8", newline="") as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        table = {}
        for row in rows:
            d = Definition(row["name"], int(row["value"]), row["group"], int(row["line"]), row["note"])
            if d.name in table:
                raise ValueError(f"{path}: {d.name} is defined twice")
            table[d.name] = d
    return table


@lru_cache(maxsize=1)
def read_parameter_names() -> dict[int, str]:
    """Read-parameter number → alias (48 → APC_FB_POS), for scope, watch and the runtime's by-alias access."""
    return {d.value: d.name for d in definitions().values() if d.group == "read parameter"}


def read_parameter_number(name: str) -> int | None:
    """The number of a read parameter given by alias (any case), by number ("48") or as "[48]"; None if unknown."""
    key = name.strip().strip("[]").strip()
    if key.lstrip("-").isdigit():
        return int(key)
    d = definitions().get(key.upper())
    return d.value if d is not None and d.group == "read parameter" else None
