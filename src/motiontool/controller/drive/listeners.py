"""How the virtual drive is reached: a registry of listener schemes, one per protocol.

`motiontool drive --listen SPEC` parses SPEC with the link syntax (comms/links.py) and calls the factory
registered for its scheme with the spec and the running `VirtualDrive`. A factory returns a `Listener`: it serves
in its own threads, `url` is the link spec a master passes to `--link` (printed as ``listening on URL``), and
`close()` stops it. The FC protocol registers ``fc`` (controller/fc/server.py); another protocol registers its own
(``canopen:slcan:socket://…``) the same way.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

from motiontool.cliargs import PORT, BadNumber, shown, whole
from motiontool.comms.links import LinkSpec, import_scheme_modules, parse_link_spec
from motiontool.comms.protocol import LinkError


class Listener(Protocol):
    url: str

    def close(self) -> None: ...


@dataclass(frozen=True)
class ListenerScheme:
    name: str
    factory: Callable[[LinkSpec, object], Listener]
    syntax: str
    help: str


_SCHEMES: dict[str, ListenerScheme] = {}
# modules that register a listener scheme on import (a missing optional module is skipped)
BUILTIN_MODULES = ("motiontool.controller.fc.server", "motiontool.controller.canopen.server")


def register_listener_scheme(name: str, factory: Callable[[LinkSpec, object], Listener], syntax: str,
                             help: str = "") -> None:
    _SCHEMES[name.lower()] = ListenerScheme(name.lower(), factory, syntax, help)


def _load() -> None:
    import_scheme_modules(BUILTIN_MODULES)


def listener_schemes() -> list[ListenerScheme]:
    _load()
    return [s for _, s in sorted(_SCHEMES.items())]


def listen_port(spec: LinkSpec, text: str) -> int:
    """The TCP port of a listener spec (0: any free port); LinkError naming the spec and the range."""
    try:
        return whole(text, f"--listen '{shown(spec.text)}': port", *PORT)
    except BadNumber as exc:
        raise LinkError(str(exc)) from None


def open_listener(text: str, drive) -> Listener:
    """Start serving `drive` as SPEC says; LinkError naming the spec when it cannot."""
    spec = parse_link_spec(text)
    _load()
    scheme = _SCHEMES.get(spec.scheme)
    if scheme is None:
        known = ", ".join(s.syntax for s in listener_schemes()) or "none"
        raise LinkError(f"--listen '{text}': unknown scheme '{spec.scheme}' (known: {known})")
    return scheme.factory(spec, drive)


LOOPBACK = ("127.0.0.1", "localhost", "::1")


def url_host(host: str) -> str:
    return f"[{host}]" if ":" in host else host


def exposed(spec: LinkSpec, host: str) -> bool:
    """True when a listener on `host` serves beyond this machine; that needs the opt-in `,any_host=1` (LinkError
    without it): the virtual drive has no authentication (issue 24 item 7). Say it with `warn_exposed`."""
    if host in LOOPBACK:
        return False
    if not spec.option("any_host", False, lambda v: v == "1"):
        raise LinkError(f"--listen '{shown(spec.text)}': listen on 127.0.0.1 (add ,any_host=1 to listen on {host}: "
                        "anyone who reaches it can control the drive)")
    return True


def warn_exposed(url: str) -> None:
    print(f"motiontool drive: WARNING: {url} serves the network without authentication: anyone who reaches it "
          "can download and start programs, write parameters and reset the controller", file=sys.stderr, flush=True)


def refuse(sock, url: str, limit: int, who: str, refused: int) -> int:
    """Close a connection beyond a listener's `limit` at once, and say so on stderr the first time; the count of
    refusals after it."""
    sock.close()
    if not refused:
        print(f"motiontool drive: {url}: a connection was refused: {limit} {who} are connected already",
              file=sys.stderr, flush=True)
    return refused + 1
