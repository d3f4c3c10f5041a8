"""Marker correction in CAM mode: SYNCCMM (master marker) and SYNCCMS (slave marker), and the SYNCMSTART 2000
start of the curve master count (kernel-spec g.2; DG 1493-1746, 3762-3781, 9530-9721, 10004-10032).

Where a marker is expected (DG 3779: "The position of the curve where the marker is detected is calculated from
the master marker position and the marker distance"):
* SYNCCMM: a product edge belongs at the working point at curve master position MMarkerPos (curve data) and the
  sensor is SYNCMPULSM MU before it, so its marker should come at D = (MMarkerPos − SYNCMPULSM) mod L. A marker at
  curve master position x is off by e = x − D (taken into −L/2 … L/2); "the curve (master curve position) is
  corrected" (DG 1612): M is shifted by −e, so the product reaches the working point at MMarkerPos.
* SYNCCMS: "the slave position is being corrected instead of the curve" (DG 1612). The slave marker should come
  when the slave is at curve slave position D = (SMarkerPos − SYNCMPULSS) mod SlaveCycleLen; the slave's actual
  curve position y at the marker gives e = y − D, and the curve is moved along the slave by +e (C += e).

How a correction is realised (DG 3762-3765, 1532-1541: "At the earliest, the correction may begin when the printing
of a box has been completed … The correction must be finished completely when the next cardboard box reaches the
processing point"): only while the curve is inside the correction window Correction Start … Correction End (may
wrap over the cycle end). For SYNCCMM these are curve master positions ("the master positions where the master
correction should begin and end", DG 3764); for SYNCCMS they are curve slave positions — "In this example, the slave
positions at the end and beginning of a box are quite suitable … Correction Start = 2800, Correction End = 750"
(DG 1712-1716): printing ends at slave 2500 and the next box is at the stamp at slave 1000 — compared with the
curve's slave position F(M) modulo SlaveCycleLen (a closed cam, SlaveCycleLen 0, uses master positions). A
correction waits for the window; it runs as the
quintic blend of the engage paths from where it begins (the window start, or where the marker came if that is inside
the window: "there is little time left … to correct", DG 1590-1594) to the window end, so the slave's velocity
and acceleration stay continuous; what is left when the master leaves the window is added at once. Correction
Start = Correction End: no window, the correction is added at once and caught up within VEL/ACC (as SYNCM without
filter times, DG 9990). Each evaluation is clamped to the curve's MaximumCorrection (MU for SYNCCMM, UU for
SYNCCMS) and to 33-30 SYNCMMAXCORR (qc of the corrected side); SYNCMMAXCORR < 0 switches the correction off and
only monitors (DG 10020-10028). A clamped error is left over and measured again at the next marker, so the
corrections converge cycle by cycle.

Monitoring (DG 9610-9662, "[qc] or in CAM mode [MU]"): one marker is expected per curve cycle, i.e. SYNCMWINM /
SYNCMWINS is the permitted deviation of the marker spacing from MasterCycleLen / SlaveCycleLen (measured on the
master counter / slave encoder, so it is the window around where the corrected curve expects the next marker).
Markers outside are ignored; a marker missing from its window sets MMERR / SMERR and nothing is corrected for it;
monitoring begins with the first marker. Every SYNCMARKM-th (SYNCMARKS-th) accepted marker is evaluated. READY /
FAULT count the evaluations as in SYNCM (33-24 / 33-25; accurate = the correction needed is inside SYNCACCURACY
qc of the corrected side); the first evaluation (the start correction) is not counted.

Marker FIFO (DG 1568-1606, 9550): a sensor k = ⌊distance / cycle⌋ cycles away sees the k-th product ahead; its
error is buffered and evaluated at the k-th following marker, "as if the sensor had been mounted at the value
(distance − master cycle length)". Corrections made in between (for the products ahead) count against it.

SYNCMSTART 2000 (DG 9716, CR 675-680; SYNCC, SYNCCMM and SYNCCMS): from SYNCC on the curve master position stands
until the first master marker (33-19 type) and counts from there: "Counting of the master pulse does not begin until
the next edge comes from the sensor" (DG 1558-1560). The other SYNCMSTART values have no effect in CAM mode.
"""

from __future__ import annotations

