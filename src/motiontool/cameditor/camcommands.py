"""The `motiontool cam` commands (build, info, export, import); their parser is in cli/cam.py.  Qt-free.

Every command takes the argparse Namespace and returns the exit code (0 ok, 1 error on stderr).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from motiontool.camcurve.layout import CurveArrayError, element_count
from motiontool.camcurve.model import (
    MAX_INTERVALS,
    Curve,
    CurveError,
    CurveType,
    FixPoint,
    StartStopPair,
    default_pairs,
)
from motiontool.cliargs import BadNumber, real, whole
from motiontool.fileio import check_writable, write_error
from motiontool.formats.dat import DatError, read_dat, write_dat
from motiontool.formats.zbc import ConfigError, ConfigFile, read_config, write_config


class _InputError(ValueError):
    pass


LONG = (-(1 << 31), (1 << 31) - 1)  # a curve's positions end up in controller longs


def _number(text: str, what: str) -> int | float:
    """A whole or decimal number in long range by cliargs (ASCII digits, finite): "٥" and "1e999" are refused."""
    try:
        return whole(text, what, *LONG)
    except BadNumber:
        pass
    try:
        return real(text, what, *LONG)
    except BadNumber as exc:
        raise _InputError(str(exc)) from None


def _numbers(text: str, count: int, what: str, example: str) -> list[int | float]:
    parts = text.split(",")
    if len(parts) != count:
        raise _InputError(f"{what}: expected {example}, got {text!r}")
    return [_number(p, what) for p in parts]


def _point(text: str) -> FixPoint:
    parts = text.split(",")
    if len(parts) not in (2, 3):
        raise _InputError(f"--point: expected MASTER,SLAVE[,TYPE], got {text!r}")
    kind = parts[2].strip().upper() if len(parts) == 3 else "C"
    return FixPoint(_number(parts[0], "--point"), _number(parts[1], "--point"), kind)


def _curve_type(text: str) -> CurveType:
    key = text.strip().upper()
    if key in {str(v) for v in CurveType._value2member_map_}:  # not isdigit(): "٢" is no curve type
        return CurveType(int(key))
    if key in CurveType.__members__:
        return CurveType[key]
    raise _InputError(f"--curve-type: {text!r} is not 0..4 or one of {', '.join(CurveType.__members__)}")


def _fmt(value: float) -> str:
    return str(int(value)) if float(value).is_integer() else repr(float(value))


def build_curve(args: argparse.Namespace) -> Curve:
    """The Curve the `cam build` options describe; raises CurveError or ValueError with a readable message."""
    if not args.name.strip():  # a program could not DIM or SETCURVE an array without a name
        raise _InputError(f"--name {args.name!r}: give the curve a name of 1 to 16 characters")
    points = tuple(_point(p) for p in args.point)
    if not points:
        raise _InputError("--point: at least one fix point is needed (the curve needs 4 for the controller)")
    master_length = (_number(args.master_length, "--master-length") if args.master_length is not None
                     else points[-1].master)
    pairs = default_pairs() + tuple(StartStopPair(*_numbers(p, 2, "--pair", "START,STOP")) for p in args.pair)
    kw: dict[str, object] = {}
    if args.correction is not None:
        kw["correction_start"], kw["correction_end"] = _numbers(args.correction, 2, "--correction", "START,END")
    if args.marker is not None:
        kw["master_marker_pos"], kw["slave_marker_pos"] = _numbers(args.marker, 2, "--marker", "MASTER,SLAVE")
    if args.gradients is not None:
        kw["start_gradient"], kw["end_gradient"] = _numbers(args.gradients, 2, "--gradients", "START,END")
    for option, key in (("slave_stop", "slave_stop_position"), ("max_correction", "max_correction"),
                        ("cycles_per_min", "cycles_per_min")):
        value = getattr(args, option)
        if value is not None:
            kw[key] = _number(value, "--" + option.replace("_", "-"))
    try:
        intervals = whole(args.intervals, "--intervals", 1, MAX_INTERVALS)
    except BadNumber as exc:
        raise _InputError(str(exc)) from None
    return Curve(args.name, master_length, points, interpolation=not args.no_interpolation, intervals=intervals,
                 curve_type=_curve_type(args.curve_type), start_stop_pairs=pairs, **kw)  # type: ignore[arg-type]


def cmd_build(args: argparse.Namespace) -> int:
    prog = "motiontool cam build"
    try:
        curve = build_curve(args)
    except (CurveError, _InputError) as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 1
    return _add_curve(prog, args.output, curve)


def _writable(prog: str, out: Path) -> bool:
    """Whether ``out`` can be written (fileio.check_writable: a name beyond NAME_MAX, a missing folder…); else
    False after the one line ``cannot write OUT: reason``."""
    try:
        check_writable(out)
    except OSError as exc:
        print(f"{prog}: error: {write_error(out, exc)}", file=sys.stderr)
        return False
    return True


def _add_curve(prog: str, out: Path, curve: Curve) -> int:
    """Add ``curve`` to the .zbc file ``out`` (created when missing); 1 after printing the error."""
    if not _writable(prog, out):
        return 1
    try:
        config = read_config(out) if out.exists() else ConfigFile()
    except ConfigError as exc:
        print(f"{prog}: error: cannot add to {out}: {exc}", file=sys.stderr)
        return 1
    try:
        config.add_curve(curve)
        write_config(out, config)
    except (CurveError, ConfigError) as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 1
    except OSError as exc:  # a full disk, a file-size limit: the old file stays (fileio's atomic save)
        print(f"{prog}: error: {write_error(out, exc)}", file=sys.stderr)
        return 1
    return 0


def cmd_info(args: argparse.Namespace) -> int:
    try:
        config = read_config(args.file)
    except ConfigError as exc:
        print(f"motiontool cam info: error: {exc}", file=sys.stderr)
        return 1
    for curve in config.curves:
        array = next((a for a in config.arrays if a.curve == curve.name), None)
        count = len(array.values) if array is not None else element_count(curve)
        print(f"{curve.name}: {count} elements, master {_fmt(curve.master_length)}, slave {_fmt(curve.slave_length)}, "
              f"{curve.intervals} intervals")
    return 0


def cmd_export(args: argparse.Namespace) -> int:
    prog = "motiontool cam export"
    if not _writable(prog, args.output):
        return 1
    try:
        config = read_config(args.file)
    except ConfigError as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 1
    curve = config.curve(args.curve) if args.curve is not None else (config.curves[0] if config.curves else None)
    if curve is None:
        print(f"{prog}: error: {args.file}: no curve {args.curve or ''}".rstrip(), file=sys.stderr)
        return 1
    try:
        write_dat(args.output, curve)
    except OSError as exc:
        print(f"{prog}: error: {write_error(args.output, exc)}", file=sys.stderr)
        return 1
    return 0


def cmd_import(args: argparse.Namespace) -> int:
    prog = "motiontool cam import"
    try:
        curve = read_dat(args.dat).to_curve()
    except DatError as exc:  # names the .dat file
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 1
    except (CurveError, CurveArrayError) as exc:
        print(f"{prog}: error: {args.dat}: {exc}", file=sys.stderr)
        return 1
    except OSError as exc:
        print(f"{prog}: error: cannot read {args.dat}: {exc.strerror or exc}", file=sys.stderr)
        return 1
    return _add_curve(prog, args.output, curve)
