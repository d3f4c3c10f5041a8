"""The DPL built-in function table resources/dpl/functions.toml: loader and validator (stdlib only).
One table feeds the checker (arity, results, task limits), the runtime's bindings and the editor."""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass
from functools import lru_cache

from motiontool.resources import resources_path

GROUPS = ("control", "encoders", "ctsync", "references", "profile", "loop", "words", "conversion", "language")
TASKS = ("any", "pos")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_ARG = re.compile(r"[A-Za-z_][A-Za-z0-9_]*%")


@dataclass(frozen=True)
class Function:
    name: str                  # as the manual writes it
    group: str
    args: tuple[str, ...]      # "Mode%"; the CAM initialisers' "…Array%" arguments take whole arrays
    returns: tuple[str, ...]   # the first is the value inside an expression
    tasks: str                 # any | pos
    help: str
    src: str
    simulated: bool = True     # False: documented outside the APC manual; the simulated module cannot run it

    @property
    def key(self) -> str:
        return self.name.upper()

    @property
    def syntax(self) -> str:
        results = self.returns[0] if len(self.returns) == 1 else f"({', '.join(self.returns)})"
        return f"{results} = {self.name}({', '.join(self.args)})"

    def takes_array(self, position: int) -> bool:
        """The CAM initialisers take whole arrays: InArray%, OutArray1%, OutArray2%, InterpolationArray%."""
        return self.args[position].upper().rstrip("%12").endswith("ARRAY")


class FunctionTableError(ValueError):
    """The function table is malformed; the message names the entry and the field."""


@lru_cache(maxsize=1)
def function_table() -> dict[str, Function]:
    """Every built-in by upper-case name."""
    path = resources_path("dpl", "functions.toml")
    with open(path, "rb") as f:
        data = tomllib.load(f)
    table: dict[str, Function] = {}
    for n, entry in enumerate(data.get("function", []), 1):
        where = f"{path}: function {n} ({entry.get('name', '?')})"
        try:
            fn = Function(entry["name"], entry["group"], tuple(entry["args"]), tuple(entry["returns"]),
                          entry["tasks"], entry["help"], entry["src"], entry.get("simulated", True))
        except KeyError as exc:
            raise FunctionTableError(f"{where}: missing field {exc}") from None
        if not _NAME.fullmatch(fn.name) or fn.group not in GROUPS or fn.tasks not in TASKS:
            raise FunctionTableError(f"{where}: bad name, group or tasks")
        if not fn.returns or not all(_ARG.fullmatch(a) for a in fn.args + fn.returns):
            raise FunctionTableError(f"{where}: arguments and results are integer names ending in %")
        if fn.key in table:
            raise FunctionTableError(f"{where}: defined twice")
        table[fn.key] = fn
    return table
