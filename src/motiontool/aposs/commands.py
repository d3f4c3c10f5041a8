"""The APOSS command table resources/aposs/commands.toml: loader and validator (stdlib only, no Qt).
One table feeds the parser, the editor (highlighting, completion, hover) and the Command List dialog."""

from __future__ import annotations

import re
import tomllib
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from motiontool.resources import resources_path

GROUPS = frozenset({"INI", "CON", "IO", "SYS", "INT", "PAR", "COM", "ROT", "ABS", "REL", "SYN", "CAM", "CAN",
                    "LANG"})
KINDS = frozenset({"command", "function", "sysvar", "pseudoarray", "keyword", "interrupt", "operator"})
RETURNS = frozenset({"none", "long", "double"})
WAITS = frozenset({"M", "B", "T", "-", "?"})
ARG_KINDS = frozenset({"expr", "var", "array", "string", "param", "word", "print"})
_MODIFIERS = {"": (False, False), "?": (True, False), "*": (True, True), "+": (False, True)}
_FIELDS: dict[str, type] = {
    "name": str, "group": str, "kind": str, "args": list, "returns": str, "statement": bool,
    "wait": str, "since": str, "syntax": str, "help": str, "errors": list, "src": str,
}
_WORD = r"[A-Z_][A-Z0-9_]*"
_NAME_RE = re.compile(rf"{_WORD}(?: {_WORD})*")
_WORD_RE = re.compile(_WORD)
_SINCE_RE = re.compile(r"(?:\d+\.\d\d)?")


class CommandTableError(ValueError):
    """The command table is malformed; the message names the entry and the field."""


@dataclass(frozen=True)
class ArgSpec:
    kind: str  # expr var array string param word print
    words: tuple[str, ...] = ()  # for kind "word"
    optional: bool = False  # "?" or "*"
    repeat: bool = False  # "*" or "+"

    @classmethod
    def parse(cls, text: str) -> ArgSpec:
        """Parse one argument spec such as "expr", "var", "expr+", "word:ON|OFF?"; ValueError if bad."""
        mod = text[-1] if text[-1:] in ("?", "*", "+") else ""
        kind, colon, rest = text[: len(text) - len(mod)].partition(":")
        if kind not in ARG_KINDS:
            raise ValueError(f"unknown argument kind {text!r}")
        if kind != "word" and colon:
            raise ValueError(f"only 'word' takes a ':' list, got {text!r}")
        words = tuple(rest.split("|")) if kind == "word" else ()
        if kind == "word" and (not all(map(_WORD_RE.fullmatch, words)) or len(set(words)) < len(words)):
            raise ValueError(f"'word' needs distinct UPPER-CASE words separated by '|', got {text!r}")
        return cls(kind, words, *_MODIFIERS[mod])

    def __str__(self) -> str:
        mod = {flags: m for m, flags in _MODIFIERS.items()}[(self.optional, self.repeat)]
        return self.kind + (":" + "|".join(self.words) if self.kind == "word" else "") + mod


@dataclass(frozen=True)
class Command:
    name: str
    group: str
    kind: str
    args: tuple[ArgSpec, ...]
    returns: str
    statement: bool
    wait: str
    since: str
    syntax: str
    help: str
    errors: tuple[int, ...]
    src: str

    @property
    def words(self) -> tuple[str, ...]:
        """The words of the name: ("MOTOR", "ON") for "MOTOR ON"."""
        return tuple(self.name.split())


class CommandTable:
    """The commands by name (case-insensitive), in file order."""

    def __init__(self, commands: Iterable[Command]) -> None:
        self._by_name: dict[str, Command] = {}
        self._by_first: dict[str, list[Command]] = {}
        for cmd in commands:
            if self._by_name.setdefault(cmd.name, cmd) is not cmd:
                raise CommandTableError(f"command {cmd.name!r}: field 'name': duplicate name")
            self._by_first.setdefault(cmd.words[0], []).append(cmd)
        for group in self._by_first.values():
            group.sort(key=lambda c: (-len(c.words), -len(c.name), c.name))

    def get(self, name: str) -> Command | None:
        """The command called `name` ("motor  on" finds MOTOR ON), or None."""
        return self._by_name.get(" ".join(name.upper().split()))

    def starting_with(self, word: str) -> list[Command]:
        """All commands whose first word is `word`, longest name first ("MOTOR ON" before "MOTOR")."""
        return list(self._by_first.get(word.strip().upper(), ()))

    def names(self) -> list[str]:
        return list(self._by_name)

    def __iter__(self) -> Iterator[Command]:
        return iter(self._by_name.values())

    def __len__(self) -> int:
        return len(self._by_name)

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and " ".join(name.upper().split()) in self._by_name


