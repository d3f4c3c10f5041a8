"""`motiontool` entry point: the IDE by default, sub-commands for headless work."""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Sequence
from pathlib import Path

from motiontool import __version__, cliargs
from motiontool.cliargs import MAX_RUN_SECONDS, NODE_ID, OutputIsInput, Refused, number_option


def _cmd_params(args: argparse.Namespace) -> int:
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
        from motiontool.headless_params import params_on_link

        return params_on_link(args.link, args.get, args.set, rows)
    for parameter in rows:
        print(parameter.format_line())
    return 0 if rows else 1


def _cmd_check(args: argparse.Namespace) -> int:
    from motiontool.aposs.driver import check_files
    from motiontool.dpl.driver import check_files as check_dpl_files
    from motiontool.dpl.driver import is_dpl

    failed = 0
    for path in args.files:  # in the order given; .dpl files are DPL (APC), the others APOSS
        failed |= check_dpl_files([path], sys.stdout) if is_dpl(path) else check_files([path], args.include, sys.stdout)
    return failed


def _cmd_compile(args: argparse.Namespace) -> int:
    from motiontool.aposs.driver import compile_file

    return compile_file(args.file, args.output, include_dirs=args.include, debug=args.debug,
                        out=sys.stdout)


def _cmd_run(args: argparse.Namespace) -> int:
    from motiontool.headless import RunOptions, run_program

    options = RunOptions(seconds=args.seconds, settings=args.set, inputs=args.input, include_dirs=args.include,
                         trace=args.trace, signals=[s for s in args.signals.split(",") if s.strip()],
                         trace_interval_ms=args.interval, record=args.record, realtime=args.realtime,
                         config=args.config, nodes=args.node, master_node=args.master_node, link=args.link,
                         timeout=args.timeout, ctsync_wires=int(args.ctsync_wires))
    if args.master_node is not None and not args.node:
        print("motiontool run: --master-node needs --node (several controllers)", file=sys.stderr)
        return 1
    if args.file is None and not args.node:
        print("motiontool run: give FILE.m, or --node ID:PROGRAM.m for several controllers", file=sys.stderr)
        return 1
    return run_program(args.file, options)


def _add_link_option(p: argparse.ArgumentParser, note: str) -> None:
    p.add_argument("--link", metavar="SPEC", help="the controller to talk to: sim (the embedded simulator, default) "
                   "or fc:URL[#ADDRESS][,baud=N,…], URL any pyserial URL (/dev/ttyUSB0, COM3, socket://HOST:PORT); "
                   f"see docs/link-protocol.md; {note}")


