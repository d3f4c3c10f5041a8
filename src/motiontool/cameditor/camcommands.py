"""The `motiontool cam` commands (build, info, export, import); their parser is in camcli.py.  Qt-free.

Every command takes the argparse Namespace and returns the exit code (0 ok, 1 error on stderr).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from motiontool.camcurve.layout import CurveArrayError, element_count
from motiontool.camcurve.model import Curve, CurveError, CurveType, FixPoint, StartStopPair, default_pairs
from motiontool.cameditor.dat import DatError, read_dat, write_dat
from motiontool.cameditor.zbc import ConfigError, ConfigFile, read_config, write_config


class _InputError(ValueError):
    pass


def _number(text: str, what: str) -> int | float:
    text = text.strip()
    try:
        return int(text)
    except ValueError:
        pass
    try:
        value = float(text)
    except ValueError:
        raise _InputError(f"{what}: {text!r} is not a number") from None
    if value != value or value in (float("inf"), float("-inf")):
        raise _InputError(f"{what}: {text!r} is not a finite number")
    return value


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
    if key.isdigit() and int(key) in CurveType._value2member_map_:
        return CurveType(int(key))
    if key in CurveType.__members__:
        return CurveType[key]
    raise _InputError(f"--curve-type: {text!r} is not 0..4 or one of {', '.join(CurveType.__members__)}")


def _fmt(value: float) -> str:
    return str(int(value)) if float(value).is_integer() else repr(float(value))


def build_curve(args: argparse.Namespace) -> Curve:
    """The Curve the `cam build` options describe; raises CurveError or ValueError with a readable message."""
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
    intervals = args.intervals.strip()
    if not intervals.lstrip("+-").isdigit():
        raise _InputError(f"--intervals: {args.intervals!r} is not an integer")
    return Curve(args.name, master_length, points, interpolation=not args.no_interpolation, intervals=int(intervals),
                 curve_type=_curve_type(args.curve_type), start_stop_pairs=pairs, **kw)  # type: ignore[arg-type]


def cmd_build(args: argparse.Namespace) -> int:
    prog = "motiontool cam build"
    try:
        curve = build_curve(args)
    except (CurveError, _InputError) as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 1
    return _add_curve(prog, args.output, curve)


def _add_curve(prog: str, out: Path, curve: Curve) -> int:
    """Add ``curve`` to the .zbc file ``out`` (created when missing); 1 after printing the error."""
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
    except OSError as exc:
        print(f"{prog}: error: cannot write {out}: {exc.strerror or exc}", file=sys.stderr)
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
        print(f"{prog}: error: cannot write {args.output}: {exc.strerror or exc}", file=sys.stderr)
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
