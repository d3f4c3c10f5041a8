"""The fieldbus option's process data as COMOPTGET/COMOPTSEND copy it (CR 514-563): the same word area PCD[n]
reads and writes "without an additional command COMOPTGET or COMOPTSEND" (CR 3278-3281), one 16-bit word per
array element, word 1 in element 1 (K122)."""

from __future__ import annotations

from motiontool.kernel.command_base import command
from motiontool.kernel.errors import ControllerError


def _checked(args) -> tuple[int, object]:
    count, array = args
    if count < 0 or len(array) < count:   # CR 516: "an array which must be at least the size of no"
        raise ControllerError(171, f"{array.name} has {len(array)} elements, {count} words asked for")
    return count, array


@command("COMOPTGET")
def comoptget(ctl, vm, args):
    """CR 518-519: "reads from the Communication option buffer the no words and writes them in the array"."""
    count, array = _checked(args)
    for n in range(1, count + 1):
        word = ctl.pcd.get(n, 0) & 0xFFFF
        array.data[n - 1] = float(word) if array.type == "double" else word


@command("COMOPTSEND")
def comoptsend(ctl, vm, args):
    """CR 548-549: "the first 'no' values are sent from the 'array'" into the option's send buffer, a word each."""
    count, array = _checked(args)
    for n in range(1, count + 1):
        ctl.pcd[n] = int(array.data[n - 1]) & 0xFFFF
