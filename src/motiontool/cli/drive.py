"""`motiontool drive`: simulated controllers in their own process behind listeners; the drive itself is
motiontool.controller.drive.command (DriveOptions, run_drive)."""

from __future__ import annotations

import argparse
from pathlib import Path

from motiontool.cliargs import NODE_ID, number_option
from motiontool.controller.drive.command import MAX_SPEED, MAX_TIMEOUT_S, DriveOptions, run_drive
from motiontool.controller.drive.simulator import CLOCKS, REACTIONS


def add_parser(sub) -> argparse.ArgumentParser:
    from motiontool.controller.drive.listeners import listener_schemes

    schemes = "; ".join(f"{s.syntax} ({s.help})" for s in listener_schemes())
    p = sub.add_parser("drive", help="serve simulated controllers to wire links (a virtual drive)",
                       description="Run simulated MCO 305 controllers in this process, paced at real time, and "
                                   "serve them over a wire protocol. Prints 'listening on URL' per listener when "
                                   "ready (URL is the --link of a master); stops cleanly on SIGINT/SIGTERM. "
                                   f"Listeners: {schemes}.")
    p.add_argument("--listen", action="append", required=True, metavar="SPEC",
                   help="where to serve, e.g. fc:socket://127.0.0.1:4001 (port 0: any free port) or fc:pty; "
                        "repeatable")
    p.add_argument("--node", action="append", default=[], metavar="ID[:PROGRAM.m]",
                   help="a controller with bus address/node id ID (1..32), optionally running PROGRAM.m (saved as "
                        "program 0 and started); repeatable; default: one controller, ID 1")
    number_option(p, "--master-node", lo=NODE_ID[0], hi=NODE_ID[1], integer=True, metavar="ID",
                  help="the node whose virtual master (PULSVEL) drives the master input of all the others")
    p.add_argument("--clock", choices=CLOCKS, default="realtime",
                   help="realtime (default): time runs by itself; virtual: it moves only when a master sends "
                        "advance (reproducible runs, as the embedded simulator)")
    number_option(p, "--speed", lo=0, hi=MAX_SPEED, above=True, default=1.0,
                  help="real-time factor of the realtime clock (default 1)")
    number_option(p, "--timeout", lo=0, hi=MAX_TIMEOUT_S, above=True, metavar="S", dest="timeout_s",
                  help="link timeout: react when a master that talked to a node is silent this long")
    p.add_argument("--timeout-reaction", choices=REACTIONS, default="stop",
                   help="what a running program does on a link timeout (default stop)")
    p.add_argument("--include", "-I", action="append", type=Path, default=[], metavar="DIR")
    p.add_argument("--stop-with-parent", action="store_true",
                   help="also stop when stdin reaches its end or the process that started the drive goes away (for "
                        "scripts and tests: a drive they start never outlives them)")
    return p


def run(args: argparse.Namespace) -> int:
    return run_drive(DriveOptions(args.listen, args.node, args.master_node, args.clock, args.speed, args.timeout_s,
                                  args.timeout_reaction, args.include, args.stop_with_parent))
