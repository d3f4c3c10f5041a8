"""`motiontool check`: syntax-check APOSS and DPL programs, GCC-style diagnostics."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path


def add_parser(sub) -> argparse.ArgumentParser:
    p = sub.add_parser("check", help="syntax-check APOSS programs and DPL programs (FILE.dpl) (GCC-style diagnostics)")
    p.add_argument("files", nargs="+", type=Path, metavar="FILE")
    p.add_argument("--include", "-I", action="append", type=Path, default=[], metavar="DIR",
                   help="extra system include directory for #include <file>")
    return p


def run(args: argparse.Namespace) -> int:
    from motiontool.aposs.driver import check_files
    from motiontool.dpl.driver import check_files as check_dpl_files
    from motiontool.dpl.driver import is_dpl

    failed = 0
    for path in args.files:  # in the order given; .dpl files are DPL (APC), the others APOSS
        failed |= check_dpl_files([path], sys.stdout) if is_dpl(path) else check_files([path], args.include, sys.stdout)
    return failed
