"""Interrupts: detection every tick, priorities, DISABLE/ENABLE, pending flags (spec §6, DG 6272-6391).

Priority (DG 6353-6379): ERROR > INT > position > COMBIT > STATBIT > PARAM > CANMSG > KEYPRESSED >
TIME/PERIOD. A handler is never interrupted by another one except ON ERROR. A source that fires again
while its own handler runs is remembered once (decisions.md, spec §10.3).
"""

from __future__ import annotations

from dataclasses import dataclass

from motiontool.kernel.cam import curve_cycle_length, master_curve_position
from motiontool.kernel.errors import ControllerError

POSITION_KINDS = ("APOS", "IPOS", "MAPOS", "MCPOS", "MIPOS")
PRIORITY = {"ERROR": 0, "INT": 1, "APOS": 2, "IPOS": 2, "MAPOS": 2, "MCPOS": 2, "MIPOS": 2, "COMBIT": 3,
            "STATBIT": 4, "PARAM": 5, "CANMSG": 6, "CANINPUT": 6, "KEYPRESSED": 7, "TIME": 8, "PERIOD": 8}
EDGE_KINDS = ("INT", "COMBIT", "STATBIT")  # CR 1084-1133: discarded while selectively disabled
LIMITS = {"INT": (32, 149), "COMBIT": (32, 149), "STATBIT": (32, 149), "PARAM": (10, 149), "POSITION": (20, 149),
          "TIMER": (12, 184)}


@dataclass
class Source:
    kind: str
    number: int            # input number / bit / parameter / period; for position kinds the position
    sub: int               # subprogram index, -1 for SETOUT
    sign: int = 1
    setout: int | None = None
    toin: int | None = None
    next_time: int = 0     # TIME / PERIOD
    pending: bool = False
    order: int = 0
    last: float | None = None  # last seen value (edges and crossings)
    spent: bool = False


