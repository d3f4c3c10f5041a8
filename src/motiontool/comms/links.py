"""One syntax for every link: `--link sim` (the embedded simulator), `--link fc:URL[#ADDRESS]`, and whatever other
schemes register an opener here (`canopen:INTERFACE:CHANNEL[#NODE]`, docs/link-protocol.md "Link syntax").

A link spec is ``SCHEME[:TARGET][#NODE][,KEY=VALUE]...``:

- SCHEME names the opener (``sim``, ``fc``, ``canopen``);
- TARGET is the scheme's business (for ``fc`` any pyserial URL: ``/dev/ttyUSB0``, ``COM3``,
  ``socket://127.0.0.1:4001``, ``rfc2217://host:port``);
- NODE is the controller's bus address or node id (``#2``);
- ``,KEY=VALUE`` options follow at the end (``,baud=115200,parity=E``); commas and ``#`` are not part of pyserial
  URLs, and none of these characters needs quoting in a shell.

Openers receive the parsed `LinkSpec` and return an open `Link` or raise `LinkError` saying what failed.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from motiontool.cliargs import BadNumber, real, shown, whole
from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError

_OPTION = re.compile(r",([A-Za-z_][A-Za-z0-9_-]*)=([^,#]*)$")
_NODE = re.compile(r"#([^#,]*)$")
ADDRESS = (0, 255)  # a bus address or node id; each scheme checks its own range (FC 1..126, CANopen 1..127)
INT_OPTION = (-(1 << 31), (1 << 31) - 1)  # the default bounds of a whole-number option
REAL_OPTION = (-1e9, 1e9)                  # … and of a decimal one (always finite)


class LinkSpecError(LinkError):
    """A malformed link spec or option (a refused command line, exit 1), not a controller that cannot be reached."""


@dataclass(frozen=True)
class LinkSpec:
    scheme: str
    target: str = ""
    node: int | None = None
    options: dict[str, str] = field(default_factory=dict)
    text: str = ""

    def option(self, name: str, default, convert: Callable = str, lo: float | None = None, hi: float | None = None):
        """An option converted by `convert`, or `default`; a bad value is a LinkError naming option and spec. Numbers
        (`convert` int or float) are read by cliargs: ASCII digits, finite, within lo..hi (default: wide bounds)."""
        if name not in self.options:
            return default
        what = f"link '{shown(self.text)}': option {name}"
        try:
            if convert is int:
                return whole(self.options[name], what, int(INT_OPTION[0] if lo is None else lo),
                             int(INT_OPTION[1] if hi is None else hi), sep="=")
            if convert is float:
                return real(self.options[name], what, REAL_OPTION[0] if lo is None else lo,
                            REAL_OPTION[1] if hi is None else hi, sep="=")
            return convert(self.options[name])
        except BadNumber as exc:
            raise LinkSpecError(str(exc)) from None
        except ValueError:
            raise LinkSpecError(f"link '{self.text}': option {name}={self.options[name]!r} is not valid") from None

    def check_options(self, known: set[str]) -> None:
        unknown = sorted(set(self.options) - known)
        if unknown:
            raise LinkSpecError(f"link '{self.text}': unknown option {unknown[0]!r} "
                            f"(known: {', '.join(sorted(known)) or 'none'})")


def parse_link_spec(text: str) -> LinkSpec:
    """`SCHEME[:TARGET][#NODE][,KEY=VALUE]...` → LinkSpec; LinkError naming the spec when it is malformed. Options
    may come before `#NODE` too (`fc:/dev/pts/3,baud=115200#1`: the drive's printed URL with a node added); one
    written after the node wins."""
    rest = text.strip()
    if not rest:
        raise LinkSpecError("empty link: give sim, fc:URL[#ADDRESS] or another registered scheme")
    rest, options = _strip_options(rest)
    node = None
    if (m := _NODE.search(rest)) is not None:
        try:
            node = whole(m.group(1), f"link '{shown(text)}': the address", *ADDRESS, sep=" #")
        except BadNumber as exc:
            raise LinkSpecError(str(exc)) from None
        rest, before = _strip_options(rest[:m.start()])
        options = {**before, **options}
    scheme, _, target = rest.partition(":")
    scheme = scheme.strip().lower()
    if not re.fullmatch(r"[a-z][a-z0-9_-]*", scheme):
        raise LinkSpecError(f"link '{text}': '{scheme}' is not a link scheme (try {', '.join(link_schemes())})")
    return LinkSpec(scheme, target.strip(), node, options, text.strip())


def _strip_options(rest: str) -> tuple[str, dict[str, str]]:
    """`…,KEY=VALUE,…` at the end of `rest`: what is left and the options in the order written."""
    options: dict[str, str] = {}
    while (m := _OPTION.search(rest)) is not None:
        options[m.group(1).lower()] = m.group(2)
        rest = rest[:m.start()]
    return rest, dict(reversed(options.items()))


@dataclass(frozen=True)
class Scheme:
    name: str
    opener: Callable[[LinkSpec], Link]
    syntax: str
    help: str
    scan: Callable[[LinkSpec, Iterable[int]], list[int]] | None = None


_SCHEMES: dict[str, Scheme] = {}


def register_link_scheme(name: str, opener: Callable[[LinkSpec], Link], syntax: str, help: str = "",
                         scan: Callable[[LinkSpec, Iterable[int]], list[int]] | None = None) -> None:
    """Make `--link NAME:…` open links with `opener` (called with the parsed LinkSpec); `scan(spec, ids)`, when
    given, returns the controller ids of `ids` that answer on the spec's interface (the IDE's scan range)."""
    _SCHEMES[name.lower()] = Scheme(name.lower(), opener, syntax, help, scan)


def link_schemes() -> list[str]:
    _load_builtin_schemes()
    return sorted(_SCHEMES)


def scheme_help() -> str:
    """One line per scheme: its syntax and what it opens (for --help texts)."""
    _load_builtin_schemes()
    return "; ".join(f"{s.syntax} ({s.help})" if s.help else s.syntax for _, s in sorted(_SCHEMES.items()))


def open_link(text: str | LinkSpec) -> Link:
    """Open the link a spec names; LinkError naming the spec when the scheme is unknown or opening fails."""
    spec = text if isinstance(text, LinkSpec) else parse_link_spec(text)
    _load_builtin_schemes()
    scheme = _SCHEMES.get(spec.scheme)
    if scheme is None:
        raise _unknown(spec)
    return scheme.opener(spec)


def scan_controllers(text: str | LinkSpec, ids: Iterable[int]) -> list[int]:
    """The controllers of `ids` that answer on the interface of a spec (its node is ignored); a scheme without
    a scanner reports every id as present."""
    spec = text if isinstance(text, LinkSpec) else parse_link_spec(text)
    _load_builtin_schemes()
    scheme = _SCHEMES.get(spec.scheme)
    if scheme is None:
        raise _unknown(spec)
    return scheme.scan(spec, ids) if scheme.scan is not None else list(ids)


def _unknown(spec: LinkSpec) -> LinkError:
    if spec.scheme in SIMULATORS:   # a Python program that builds the IDE's parts itself (decision N56)
        return LinkError(f"link '{spec.text}': the simulators are not registered in this program; call "
                         "motiontool.controller.schemes.register() first, as the motiontool command does")
    return LinkError(f"link '{spec.text}': unknown scheme '{spec.scheme}' (known: {', '.join(link_schemes())})")


# --- the built-in schemes ---------------------------------------------------------------------------------------
MAX_REALTIME = 1000.0  # realtime=FACTOR: virtual time at most this much faster than real time
SIMULATORS = ("sim", "apcsim")   # the controller's side registers them (controller/schemes.py)

_loaded = False


def _load_builtin_schemes() -> None:
    """Register the wire schemes on first use (the FC and CANopen modules import pyserial/python-can, so they load
    only when a link is opened). The simulators (`sim`, `apcsim`) are the controller's side: the composition root
    registers them (controller/schemes.py), this package never imports them."""
    global _loaded
    if _loaded:
        return
    _loaded = True
    import_scheme_modules(BUILTIN_MODULES)


# modules that register a link scheme on import (comms/canopen is optional: skipped while it does not exist)
BUILTIN_MODULES = ("motiontool.comms.fc.link", "motiontool.comms.canopen.link")


def import_scheme_modules(modules) -> None:
    """Import the modules that register schemes; a module that does not exist is skipped, while a module that
    exists but fails (a missing dependency inside it) raises as usual."""
    import importlib

    for module in modules:
        try:
            importlib.import_module(module)
        except ModuleNotFoundError as exc:
            if exc.name is None or not module.startswith(exc.name):
                raise
