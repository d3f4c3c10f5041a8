"""`motiontool cam` sub-commands: build a curve into a .zbc file, list the curves of a file.  Qt-free.

The commands and the curve maths (scipy) are in cameditor/camcommands.py, imported when a ``cam`` command runs, so
building the top-level parser costs nothing at GUI start; each takes the argparse Namespace and returns the exit
code (0 ok, 1 error on stderr).
"""

from __future__ import annotations

import argparse
from pathlib import Path


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Add ``cam`` (build, info, export, import) to a top-level ``add_subparsers()`` object."""
    cam = subparsers.add_parser("cam", help="CAM curves in .zbc configuration files",
                                description="Build CAM curves into .zbc/.cnf configuration files and list them "
                                            "(format: docs/formats/zbc.md).")
    sub = cam.add_subparsers(dest="cam_command", metavar="CAM_COMMAND", required=True)

    p = sub.add_parser("build", help="create FILE.zbc or add/replace a curve in it",
                       description="Exit 0 silently on success, 1 with a message naming the field on bad input.")
    p.add_argument("--name", required=True, help="curve (and array) name, at most 16 characters")
    p.add_argument("--master-length", metavar="L", help="master cycle length in MU (default: last point)")
    p.add_argument("--intervals", default="40", metavar="K", help="number of interpolation intervals (default 40)")
    p.add_argument("--point", action="append", default=[], metavar="M,S[,TYPE]",
                   help="fix point, TYPE C (default), T, CZ, C3 or a VDI 2143 motion law for the segment ending "
                        "there: P345, MSIN, CYCL, MTRAP, HARM; repeat in master order")
    p.add_argument("--pair", action="append", default=[], metavar="A,B",
                   help="start/stop pair 1, 2, ... (pair 0, Start = Stop = 0, is always added)")
    p.add_argument("--slave-stop", metavar="P", help="slave stop position")
    p.add_argument("--correction", metavar="START,END", help="correction window (master positions)")
    p.add_argument("--max-correction", metavar="C", help="maximum correction")
    p.add_argument("--marker", metavar="MASTER,SLAVE", help="master and slave marker positions")
    p.add_argument("--cycles-per-min", metavar="C", help="master cycles per minute (default 60)")
    p.add_argument("--curve-type", default="0", metavar="T",
                   help="0..4 or AVERAGE_GRADIENTS, END_EQUALS_START, ZERO_GRADIENTS, SPECIFIED_GRADIENTS, "
                        "SPECIFIED_IMMEDIATE (default 0)")
    p.add_argument("--gradients", metavar="START,END", help="start/end gradients (UU/MU) of the SPECIFIED types")
    p.add_argument("--no-interpolation", action="store_true", help="store no interpolation points")
    p.add_argument("-o", "--output", type=Path, required=True, metavar="FILE.zbc")

    p = sub.add_parser("info", help="one line per curve: NAME: N elements, master L, slave S, K intervals")
    p.add_argument("file", type=Path, metavar="FILE.zbc")

    p = sub.add_parser("export", help="write one curve's controller array as a .dat file")
    p.add_argument("file", type=Path, metavar="FILE.zbc")
    p.add_argument("--curve", help="curve name (default: the first curve)")
    p.add_argument("-o", "--output", type=Path, required=True, metavar="CURVE.dat")

    p = sub.add_parser("import", help="add/replace a curve from a .dat file written by export")
    p.add_argument("dat", type=Path, metavar="CURVE.dat")
    p.add_argument("-o", "--output", type=Path, required=True, metavar="FILE.zbc")
    return cam


def run(args: argparse.Namespace) -> int:
    from motiontool.cameditor import camcommands

    return getattr(camcommands, f"cmd_{args.cam_command}")(args)