def _command(index: int, raw: object) -> Command:
    if not isinstance(raw, dict):
        raise CommandTableError(f"command #{index + 1}: not a table")
    label = f"command #{index + 1}" + (f" {raw['name']!r}" if isinstance(raw.get("name"), str) else "")

    def bad(field: str, why: str) -> CommandTableError:
        return CommandTableError(f"{label}: field {field!r}: {why}")

    for field, typ in _FIELDS.items():
        if field not in raw:
            raise bad(field, "missing")
        if not isinstance(raw[field], typ):
            raise bad(field, f"expected {typ.__name__}, got {type(raw[field]).__name__}")
    if extra := sorted(set(raw) - set(_FIELDS)):
        raise bad(extra[0], "unknown key")
    if not _NAME_RE.fullmatch(raw["name"]):
        raise bad("name", "must be UPPER CASE words separated by single spaces")
    for field, allowed in (("group", GROUPS), ("kind", KINDS), ("returns", RETURNS), ("wait", WAITS)):
        if raw[field] not in allowed:
            raise bad(field, f"{raw[field]!r} is not one of {' '.join(sorted(allowed))}")
    if raw["kind"] in ("function", "sysvar", "pseudoarray") and raw["returns"] == "none":
        raise bad("returns", f"a {raw['kind']} must return long or double")
    if not _SINCE_RE.fullmatch(raw["since"]):
        raise bad("since", f"expected '' or a version like '5.00', got {raw['since']!r}")
    if empty := [f for f in ("syntax", "help") if not raw[f].strip()]:
        raise bad(empty[0], "empty")
    args: list[ArgSpec] = []
    for pos, text in enumerate(raw["args"]):
        try:
            spec = ArgSpec.parse(text if isinstance(text, str) else repr(text))
        except ValueError as exc:
            raise bad("args", f"argument {pos + 1}: {exc}") from None
        if (spec.optional or spec.repeat) and pos != len(raw["args"]) - 1:
            raise bad("args", f"argument {pos + 1} {text!r}: modifiers ? * + only on the last argument")
        args.append(spec)
    errors = raw["errors"]
    if not all(isinstance(e, int) and not isinstance(e, bool) and e > 0 for e in errors):
        raise bad("errors", "must be a list of positive error numbers")
    return Command(
        name=raw["name"], group=raw["group"], kind=raw["kind"], args=tuple(args),
        returns=raw["returns"], statement=raw["statement"], wait=raw["wait"], since=raw["since"],
        syntax=raw["syntax"], help=raw["help"].strip(), errors=tuple(errors), src=raw["src"],
    )


def load_command_table(path: str | Path) -> CommandTable:
    """Read and validate a command table file (no caching)."""
    path = Path(path)
    try:
        with path.open("rb") as fh:
            data = tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise CommandTableError(f"{path}: not valid TOML: {exc}") from None
    version = data.get("version")
    if type(version) is not int or version != 1:
        raise CommandTableError(f"{path}: field 'version': expected 1, got {version!r}")
    if extra := sorted(set(data) - {"version", "command"}):
        raise CommandTableError(f"{path}: unknown top-level key {extra[0]!r}")
    raw = data.get("command", [])
    if not isinstance(raw, list):
        raise CommandTableError(f"{path}: 'command' must be an array of tables ([[command]])")
    commands: dict[str, Command] = {}
    try:
        for i, entry in enumerate(raw):
            cmd = _command(i, entry)
            if cmd.name in commands:
                raise CommandTableError(f"command #{i + 1} {cmd.name!r}: field 'name': duplicate name")
            commands[cmd.name] = cmd
    except CommandTableError as exc:
        raise CommandTableError(f"{path}: {exc}") from None
    return CommandTable(commands.values())


@lru_cache(maxsize=1)
def _default_table() -> CommandTable:
    return load_command_table(resources_path("aposs", "commands.toml"))


def command_table(path: str | Path | None = None) -> CommandTable:
    """The APOSS command table; the packaged one (loaded once, then cached) when `path` is None."""
    return _default_table() if path is None else load_command_table(path)
