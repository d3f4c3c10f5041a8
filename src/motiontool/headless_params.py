"""`motiontool params --link SPEC`: read and write parameters of a controller over a link (decision F18)."""

from __future__ import annotations

import sys
from typing import TextIO

from motiontool.cliargs import PARAMETER_VALUE, BadNumber, shown, whole
from motiontool.comms.protocol import LinkError
from motiontool.headless import open_run_link


def params_on_link(spec: str | None, gets: list[str], sets: list[str], rows, out: TextIO | None = None,
                   err: TextIO | None = None) -> int:
    """`motiontool params --link SPEC [--set KEY=VALUE]… [--get KEY]…`: writes first (each read back), then reads;
    without --get/--set every parameter of `rows` is read. One line per parameter: `32-60 KPROP 50` (the raw
    value the link carries). Exit 0, or 1 after the first refusal (stderr names the parameter)."""
    from motiontool.paramdb import ParameterError, database

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
            try:
                p = db.get(key.strip())
                number = whole(value, f"--set {key.strip()}", *PARAMETER_VALUE, hex=True, sep="=")
            except ParameterError as exc:
                raise LinkError(f"--set {setting}: {exc}") from None
            except BadNumber as exc:
                raise LinkError(str(exc)) from None
            link.write_parameter(p.number, number)
            print(f"{p.label} {link.read_parameter(p.number)}", file=out)
        for key in gets:
            try:
                p = db.get(key.strip())
            except ParameterError as exc:
                raise LinkError(f"--get {key}: {exc}") from None
            print(f"{p.label} {link.read_parameter(p.number)}", file=out)
        if not gets and not sets:
            for p in rows:
                print(f"{p.label} {link.read_parameter(p.number)}", file=out)
    except LinkError as exc:
        print(f"motiontool params: {exc}", file=err)
        return 1
    finally:
        link.close()
    return 0