class _Parser(argparse.ArgumentParser):
    """Command-line errors exit 1 like every other refusal before anything ran (argparse's own would be 2, which
    `run` uses for a controller error; decisions R10). Sub-command parsers inherit this class."""

    def error(self, message: str):
        self.print_usage(sys.stderr)
        self.exit(1, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="motiontool",
        description="Engineering IDE for the MCO 305 motion controller. Without a sub-command the IDE opens.")
    parser.add_argument("--version", action="version", version=f"motiontool {__version__}")
    parser.add_argument("--screenshot", type=Path, metavar="PATH",
                        help="open the window, save a PNG of it once painted, and exit")
    parser.add_argument("--open", type=Path, metavar="FILE", dest="open_file",
                        help="open this program in the editor")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    p = sub.add_parser("params", help="list MCO 305 parameters, one per line")
    p.add_argument("--find", metavar="TEXT", help="only parameters whose number, name or text contains TEXT")
    p.add_argument("--group", metavar="PREFIX", help="only parameters of this group, e.g. 32-6")
    p.add_argument("--get", action="append", default=[], metavar="KEY", help="read a parameter from the controller")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="write a parameter on the controller (raw value) and read it back")
    _add_link_option(p, "with --link alone: read the live value of every listed parameter")
    p.set_defaults(func=_cmd_params)

    p = sub.add_parser("check", help="syntax-check APOSS programs and DPL programs (FILE.dpl) (GCC-style diagnostics)")
    p.add_argument("files", nargs="+", type=Path, metavar="FILE")
    p.add_argument("--include", "-I", action="append", type=Path, default=[], metavar="DIR",
                   help="extra system include directory for #include <file>")
    p.set_defaults(func=_cmd_check)

    p = sub.add_parser("compile", help="compile an APOSS program to a program image")
    p.add_argument("file", type=Path, metavar="FILE")
    p.add_argument("-o", "--output", type=Path, required=True, metavar="OUT")
    p.add_argument("--include", "-I", action="append", type=Path, default=[], metavar="DIR")
    p.add_argument("--debug", action="store_true", help="keep what a debugger needs (statement stops)")
    p.set_defaults(func=_cmd_compile)

    p = sub.add_parser("run", help="run a program on the embedded simulated controller",
                       description="stdout: exactly the program's PRINT output; stderr: controller errors. "
                                   "Exit 0 when the program ends or the time is up, 1 on a compile error or a "
                                   "refused file, option or output path, 2 on an unhandled controller error. "
                                   "With --node, several controllers (node "
                                   "ids 1..32) run in lockstep on one master signal: FILE.m (optional then) on "
                                   "node 1, each --node ID:PROGRAM.m on node ID; the virtual master (PULSVEL) of "
                                   "--master-node is the master input of all the others; each output line is "
                                   "prefixed with its node id ('2: text'), --trace columns are 'ID:SIGNAL', "
                                   "--record writes OUT-nodeID.csv; the time ends when every program has stopped. "
                                   "FILE.dpl (with --node ID:OTHER.dpl): DPL programs on simulated APCs (Unidrive "
                                   "SP), several on one CTSync line; --set [ID:]MM.PP=VALUE[@MS] (docs/dpl.md).")
    p.add_argument("file", type=Path, metavar="FILE.m|FILE.dpl", nargs="?")
    p.add_argument("--node", action="append", default=[], metavar="ID:PROGRAM.m",
                   help="also run PROGRAM.m on controller ID (1..32) of the same simulated project; repeatable")
    number_option(p, "--master-node", lo=NODE_ID[0], hi=NODE_ID[1], integer=True, metavar="ID",
                  help="with --node: the node whose virtual master (PULSVEL) drives the master input of all the "
                       "others (default: the lowest node id)")
    number_option(p, "--seconds", lo=0, hi=MAX_RUN_SECONDS, above=True, default=60.0,
                  help="virtual time to run at most (default 60)")
    p.add_argument("--set", action="append", default=[], metavar="[ID:]NAME=VALUE",
                   help="set a parameter before the start, e.g. KPROP=50 or 32-60=50; with ID: only on that node; "
                        "FILE.dpl: a drive parameter MM.PP=VALUE[@MS], at MS ms (1.11=0@2000 stops the drive)")
    p.add_argument("--input", action="append", default=[], metavar="[ID:]N=V@T",
                   help="set digital input N to V at T ms (default 0); with ID: only on that node; FILE.dpl: "
                        "DIGIN0=V (the freeze input, also 0=V), REF_MARKER=1 or FB_MARKER=1 (a marker pulse)")
    p.add_argument("--ctsync-wires", choices=("2", "4"), default="2", metavar="2|4",
                   help="FILE.dpl with --node: the CTSync line's RS485 wiring, 2-wire (up to 8 nodes, the "
                        "default) or 4-wire (up to 16)")
    p.add_argument("--include", "-I", action="append", type=Path, default=[], metavar="DIR")
    p.add_argument("--config", type=Path, metavar="CONF.zbc",
                   help="load parameters and arrays first (with --node: into every node)")
    p.add_argument("--trace", type=Path, metavar="OUT.csv", help="write a trace of --signals")
    p.add_argument("--signals", default="APOS,CPOS,TRACKERR",
                   help="comma-separated signal names (FILE.dpl: read parameters such as APC_FB_POS or 48, drive "
                        "parameters such as 18.12; default APC_FB_POS,APC_TOT_POS_REF,APC_POS_ERROR)")
    number_option(p, "--interval", lo=1, hi=MAX_TRACE_INTERVAL_MS, integer=True, default=1, metavar="MS",
                  help="trace interval (default 1 ms)")
    p.add_argument("--record", type=Path, metavar="OUT.csv", help="write every TESTSETP recording as CSV")
    p.add_argument("--realtime", action="store_true", help="pace virtual time at real time")
    _add_link_option(p, "--seconds then counts the controller's own time")
    number_option(p, "--timeout", lo=0, hi=MAX_RUN_SECONDS, default=30.0, metavar="S",
                  help="with --link: how long a lost connection may last; the run waits for the link, says so on "
                       "stderr and goes on (default 30 s, 0: end the run at once)")
    p.set_defaults(func=_cmd_run)

    from motiontool.controller.drive.command import add_parser as add_drive_parser

    add_drive_parser(sub)

    from motiontool.cameditor import camcli

    camcli.add_parser(sub)

    from motiontool import sweepcli

    sweepcli.add_parser(sub)
    return parser


MAX_TRACE_INTERVAL_MS = 3600 * 1000  # an hour between trace rows


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


if __name__ == "__main__":
    sys.exit(main())
