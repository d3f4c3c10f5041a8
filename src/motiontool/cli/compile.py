"""`motiontool compile`: an APOSS program to a program image."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path


def add_parser(sub) -> argparse.ArgumentParser:
    p = sub.add_parser("compile", help="compile an APOSS program to a program image")
    p.add_argument("file", type=Path, metavar="FILE")
    p.add_argument("-o", "--output", type=Path, required=True, metavar="OUT")
    p.add_argument("--include", "-I", action="append", type=Path, default=[], metavar="DIR")
    p.add_argument("--debug", action="store_true", help="keep what a debugger needs (statement stops)")
    return p


def run(args: argparse.Namespace) -> int:
    from motiontool.aposs.driver import compile_file

    return compile_file(args.file, args.output, include_dirs=args.include, debug=args.debug,
                        out=sys.stdout)
