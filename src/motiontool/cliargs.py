"""Numbers and files on the command line: one parser for every number an option or a link option takes, and the
refusal of an output that is one of the command's inputs (docs/decisions.md R12-R14).  Qt-free and importing
nothing of motiontool, so the comms layer, the CAM commands and the CLI can all use it.

Python's ``int()`` and ``float()`` take every script's digits ("٥" is 5, "²" raises), ``float()`` takes nan and
inf, and ``int()`` of more than 4300 digits raises its own ValueError: a number here is ASCII digits of bounded
length, finite, inside the range the option allows, or a one-line ``BadNumber`` naming the option and that range.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Iterable
from pathlib import Path

MAX_DIGITS = 30                    # far beyond any value a controller holds; int() never sees a long string
MAX_RUN_SECONDS = 10 * 24 * 3600   # `run --seconds`: ten days of virtual time
PORT = (0, 65535)                  # a TCP port; 0 lets the system pick a free one
NODE_ID = (1, 32)                  # controllers of one simulated project (controller/bus.py)

_WHOLE = re.compile(rf"[-+]?[0-9]{{1,{MAX_DIGITS}}}")
_HEX = re.compile(rf"[-+]?0[xX][0-9a-fA-F]{{1,{MAX_DIGITS}}}")
_REAL = re.compile(r"[-+]?([0-9]{1,30}\.?[0-9]{0,30}|\.[0-9]{1,30})([eE][-+]?[0-9]{1,3})?")
_SHOWN = 64  # characters of a refused text repeated in the message (a 5000-digit number stays one short line)


class BadNumber(ValueError):
    """A refused number: ``str()`` is the one line to print (after the program's name)."""


class Refused(Exception):
    """A refused command-line argument, its line complete with the program's name. Not a ValueError, so that
    argparse lets it pass a ``type=`` conversion unchanged instead of replacing it by "invalid value"."""


def shown(text: str) -> str:
    """``text`` as a message repeats it: shortened when long, so the message stays one readable line."""
    text = text.replace("\n", " ").replace("\r", " ")
    return text if len(text) <= _SHOWN else f"{text[:_SHOWN]}… ({len(text)} characters)"


def _fmt(value: float) -> str:
    return f"{value:g}" if isinstance(value, float) and not float(value).is_integer() else str(int(value))


def whole(text: str, what: str, lo: int, hi: int, *, hex: bool = False, sep: str = " ") -> int:
    """The whole number ``text`` (decimal, or 0x… with ``hex``) in lo..hi, else BadNumber naming ``what`` (then
    ``sep``, then the text: "--set KPROP=abc")."""
    t = text.strip()
    if _WHOLE.fullmatch(t) or (hex and _HEX.fullmatch(t)):
        value = int(t, 0) if hex and _HEX.fullmatch(t) else int(t, 10)
        if lo <= value <= hi:
            return value
    kind = "a whole number (or 0x hex)" if hex else "a whole number"
    raise BadNumber(f"{what}{sep}{shown(text)}: give {kind} from {lo} to {hi}")


def real(text: str, what: str, lo: float, hi: float, *, above: bool = False, sep: str = " ") -> float:
    """The finite decimal number ``text`` in lo..hi (above lo, not at it, with ``above``), else BadNumber."""
    t = text.strip()
    if _REAL.fullmatch(t):
        value = float(t)
        if math.isfinite(value) and (lo < value if above else lo <= value) and value <= hi:
            return value
    limits = f"above {_fmt(lo)} and at most {_fmt(hi)}" if above else f"from {_fmt(lo)} to {_fmt(hi)}"
    raise BadNumber(f"{what}{sep}{shown(text)}: give a number {limits}")


def node_id(text: str, what: str = "--node") -> int:
    """A controller's node id 1..32 (the bus's own words for one outside the range)."""
    t = text.strip()
    if _WHOLE.fullmatch(t):
        n = int(t)
        if NODE_ID[0] <= n <= NODE_ID[1]:
            return n
        raise BadNumber(f"{what} {n}: node id {n} is outside {NODE_ID[0]}..{NODE_ID[1]}")
    raise BadNumber(f"{what} {shown(text)}: give a node id, a whole number from {NODE_ID[0]} to {NODE_ID[1]}")


# --- numbers inside compound options of `run` and `params` ----------------------------------------------------------
_INPUT = re.compile(r"^([^=@]+)=([^=@]+)(?:@([^=@]+))?$")  # N=V@T, each number read by whole()
PARAMETER_VALUE = (-(1 << 31), (1 << 32) - 1)  # 32 bits, signed or unsigned: the controller checks its own range
ANALOG_VALUE = (-(1 << 15), (1 << 15) - 1)     # 16 bits, as the DS401 object 0x6401 carries an analog input
SIGNAL_NUMBER = (0, (1 << 31) - 1)             # a SYSVAR index or APC read parameter in --signals


def parse_input(spec: str) -> tuple[int, int, int] | None:
    """(input, value, time ms) of `--input N=V[@T]`; None when it has another form; BadNumber for a number that is
    not ASCII digits or outside its bounds (the controller then refuses inputs it does not have)."""
    m = _INPUT.match(spec.strip())
    if not m:
        return None
    what = f"--input {shown(spec)}:"
    return (whole(m.group(1), f"{what} input", 0, 9999), whole(m.group(2), f"{what} value", *ANALOG_VALUE),
            whole(m.group(3) or "0", f"{what} time", 0, MAX_RUN_SECONDS * 1000))


def parse_setting(setting: str) -> tuple[str, int] | None:
    """(key, value) of `--set KEY=VALUE`; None without '='; BadNumber for a value that is no 32-bit whole number."""
    key, _, value = setting.partition("=")
    if not value or not key.strip():
        return None
    return key.strip(), whole(value, f"--set {key.strip()}", *PARAMETER_VALUE, hex=True, sep="=")


def check_signals(signals: list[str]) -> None:
    """Numbers in --signals (SYSVAR 4097, 0x1001, APC [48], drive #18.12): ASCII digits of bounded length."""
    for name in signals:
        text = name.strip().lstrip("#").removeprefix("[").removesuffix("]")
        if text[:1].isdigit():  # any script's digit starts a number
            if "." in text:
                for part in text.split(".", 1):
                    whole(part, f"--signals {shown(name)}: menu or parameter", 0, 99)
            else:
                whole(text, "--signals", *SIGNAL_NUMBER, hex=True)


class Number:
    """An argparse ``type=`` for a numeric option: ``whole`` or ``real`` with the option's range; a refusal is
    ``Refused`` with the sub-command's name (cli.main prints it as one line, exit 1, before anything runs)."""

    def __init__(self, prog: str, option: str, lo: float, hi: float, *, integer: bool = False,
                 above: bool = False):
        self.prog, self.option, self.lo, self.hi, self.integer, self.above = prog, option, lo, hi, integer, above
        self.__name__ = "int" if integer else "float"  # argparse names the type in its own messages

    def __call__(self, text: str) -> int | float:
        try:
            if self.integer:
                return whole(text, self.option, int(self.lo), int(self.hi))
            return real(text, self.option, self.lo, self.hi, above=self.above)
        except BadNumber as exc:
            raise Refused(f"{self.prog}: {exc}") from None


def number_option(parser, *names: str, lo: float, hi: float, integer: bool = False, above: bool = False, **kw):
    """``parser.add_argument(*names, type=Number(...), **kw)`` with the range named in the refusal."""
    return parser.add_argument(*names, type=Number(parser.prog, names[0], lo, hi, integer=integer, above=above), **kw)


# --- an output onto an input ---------------------------------------------------------------------------------------
def same_file(a: Path | str, b: Path | str) -> bool:
    """Whether two paths name one file: the same device and inode when both exist (hard links, symbolic links,
    other spellings), else the same path once symbolic links are resolved (a dangling link to the other)."""
    try:
        sa, sb = os.stat(a), os.stat(b)
    except (OSError, ValueError):
        pass
    else:
        return (sa.st_dev, sa.st_ino) == (sb.st_dev, sb.st_ino)
    try:
        return os.path.realpath(a) == os.path.realpath(b)
    except (OSError, ValueError):
        return False


def refuse_overwriting_inputs(outputs: Iterable[tuple[str, Path]], inputs: Iterable[tuple[str, Path]]) -> None:
    """Raise ``OutputIsInput`` when an output is one of the inputs or another output, as compilers refuse "input
    file is the same as output file": a command must never replace its own source (or one output the other)."""
    outputs, inputs = list(outputs), list(inputs)
    for k, (option, out) in enumerate(outputs):
        for what, path in inputs:
            if same_file(out, path):
                named = f" ({what})" if what else ""
                raise OutputIsInput(f"input file {path}{named} is the same as output file {out} ({option}); "
                                    "nothing was written")
        for other_option, other in outputs[:k]:
            if same_file(out, other):
                raise OutputIsInput(f"output files {other} ({other_option}) and {out} ({option}) are the same file; "
                                    "nothing was written")


class OutputIsInput(ValueError):
    """An output path that names an input (or another output) of the same command."""