import math
from collections import deque

from motiontool.kernel.cam import CATCHUP, CURVE, ENGAGE, _blend
from motiontool.kernel.markers import MMERR, MMHIT, SMERR, SMHIT, SYNCSTAT_FAULT, _Side
from motiontool.kernel.sync import trapezoid_part

MASTER, SLAVE = "master", "slave"
HISTORY = 1000  # evaluations kept in CamMarkers.corrections / errors
_ENGAGED = (CURVE, CATCHUP, ENGAGE)  # slave markers are evaluated and realised only while the slave is on the curve


def _wrap(x: float, length: float) -> float:
    """x taken into −length/2 … length/2 (unchanged for a zero length, e.g. a closed cam's slave)."""
    if not length:
        return x
    return x - math.floor(x / length + 0.5) * length


class CamMarkers:
    """The marker handling of one SYNCC / SYNCCMM / SYNCCMS (side None / "master" / "slave")."""

    def __init__(self, ctl, motion, side: str | None, start_mode: int):
        self.ctl = ctl
        self.motion = motion
        self.side = side
        self.waiting = start_mode == 2000            # SYNCMSTART 2000: M stands until the first master marker
        self.frozen = motion.cam.master_position()
        self.pending = 0.0        # corrections (MU / UU) waiting for the correction window
        self.run: list | None = None  # [amount, u0, realised]: the correction running through the window
        self.applied = 0.0        # all corrections realised so far
        # the last HISTORY evaluated corrections after clamping and measured errors (MU / UU), for tests and
        # diagnosis; bounded, as a SYNCC may run for days
        self.corrections: list[float] = []
        self.errors: list[float] = []
        self._reset()
        self.read_parameters()

    def _reset(self) -> None:
        self.master = _Side(MMHIT, MMERR)
        self.slave = _Side(SMHIT, SMERR)
        self.fifo: deque = deque()
        self.evaluated = False
        self.ready_count = self.fault_count = 0
        self.ready = self.side is None or self._p("SYNCREADY") <= 0
        self.fault = False

    def _p(self, name: str) -> int:
        return self.ctl.params[name]

    def read_parameters(self) -> None:
        """Marker distances, numbers and tolerance windows: at SYNCC and at every curve restart (CR 3936-3944, K39)."""
        self.distance = abs(self._p("SYNCMPULSM") if self.side == MASTER else self._p("SYNCMPULSS"))
        self.every = max(1, self._p("SYNCMARKM") if self.side == MASTER else self._p("SYNCMARKS"))
        self.window_m, self.window_s = self._p("SYNCMWINM"), self._p("SYNCMWINS")
        # the shaping of a correction (K52): 33-27 SYNCOFFTIME ms per curve cycle of correction, as a 20/60/20
        # trapezoid; 33-29 SYNCMFTIME: a PT1 filter reaching 95 % in that time (time constant SYNCMFTIME/3)
        self.offtime = max(0, self._p("SYNCOFFTIME"))
        mftime = self._p("SYNCMFTIME")
        self.filter_step = 1.0 - math.exp(-3.0 / mftime) if mftime > 0 else 0.0

    def restart(self) -> None:
        """SYNCMARKERSTART: forget the markers seen (monitoring, FIFO, READY/FAULT) and start again (DG 7242)."""
        self._reset()

    def fault_bit(self) -> int:
        return SYNCSTAT_FAULT if self.fault else 0

    # --- geometry -------------------------------------------------------------------------------------------
    def _cycle(self) -> float:
        """One curve cycle on the corrected side: MasterCycleLen (MU) or SlaveCycleLen (UU)."""
        curve = self.motion.cam.curve
        return curve.length if self.side == MASTER else curve.slave_length

    def _qc_per_unit(self) -> float:
        """Master qc per MU (SYNCFACTM/SYNCFACTS) or slave qc per UU."""
        cam = self.motion.cam
        if self.side == MASTER:
            return abs(cam.factm / cam.facts) if cam.facts else 1.0  # SYNCFACTS 0: the curve master stands
        return abs(self.motion.k)

    def _expected(self) -> float:
        decoded = self.motion.cam.curve.decoded
        position = decoded.master_marker_pos if self.side == MASTER else decoded.slave_marker_pos
        cycle = self._cycle()
        return position - self.distance - (math.floor((position - self.distance) / cycle) * cycle if cycle else 0)

    def _depth(self) -> int:
        cycle = abs(self._cycle())
        return int(self.distance // cycle) if cycle else 0

    # --- markers (called by markers.Markers after the axis stepped) -----------------------------------------
    def tick(self, master_events, slave_events, master_pos: float, slave_pos: float) -> None:
        ctl = self.ctl
        flags = 0
        scale = self._qc_per_unit() if self.side else 1.0
        cycle_qc = abs(self._cycle()) * scale if self.side else 0.0
        for raw, _ in master_events:
            if self.waiting:
                self._start_count(raw - ctl.master.origin)
                if self.side == MASTER:
                    self.master.accept(raw, cycle_qc, 0)
                    self.evaluated = True  # counting starts exactly at this marker: no start correction
                    flags |= MMHIT
            elif self.side == MASTER and self.master.accept(raw, cycle_qc, round(self.window_m * scale)):
                flags |= MMHIT
                if (self.master.count - 1) % self.every == 0:
                    x = self.motion.cam.master_position_at(raw - ctl.master.origin)
                    self._measure(x - self._expected())
        if self.side == SLAVE and not self.waiting:
            window = round(self.window_s * scale) if cycle_qc else 0
            for raw in slave_events:
                if self.slave.accept(raw, cycle_qc, window):
                    flags |= SMHIT
                    if (self.slave.count - 1) % self.every == 0 and self.motion.state in _ENGAGED:
                        mo = self.motion
                        y = (raw - ctl.axis.origin - mo.base) / mo.k
                        self._measure(y - self._expected())
            if self.slave.missing(slave_pos, ctl.axis.plant.velocity, cycle_qc, window):
                flags |= SMERR
                self._missed()
        elif self.side == MASTER and not self.waiting:
            window = round(self.window_m * scale)
            if self.master.missing(master_pos, ctl.master.velocity, cycle_qc, window):
                flags |= MMERR
                self._missed()
        if flags:
            ctl.program_data.syncstat_flags |= flags

    def _start_count(self, mapos: int) -> None:
        """SYNCMSTART 2000: the curve master position counts on from where it stood, beginning at this marker."""
        cam = self.motion.cam
        cam.mu_shift += self.frozen - cam.master_position_at(mapos)
        self.waiting = False

    def _measure(self, error: float) -> None:
        """A marker error (MU / UU): buffered while the sensor is cycles away, then evaluated."""
        self.fifo.append((_wrap(error, self._cycle()), self.applied))
        while len(self.fifo) > self._depth():
            self._evaluate(*self.fifo.popleft())

    def _missed(self) -> None:
        """A missing marker: nothing is corrected for its product (its FIFO place stays empty)."""
        if self._depth():
            self.fifo.append(None)
            while len(self.fifo) > self._depth():
                item = self.fifo.popleft()
                if item is not None:
                    self._evaluate(*item)

    def _outstanding(self) -> float:
        run = self.run
        return self.pending + (run[0] - run[2] if run is not None else 0.0)

    def _evaluate(self, error: float, applied_then: float) -> None:
        """Plan what the product still needs: −e (master) or +e (slave) since its marker, less what has been
        realised since or is still planned; count READY/FAULT (DG 9723-9761), clamp (DG 10004-10032)."""
        needed = -error if self.side == MASTER else error
        x = applied_then + needed - self.applied - self._outstanding()
        _keep(self.errors, error)
        scale = self._qc_per_unit()
        if self.evaluated:  # the start correction is expected to be large; only later evaluations count
            if abs(x) * scale <= abs(self.motion.accuracy):
                self.ready_count += 1
                self.ready = self.ready or self.ready_count >= self._p("SYNCREADY")
            else:
                self.ready_count = 0
                self.ready = self._p("SYNCREADY") <= 0
                self.fault_count += 1
                self.fault = self.fault or self.fault_count > self._p("SYNCFAULT")
        self.evaluated = True
        maxcorr = self._p("SYNCMMAXCORR")
        if maxcorr < 0:
            _keep(self.corrections, 0.0)
            return  # marker correction switched off: monitoring only
        # SYNCMMAXCORR is "given in qc (slave)" (DG 10020): a slave correction in UU is k qc per UU; a curve master
        # correction of x MU moves the slave x·SYNCFACTM/SYNCFACTS master qc × SYNCFACTS/SYNCFACTM = x slave qc
        # through the gear (decision K34)
        slave_qc = maxcorr if self.side == MASTER else maxcorr / scale
        limits = [lim for lim in (self.motion.cam.curve.decoded.max_correction, slave_qc) if lim > 0]
        if limits:
            x = max(-min(limits), min(min(limits), x))
        _keep(self.corrections, x)
        self.pending += x

    # --- realising (called by CamMotion.step before the target is computed) --------------------------------
    def realise(self) -> None:
        mo = self.motion
        cam = mo.cam
        if self.waiting:  # the curve master position stands until the first master marker
            cam.mu_shift += self.frozen - cam.master_position()
            return
        if self.run is None and not self.pending:
            return
        if self.side == SLAVE and mo.state not in _ENGAGED:
            return
        curve = cam.curve
        start, end = curve.decoded.correction_start, curve.decoded.correction_end
        length = abs(curve.slave_length) if self.side == SLAVE else 0.0
        if length:  # SYNCCMS: the window is a range of curve slave positions (DG 1714-1716)
            position = curve.periodic(cam.master_position())
        else:
            length, position = curve.length, cam.master_position()
        width = (end - start) % length
        if self.filter_step or self.offtime:
            self._shaped(not width or (position - start) % length <= width)
            return
        if not width:  # no window: at once
            delta, self.pending, self.run = self._outstanding(), 0.0, None
        else:
            into = (position - start) % length
            if into <= width:
                u = into / width
                if self.run is None:
                    self.run, self.pending = [self.pending, u, 0.0], 0.0
                elif self.pending:  # a new evaluation inside the window: the rest runs from here
                    amount, _, done = self.run
                    self.run, self.pending = [amount - done + self.pending, u, 0.0], 0.0
                amount, u0, done = self.run
                w = 1.0 if u0 >= 1.0 else _blend((u - u0) / (1.0 - u0))
                delta = amount * w - done
                self.run[2] = amount * w
            elif self.run is not None:  # left the window: the rest at once
                delta = self.run[0] - self.run[2]
                self.run = None
            else:
                return
        self._apply(delta)

    def _shaped(self, inside: bool) -> None:
        """A correction shaped by SYNCMFTIME or SYNCOFFTIME (K52), realised only inside the correction window (or
        always without one). SYNCMFTIME: each ms 1 − e^(−3/SYNCMFTIME) of what is outstanding ("A marker error is
        corrected within a period of 2000 ms", DG 9907-9911); a rest waits for the next window. SYNCOFFTIME: "the
        time which should be used to compensate one marker distance" (DG 9833-9836) — here one curve cycle — as a
        20/60/20 trapezoid (DG 9838-9843); what is left when the window closes is added at once (as K31)."""
        if self.filter_step:
            if inside:
                total = self._outstanding()
                delta = total * self.filter_step
                self.run, self.pending = None, total - delta
                self._apply(delta)
            return
        run = self.run
        if inside:
            if run is None or self.pending:  # a new correction: a trapezoid for all that is outstanding
                amount = self._outstanding()
                cycle = abs(self._cycle()) or self.motion.cam.curve.length
                run = self.run = [amount, 0.0, 0.0, 0, max(1.0, self.offtime * abs(amount) / cycle)]
                self.pending = 0.0
            run[3] += 1
            x = run[3] / run[4]
            realised = run[0] * trapezoid_part(x)
            delta, run[2] = realised - run[2], realised
            if x >= 1.0:
                self.run = None
        elif run is not None:  # left the window: the rest at once
            delta, self.run = run[0] - run[2], None
        else:
            return
        self._apply(delta)

    def _apply(self, delta: float) -> None:
        if not delta:
            return
        self.applied += delta
        mo = self.motion
        if self.side == MASTER:
            mo.cam.mu_shift += delta
        else:
            mo.base += delta * mo.k
            mo.cam.slave_base_qc = mo.base


def _keep(history: list[float], value: float) -> None:
    history.append(value)
    if len(history) > HISTORY:
        del history[0]
