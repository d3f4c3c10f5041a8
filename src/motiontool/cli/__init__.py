"""`motiontool` entry point: the IDE by default, sub-commands for headless work. Each sub-command is a module of this
package with `add_parser(subparsers)` (returns its parser) and `run(args) -> int` (the exit code), listed in
COMMANDS in the order `motiontool --help` shows them."""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Sequence
from pathlib import Path

from motiontool import __version__, cliargs
from motiontool.cli import cam, check, compile, drive, params, run, sweep
from motiontool.cli.common import Parser
from motiontool.cliargs import OutputIsInput, Refused

COMMANDS = (params, check, compile, run, drive, cam, sweep)


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(
        prog="motiontool",
        description="Engineering IDE for the MCO 305 motion controller. Without a sub-command the IDE opens.")
    parser.add_argument("--version", action="version", version=f"motiontool {__version__}")
    parser.add_argument("--screenshot", type=Path, metavar="PATH",
                        help="open the window, save a PNG of it once painted, and exit")
    parser.add_argument("--open", type=Path, metavar="FILE", dest="open_file",
                        help="open this program in the editor")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for command in COMMANDS:
        command.add_parser(sub).set_defaults(func=command.run)
    return parser


def _files(args: argparse.Namespace) -> tuple[list[tuple[str, Path]], list[tuple[str, Path]]]:
    """(outputs, inputs) of a sub-command, each with the option that names it. `cam build -o` is left out: it
    reads and extends that file by design."""
    inputs = [(label, getattr(args, attr)) for attr, label in (("file", ""), ("dat", ""),
                                                               ("config", "--config"))
              if getattr(args, attr, None) is not None]
    nodes = getattr(args, "node", None) or []
    inputs += [("--node", Path(spec.partition(":")[2].strip())) for spec in nodes if spec.partition(":")[2].strip()]
    outputs = [(option, getattr(args, attr)) for attr, option in (("output", "-o"), ("trace", "--trace"))
               if getattr(args, attr, None) is not None and not (args.command == "cam" and args.cam_command == "build")]
    record = getattr(args, "record", None)
    if record is not None:  # several nodes record into OUT-nodeID.csv (headless._record_path)
        ids = ([1] if args.file is not None else []) + [int(m.group(1)) for spec in nodes
                                                         if (m := re.match(r"\s*([0-9]{1,2})\s*:", spec))]
        outputs += [("--record", record.with_name(f"{record.stem}-node{n}{record.suffix}")) for n in ids] \
            if nodes else [("--record", record)]
    return outputs, inputs


def main(argv: Sequence[str] | None = None) -> int:
    from motiontool.controller import schemes

    schemes.register()  # the composition root: `sim` and `apcsim` links open the simulators (issue 27 item 3)
    try:  # a refused number surfaces from parse_args as Refused, its line complete (cliargs.Number)
        args = build_parser().parse_args(argv)
    except Refused as exc:
        print(exc, file=sys.stderr)
        return 1
    if args.command is None:
        from motiontool.ui.app import run_gui

        return run_gui(open_file=args.open_file, screenshot=args.screenshot)
    prog = " ".join(["motiontool", args.command, getattr(args, "cam_command", None) or ""]).strip()
    try:
        cliargs.refuse_overwriting_inputs(*_files(args))  # before anything is compiled, run or written
        return args.func(args)
    except (Refused, OutputIsInput) as exc:
        print(exc if isinstance(exc, Refused) else f"{prog}: {exc}", file=sys.stderr)
        return 1
