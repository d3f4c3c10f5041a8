"""`motiontool params`: the MCO 305 parameters, one per line; with --link, read and write them on a controller
(decision F18)."""

from __future__ import annotations

import argparse
import re
import sys
from typing import TextIO

from motiontool.cli.common import add_link_option
from motiontool.cliargs import PARAMETER_VALUE, BadNumber, shown, whole
from motiontool.comms.protocol import LinkError

_LCP_RE = re.compile(r"([0-9]{1,2})-([0-9]{1,2})")


def add_parser(sub) -> argparse.ArgumentParser:
    p = sub.add_parser("params", help="list MCO 305 parameters, one per line")
    p.add_argument("--find", metavar="TEXT", help="only parameters whose number, name or text contains TEXT")
    p.add_argument("--group", metavar="PREFIX", help="only parameters of this group, e.g. 32-6")
    p.add_argument("--get", action="append", default=[], metavar="KEY", help="read a parameter from the controller")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="write a parameter on the controller (raw value) and read it back")
    add_link_option(p, "with --link alone: read the live value of every listed parameter")
    return p


def run(args: argparse.Namespace) -> int:
    from motiontool.paramdb import ParameterError, database

    try:
        db = database()
    except ParameterError as exc:
        print(f"motiontool params: {exc}", file=sys.stderr)
        return 1
    rows = list(db)
    if args.group:
        rows = [p for p in rows if p in db.group(args.group)]
    if args.find:
        found = set(db.find(args.find))
        rows = [p for p in rows if p in found]
    if args.link or args.get or args.set:  # live values from a controller
        return params_on_link(args.link, args.get, args.set, rows)
    for parameter in rows:
        print(parameter.format_line())
    return 0 if rows else 1


def _row(db, key: str, option: str) -> tuple[str, str]:
    """(what the link is asked for, the row's label) for a --get/--set KEY: an MCO 305 parameter from the database
    (`32-60 KPROP`), else an FC 300 parameter by its LCP number (`4-13`, decision K124, docs/fc300.md) which only the
    controller can know: the link's refusal names the key then. headless modules do not import the kernel."""
    from motiontool.paramdb import ParameterError

    key = key.strip()
    try:
        p = db.get(key)
    except ParameterError as exc:
        lcp = _LCP_RE.fullmatch(key)
        if lcp is None:
            raise LinkError(f"{option} {shown(key)}: {exc}") from None
        label = f"{int(lcp[1])}-{int(lcp[2]):02d}"
        return label, label
    return p.number, p.label


def params_on_link(spec: str | None, gets: list[str], sets: list[str], rows, out: TextIO | None = None,
                   err: TextIO | None = None) -> int:
    """`motiontool params --link SPEC [--set KEY=VALUE]… [--get KEY]…`: writes first (each read back), then reads;
    without --get/--set every parameter of `rows` is read. One line per parameter: `32-60 KPROP 50` (the raw
    value the link carries). Exit 0, or 1 after the first refusal (stderr names the parameter)."""
    from motiontool.headless import open_run_link  # the link machinery only when a controller is asked
    from motiontool.paramdb import database

    out, err = out or sys.stdout, err or sys.stderr  # looked up now: a caller may have redirected them
    db = database()
    try:
        link = open_run_link(spec)
    except LinkError as exc:
        print(f"motiontool params: {exc}", file=err)
        return 1
    try:
        for setting in sets:
            key, _, value = setting.partition("=")
            if not value:
                raise LinkError(f"--set needs KEY=VALUE with a whole number, got '{shown(setting)}'")
            target, label = _row(db, key, "--set")
            try:
                number = whole(value, f"--set {key.strip()}", *PARAMETER_VALUE, hex=True, sep="=")
            except BadNumber as exc:
                raise LinkError(str(exc)) from None
            _ask(link.write_parameter, f"--set {label}", target, number)
            print(f"{label} {_ask(link.read_parameter, f'--set {label}', target)}", file=out)
        for key in gets:
            target, label = _row(db, key, "--get")
            print(f"{label} {_ask(link.read_parameter, f'--get {label}', target)}", file=out)
        if not gets and not sets:
            for p in rows:
                print(f"{p.label} {link.read_parameter(p.number)}", file=out)
    except LinkError as exc:
        print(f"motiontool params: {exc}", file=err)
        return 1
    finally:
        link.close()
    return 0


def _ask(request, option: str, *args):
    """A parameter request on the link; its refusal names the key (`--get 4-99: error 112: Unknown param. …`)."""
    try:
        return request(*args)
    except LinkError as exc:
        raise LinkError(f"{option}: {exc}") from None
