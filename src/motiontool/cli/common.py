"""What the sub-commands' parsers share: the parser class and the --link option."""

from __future__ import annotations

import argparse
import sys


class Parser(argparse.ArgumentParser):
    """Command-line errors exit 1 like every other refusal before anything ran (argparse's own would be 2, which
    `run` uses for a controller error; decisions R10). Sub-command parsers inherit this class."""

    def error(self, message: str):
        self.print_usage(sys.stderr)
        self.exit(1, f"{self.prog}: error: {message}\n")


def add_link_option(p: argparse.ArgumentParser, note: str) -> None:
    p.add_argument("--link", metavar="SPEC", help="the controller to talk to: sim (the embedded simulator, default) "
                   "or fc:URL[#ADDRESS][,baud=N,…], URL any pyserial URL (/dev/ttyUSB0, COM3, socket://HOST:PORT); "
                   f"see docs/link-protocol.md; {note}")
