"""`motiontool run`: a program on the embedded simulated controller, several on one master (--node), DPL programs on
simulated APCs (FILE.dpl), or a program on a controller behind --link; the run itself is motiontool.headless."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from motiontool.cli.common import add_link_option
from motiontool.cliargs import MAX_RUN_SECONDS, NODE_ID, number_option

MAX_TRACE_INTERVAL_MS = 3600 * 1000  # an hour between trace rows


def add_parser(sub) -> argparse.ArgumentParser:
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
    add_link_option(p, "--seconds then counts the controller's own time")
    number_option(p, "--timeout", lo=0, hi=MAX_RUN_SECONDS, default=30.0, metavar="S",
                  help="with --link: how long a lost connection may last; the run waits for the link, says so on "
                       "stderr and goes on (default 30 s, 0: end the run at once)")
    return p


def run(args: argparse.Namespace) -> int:
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
