"""CTSync: several drives on one RS485 line running their POS tasks in lockstep (seed 004 §4.10 L2058-2101,
§5.2.3 L3241-3288, §7.5-7.6 L6056-6541).

One master (#81.06 = 25) broadcasts two int32 references and an 8-bit auxiliary value each sample with
CTSyncSetMasterReferences; every node, the master included, reads the last data received with
CTSyncGetSlaveReferences in POS0. The broadcast of sample k arrives for sample k+1, so all nodes apply the
same one-sample-old data at the same instant (L2080-2094; §7.5 "the master also follows its own data").
Status: 1 ok, 0 nothing or too short, −1 too long, −2 checksum error (L3276-3281); menu 91 counts valid,
invalid and missing messages (91.17-91.19). All nodes must run the same POS rate (L2071).

Faults can be injected per sample to check programs against a bad line (**inferred** diagnostics model:
a faulty message leaves the previous data in place).
"""

from __future__ import annotations

from collections.abc import Iterable

from motiontool.apc import fused
from motiontool.apc.drive import ApcDrive
from motiontool.apc.units import pos_rate_code

MAX_NODES_2WIRE, MAX_NODES_4WIRE = 8, 16     # L2072-2075
FAULT_STATUS = {"short": 0, "long": -1, "checksum": -2}


class CTSyncLine:
    """Drives stepped together, sample by sample, with the master's data delivered one sample late."""

    def __init__(self, drives: Iterable[ApcDrive], *, four_wire: bool = False):
        self.drives = list(drives)
        if not self.drives:
            raise ValueError("a CTSync line needs at least one drive")
        limit = MAX_NODES_4WIRE if four_wire else MAX_NODES_2WIRE
        if len(self.drives) > limit:
            raise ValueError(f"{len(self.drives)} nodes: CTSync allows {limit} on a "
                             f"{'4' if four_wire else '2'}-wire line without repeaters"
                             + ("" if four_wire else f" ({MAX_NODES_4WIRE} on a 4-wire line)"))
        self.four_wire = four_wire
        periods = {d.period_us for d in self.drives}
        if len(periods) > 1:
            raise ValueError(f"every CTSync node must run the same POS rate (#81.12); found {sorted(periods)} µs")
        self.faults: dict[int, str] = {}      # sample number → "short" | "long" | "checksum" | "missing"
        self.samples = 0
        self._in_flight: tuple[int, int, int] | None = None

    def inject(self, sample: int, fault: str) -> None:
        """Spoil the message that arrives for `sample` (1-based count of line samples)."""
        if fault not in (*FAULT_STATUS, "missing"):
            raise ValueError(f"fault {fault!r}: short, long, checksum or missing")
        self.faults[sample] = fault

    def masters(self) -> list[ApcDrive]:
        return [d for d in self.drives if d.params.values.get((81, 6)) == 25]

    def tick(self) -> None:
        """One sample on every node: deliver last sample's broadcast, run all nodes, collect the new one."""
        self.samples += 1
        message, fault = self._in_flight, self.faults.pop(self.samples, None) if self.faults else None
        drives = self.drives
        period = drives[0].period_ns
        steady_tick = fused.steady_tick    # ApcDrive.tick's first step, called here without the method's call
        received = (*message, 1) if message is not None and fault is None else None
        if received is None:   # the previous data stay, with this sample's status
            missing = fault == "missing" or message is None and self.samples > 1 and bool(self.masters())
            for d in drives:
                if message is None or fault == "missing":
                    d.ctsync_received = (*d.ctsync_received[:3], 0)
                    d.ctsync_counts[2] += missing
                else:  # a message was sent, so this branch means a fault
                    assert fault is not None
                    d.ctsync_received = (*d.ctsync_received[:3], FAULT_STATUS[fault])
                    d.ctsync_counts[1] += 1
        sent = None
        for d in drives:
            if d.period_ns != period:      # a REINIT in a node's program (L2077; checked here, sample by sample)
                if received is not None:
                    self._deliver_rest(d, received)
                raise CTSyncRateError(self)
            if received is not None:       # the usual sample: each node gets it just before it runs
                d.ctsync_received = received
                d.ctsync_counts[0] += 1
            d.ctsync_out = None
            if not steady_tick(d):
                d.tick()
            out = d.ctsync_out
            if out is not None:
                sent = out
        self._in_flight = sent

    def _deliver_rest(self, first, received: tuple[int, int, int, int]) -> None:
        """Before a rate error: the nodes from `first` on get the message too, as every node had before."""
        for d in self.drives[self.drives.index(first):]:
            d.ctsync_received = received
            d.ctsync_counts[0] += 1

    @property
    def period_ns(self) -> int:
        """The line's POS period: the first node's #81.12 as of its last REINIT (every node must run it, L2077)."""
        return self.drives[0].period_ns

    def run_ms(self, ms: float) -> None:
        """The line's samples within the next `ms` milliseconds, the period read before each (as ApcDrive.run_ms)."""
        first = self.drives[0]
        end = first.time_ns + round(ms * 1_000_000)
        while first.time_ns + first.period_ns <= end:
            self.tick()


class CTSyncRateError(ValueError):
    """A node whose POS rate (#81.12, taken by REINIT) differs from the line's: the master's when there is one,
    else the first node's (decision A73). `odd`: the 0-based positions of those nodes; `line_us`: the line's rate."""

    def __init__(self, line: CTSyncLine):
        masters = line.masters()
        self.by_master = len(masters) == 1
        ref = masters[0] if self.by_master else line.drives[0]
        self.reference = line.drives.index(ref)
        self.line_us = ref.period_us
        self.odd = [i for i, d in enumerate(line.drives) if d.period_us != self.line_us]
        self.periods = {i: line.drives[i].period_us for i in self.odd}
        super().__init__(self.describe([i + 1 for i in range(len(line.drives))]))

    def describe(self, names: list) -> str:
        """The message with the nodes called `names[position]` (the command line's node ids)."""
        which = "the master" if self.by_master else "the first node"
        odd = ", ".join(f"node {names[i]} runs its POS task every {self.periods[i] / 1000:g} ms (#81.12 = "
                        f"{pos_rate_code(self.periods[i])})" for i in self.odd)
        return (f"CTSync: {odd}, the line every {self.line_us / 1000:g} ms (#81.12 = "
                f"{pos_rate_code(self.line_us)} on node {names[self.reference]}, {which}): all CTSync master "
                f"and slave POS tasks must be set to the same update time")