class Interrupts:
    def __init__(self) -> None:
        self.sources: list[Source] = []
        self.error_sub: int | None = None
        self.disabled: set[str] = set()
        self.all_disabled = False
        self._order = 0

    def reset(self) -> None:
        type(self).__init__(self)

    # --- definition (ON ... statements) ------------------------------------------------------------------
    def define(self, kind: str, sign: int, sub: int, operands: list[int], now: int, has_value: bool,
               setout: bool, toin: bool, delete: bool) -> None:
        ops = list(operands)
        value = ops.pop(0) if has_value else 0
        out = ops.pop(0) if setout else None
        inp = ops.pop(0) if toin else None
        if kind == "ERROR":
            self.error_sub = sub
            return
        if delete:  # ON DELETE pos GOSUB name / ON DELETE pos SETOUT n (C:2536-2628)
            self.sources = [s for s in self.sources if not (s.kind in POSITION_KINDS and
                                                            ((sub >= 0 and s.sub == sub) or
                                                             (out is not None and s.setout == out)))]
            return
        if kind in ("TIME", "PERIOD"):
            self.sources = [s for s in self.sources if not (s.kind == kind and s.sub == sub)]
            if kind == "PERIOD" and value == 0:  # ON PERIOD 0 switches it off
                return
            self.drop_spent()
            self._check_limit("TIMER", sum(s.kind in ("TIME", "PERIOD") for s in self.sources))
            self._add(Source(kind, value, sub, next_time=now + value))
            return
        if kind in POSITION_KINDS:
            # CR 2567-2600: the same sign and position re-routes the existing interrupt
            self.sources = [s for s in self.sources if not (s.kind == kind and s.sign == sign and s.number == value
                                                            and (s.setout is None) == (out is None))]
            self._check_limit("POSITION", sum(s.kind in POSITION_KINDS for s in self.sources))
            self._add(Source(kind, value, sub, sign, out, inp))
            return
        if kind == "INT" and value == 0:
            raise ControllerError(183, "ON INT 0")
        self.sources = [s for s in self.sources if not (s.kind == kind and s.number == value)]
        if kind in LIMITS:
            self._check_limit(kind, sum(s.kind == kind for s in self.sources))
        self._add(Source(kind, value, sub))

    def _add(self, source: Source) -> None:
        self._order += 1
        source.order = self._order
        self.sources.append(source)

    @staticmethod
    def _check_limit(group: str, count: int) -> None:
        limit, error = LIMITS[group]
        if count >= limit:
            raise ControllerError(error, f"more than {limit} {group} interrupts")

    # --- detection ------------------------------------------------------------------------------------
    @staticmethod
    def _value(s: Source, read_input, positions: dict[str, float], statbits: int, combits: int):
        """What an edge or crossing source watches, now; None for the others (and an absent position)."""
        kind = s.kind
        if kind == "INT":
            return read_input(abs(s.number))
        if kind in POSITION_KINDS:
            return positions.get(kind)
        if kind in ("STATBIT", "COMBIT"):  # bit n 1-based, -n: the bit is cleared (like ON INT -n)
            return ((statbits if kind == "STATBIT" else combits) >> (abs(s.number) - 1)) & 1
        return None

    def prime(self, read_input, positions: dict[str, float], statbits: int, combits: int = 0) -> None:
        """Sources defined just now take the state at their definition as their start: a bit, input or position
        that changes in the very next tick fires them (sampling only at the next detection missed that change)."""
        for s in self.sources:
            if s.last is None:
                s.last = self._value(s, read_input, positions, statbits, combits)

    def detect(self, now: int, read_input, positions: dict[str, float], statbits: int, combits: int = 0) -> list:
        """Set pending flags for sources that fired this tick; returns SETOUT actions [(out, value)].
        `statbits`: the 32 status bits of ON STATBIT; `combits`: the first 32 bits of the process data (ON COMBIT)."""
        actions = []
        for s in self.sources:
            kind = s.kind
            fired = False
            if kind in ("TIME", "PERIOD"):
                if now >= s.next_time:
                    fired = True
                    if kind == "PERIOD":
                        s.next_time += max(s.number, 1)  # fixed rate: next = previous start + n (DG 6325)
                    else:
                        s.next_time = 1 << 62
                        s.spent = True  # a fired ON TIME no longer counts toward the 12 timers
            elif kind in POSITION_KINDS:
                value = positions.get(kind)
                if value is not None and s.last is not None:
                    p = s.number
                    cycle = positions.get("MCPOS_CYCLE") if kind == "MCPOS" else None
                    if cycle and abs(value - s.last) > cycle / 2:  # the curve restarted (… L → 0 …): unwrap
                        v = value + cycle if value < s.last else value - cycle
                        fired = any((s.last < q <= v) if s.sign > 0 else (s.last > q >= v)
                                    for q in (p - cycle, p, p + cycle))
                    else:
                        fired = (s.last < p <= value) if s.sign > 0 else (s.last > p >= value)
                s.last = value
                if fired and s.sub < 0:  # SETOUT in the background, < 1 ms (CR 2985-3016)
                    out = s.setout
                    assert out is not None  # sub -1 only with SETOUT (aposs/codegen.py; verify.py refuses others)
                    level = 1 if out > 0 else 0
                    if s.toin is not None:
                        level = read_input(abs(s.toin))
                        if (out < 0) != (s.toin < 0):
                            level = 1 - level
                    actions.append((abs(out), level))
                    fired = False
            elif kind in EDGE_KINDS:
                value = self._value(s, read_input, positions, statbits, combits)
                if s.last is not None:
                    fired = bool(value and not s.last) if s.number > 0 else bool(s.last and not value)
                s.last = value
            if not fired:
                continue
            if kind in EDGE_KINDS and kind in self.disabled and not self.all_disabled:
                continue  # edge interrupts are lost while selectively disabled
            s.pending = True
        return actions

    def fire_param(self, number: int) -> None:
        for s in self.sources:
            if s.kind == "PARAM" and s.number == number:
                s.pending = True

    def fire(self, kind: str) -> None:
        """An event source fired outside `detect` (CANINPUT: a global CAN telegram, CANMSG: a buffered message)."""
        for s in self.sources:
            if s.kind == kind:
                s.pending = True

    def drop_spent(self) -> None:
        self.sources = [s for s in self.sources if not (s.spent and not s.pending)]

    def next_ready(self) -> Source | None:
        """The pending source to serve now, by priority; None if all pending ones are disabled."""
        if self.all_disabled:
            return None
        ready = [s for s in self.sources if s.pending and s.kind not in self.disabled
                 and not (s.kind in POSITION_KINDS and "POSITION" in self.disabled)]
        if not ready:
            return None
        ready.sort(key=lambda s: (PRIORITY[s.kind], abs(s.number) if s.kind in EDGE_KINDS else s.order))
        return ready[0]

    def disable(self, kind: str) -> None:
        if kind == "ALL":
            self.all_disabled = True
        else:
            self.disabled.add(kind)

    def enable(self, kind: str) -> None:
        if kind == "ALL":
            self.all_disabled = False
        else:
            self.disabled.discard(kind)


def interrupt_readings(ctl) -> tuple:
    """What the sources of `ctl` watch, now: (read_input, positions, statbits, combits) for detect/prime."""
    kinds = {s.kind for s in ctl.interrupts.sources}
    positions = {"APOS": ctl.uu(ctl.axis.apos)} if "APOS" in kinds else {}
    if "MAPOS" in kinds:  # master qc, like the MAPOS readout (decision K46)
        positions["MAPOS"] = ctl.master.mapos
    if "IPOS" in kinds or "MIPOS" in kinds:  # distance since the last marker (DG 7158)
        positions["IPOS"] = ctl.uu(ctl.axis.apos) - ctl.uu(ctl.markers.ipos_qc())
        positions["MIPOS"] = ctl.master.mapos - ctl.markers.mipos()
    if "MCPOS" in kinds:  # CAM box: curve master position in MU (DG 1748-1772)
        mcpos = master_curve_position(ctl)
        if mcpos is not None:
            positions["MCPOS"] = mcpos
            positions["MCPOS_CYCLE"] = curve_cycle_length(ctl)
    statbits = ctl.statbits() if "STATBIT" in kinds else 0
    # ON COMBIT: "the first 32 Bits of the process data memory" (CR 2515) = PDO[1001], bytes 1-4 of PDO 1,
    # which a received RxPDO 1 fills ("as soon as the bit n of the PDO changes", CR 3334; K53)
    combits = ctl.can.pdo.read_element(1001) & 0xFFFFFFFF if "COMBIT" in kinds else 0
    inputs = ctl.io.inputs
    return (lambda n: inputs.get(n, 0)), positions, statbits, combits
