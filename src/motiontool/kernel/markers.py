"""Master and slave markers, IPOS/MIPOS, and SYNCM marker synchronisation (kernel-spec d.3, f.3).

Marker sources (33-19 SYNCMTYPM / 33-20 SYNCMTYPS, DG 9567-9608): 0/1 the encoder's index (Z) pulse,
rising/falling flank; 2/3 the external marker input, rising/falling flank — input 5 for the master,
input 6 for the slave (CR 1782-1783, 2272-2273); the extended type 10·n + t (t = 0…3) takes a marker of type t only
while input n is on ("a logical AND for marker input and a second input", DG 9581; our coding, decision K51). The
simulated machine can carry a marker sensor on either side (`MarkerSensor`: products passing a light barrier at
master/slave positions, optionally irregular or with jitter); it drives input 5/6 like a wired sensor. An edge is
latched at the position where it happened inside the tick (the crossing is interpolated), so MIPOS/IPOS are exact to
±1 qc (CR 1767-1815, 2263-2310). Edges of a scripted input (schedule_input) are latched at the tick's position.

SYNCM (DG 1143-1340, 9494-10032) is a SYNCP whose slave is shifted so that every SYNCMARKS-th slave
marker passes when every SYNCMARKM-th master marker does. At a master marker the slave position A is
noted; with the slave marker at S the error is e = S + offset − A (slave qc, offset = SYNCPOSOFFS +
MOVESYNCORIGIN through the gear); A counts corrections still being realised, so a slow correction is not
repeated. Which markers form the first pair is SYNCMSTART (33-23); afterwards a master marker pairs with
the slave marker closest to it (within half a slave marker distance). Corrections are clamped by
SYNCMMAXCORR and realised through SyncMotion.correct (SYNCOFFTIME trapezoid or at once within VEL/ACC).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

SYNCSTAT_READY, SYNCSTAT_FAULT = 1, 2
MMHIT, SMHIT, MMERR, SMERR = 8, 16, 32, 64   # SYNCSTAT bits 4-7 (CR 3060-3061, kernel-spec j.5)
MASTER_MARKER_INPUT, SLAVE_MARKER_INPUT = 5, 6
Z_WIDTH_QC = 1          # the index pulse is 1 qc wide, so both flanks latch within ±1 qc of it (our choice)
MAX_SEARCH_QC = 1 << 22  # a jump of the counter (SYSVAR 4105 write) is not searched for markers


def _boundary_in(lo: float, hi: float, base: float, period: float) -> bool:
    """Whether some base + k·period lies in (lo, hi]. The division only picks the candidates — it rounds
    (an edge a denormal above lo gives -0.0) — the comparison with the boundary itself decides."""
    k = math.floor((lo - base) / period)
    for j in (k - 1, k, k + 1, k + 2):
        b = base + j * period
        if b > lo:
            return b <= hi
    return False


@dataclass(frozen=True)
class MarkerSensor:
    """A sensor that is on while the position is inside [c_k, c_k + width): c_k = offset + k · period
    (+ a deterministic jitter in ±jitter drawn from `seed` and k), or c_k from `positions` (irregular
    products). Positions are raw counter qc of the side the sensor watches."""

    period: float = 0.0
    offset: float = 0.0
    width: float = 100.0
    positions: tuple = ()
    jitter: float = 0.0
    seed: int = 0

    @property
    def active(self) -> bool:
        return self.period > 0 or bool(self.positions)

    def _start(self, k: int) -> float:
        c = self.offset + k * self.period
        if self.jitter:
            c += random.Random(self.seed * 1_000_003 + k).uniform(-self.jitter, self.jitter)
        return c

    def _starts(self, lo: float, hi: float) -> list[float]:
        if self.positions:
            return [c for c in self.positions if c - self.width <= hi and c >= lo - self.width]
        reach = self.width + self.jitter
        # one period of margin each side: the divisions round, the exact comparison in edges() decides
        first = math.floor((lo - self.offset - reach) / self.period) - 1
        last = math.ceil((hi - self.offset + self.jitter) / self.period) + 1
        return [self._start(k) for k in range(first, last + 1)]

    def edges(self, p0: float, p1: float) -> list[tuple[float, bool]]:
        """Edges passed moving from p0 to p1, in the order they happen: (position, rising in time)."""
        if p0 == p1 or not self.active or abs(p1 - p0) > MAX_SEARCH_QC:
            return []
        lo, hi = (p0, p1) if p1 > p0 else (p1, p0)
        if not self.positions and not self.jitter:  # fast path: no boundary offset + k·period (+ width) passed
            period, start, end = self.period, self.offset, self.offset + self.width
            if not _boundary_in(lo, hi, start, period) and not _boundary_in(lo, hi, end, period):
                return []
        up = p1 > p0
        found = []
        for c in self._starts(lo, hi):
            for b, entering in ((c, up), (c + self.width, not up)):
                if lo < b <= hi:
                    found.append((b, entering))
        found.sort(key=lambda e: e[0], reverse=not up)
        return found

    def level(self, p: float) -> bool:
        if not self.active:
            return False
        if not self.positions and not self.jitter:
            return (p - self.offset) % self.period < self.width
        return any(c <= p < c + self.width for c in self._starts(p, p))


class MarkerChannel:
    """One side's marker input: finds this tick's markers of the selected type and latches the last one."""

    def __init__(self, input_number: int, sensor: MarkerSensor | None):
        self.input = input_number
        self.sensor = sensor if sensor is not None and sensor.active else None
        self.latched_raw: int | None = None   # raw counter qc of the last marker (MIPOS / IPOS)
        self._last_level = 0
        self._cells: tuple | None = None

    def tick(self, p0: float, p1: float, marker_type: int, z_period: int, io) -> list[tuple[int, float]]:
        """Markers in this tick as (latched raw qc, fraction of the tick when it happened). Runs every tick
        on every controller, so the common cases (no marker passed) return early. An extended type 10·n + t
        counts a marker of type t only while input n is on (logical AND, DG 9581; decision K51)."""
        gate = 0
        if marker_type >= 10:
            gate, marker_type = divmod(marker_type, 10)
        sensor = self.sensor
        if sensor is not None:  # the sensor is wired to the input; a pulse shorter than 1 ms is seen
            sensor_edges = sensor.edges(p0, p1)
            io.inputs[self.input] = int(any(r for _, r in sensor_edges) or sensor.level(p1))
        if marker_type == 0 or marker_type == 1:
            if p0 == p1:
                return _NONE
            cells = (p1 // z_period, (p1 - Z_WIDTH_QC) // z_period, z_period)  # which index pulse p1 is after
            last, self._cells = self._cells, cells
            if cells == last:
                return _NONE
            found = _index_markers(p0, p1, z_period, marker_type == 0)
        elif marker_type == 2 or marker_type == 3:
            want_rising = marker_type == 2
            level = io.inputs.get(self.input, 0)
            last_level, self._last_level = self._last_level, level
            if sensor is not None:
                found = [(b, _fraction(p0, p1, b)) for b, rising in sensor_edges if rising == want_rising]
            elif level != last_level and bool(level) == want_rising:
                found = [(p1, 1.0)]
            else:
                return _NONE
        else:
            return _NONE
        if not found or (gate and not io.inputs.get(gate, 0)):
            return _NONE
        events = [(math.floor(b), f) for b, f in found]
        self.latched_raw = events[-1][0]
        return events


_NONE: list = []  # shared empty result, never modified


def _index_markers(p0: float, p1: float, period: int, rising: bool) -> list[tuple[float, float]]:
    """The index pulses' rising (or falling) flanks passed from p0 to p1 (p0 != p1) as (position, fraction of the
    tick), in the order they happen: MarkerSensor(period=period, width=Z_WIDTH_QC).edges(p0, p1) of that flank,
    the same floats, without the sensor's list of both flanks and its sort (issue 30: a CAM axis crosses a pulse
    edge every ~25 ms). Moving up a pulse rises at k·period, moving down at k·period + Z_WIDTH_QC."""
    if abs(p1 - p0) > MAX_SEARCH_QC:
        return _NONE
    up = p1 > p0
    lo, hi = (p0, p1) if up else (p1, p0)
    width = 0 if rising == up else Z_WIDTH_QC
    ks = range(math.floor((lo - Z_WIDTH_QC) / period) - 1, math.ceil(hi / period) + 2)  # MarkerSensor._starts
    found = []
    for k in ks if up else reversed(ks):
        b = 0.0 + k * period + width
        if lo < b <= hi:
            found.append((b, (b - p0) / (p1 - p0)))
    return found


def _between(cells: tuple | None, period: int) -> tuple[float, float]:
    """The open range of positions whose MarkerChannel cells are `cells` (for this index period), shrunk by ½ qc;
    empty without cells or for another period."""
    if cells is None or cells[2] != period:
        return math.inf, -math.inf
    a, b, zp = cells
    return max(a * zp, b * zp + Z_WIDTH_QC) + 0.5, min((a + 1) * zp, (b + 1) * zp + Z_WIDTH_QC) - 0.5


def _fraction(p0: float, p1: float, b: float) -> float:
    return (b - p0) / (p1 - p0) if p1 != p0 else 1.0


class Markers:
    """The controller's marker inputs: latches MIPOS/IPOS every tick and feeds a running SYNCM or the marker
    handling of a running SYNCC/SYNCCMM/SYNCCMS (kernel/cam_markers.py)."""

    def __init__(self, ctl) -> None:
        self.ctl = ctl
        mc, pc = ctl.master.config, ctl.axis.plant.config
        self.master = MarkerChannel(MASTER_MARKER_INPUT, MarkerSensor(
            mc.marker_period_qc, mc.marker_offset_qc, mc.marker_width_qc, tuple(mc.marker_positions_qc),
            mc.marker_jitter_qc, mc.seed))
        self.slave = MarkerChannel(SLAVE_MARKER_INPUT, MarkerSensor(
            pc.slave_marker_period_qc, pc.slave_marker_offset_qc, pc.slave_marker_width_qc,
            tuple(pc.slave_marker_positions_qc)))
        self._m = ctl.master.position
        self._s = ctl.axis.plant.position
        self._scaling = None
        self._slave_period = 1
        self.master_events: list[tuple[int, float]] = []  # this tick: (raw master qc, slave raw qc then)
        self.slave_events: list[int] = []                 # this tick: raw slave qc
        ctl.params.readouts.update({3453: lambda: ctl.uu(self.ipos_qc()), 3454: self.mipos})

    def tick(self) -> None:
        ctl = self.ctl
        axis = ctl.axis
        values = ctl.params.values
        sync = axis.sync
        # fast path (issue 5, benchmarks/kernel_rtf.py): no marker can come this tick, see _quiet
        if sync is None or sync.markers is None:
            key = (axis.scaling, values[3231], values[3319], values[3320])
            if key == self._q_key or self._quiet(key):
                m1 = ctl.master.position
                s1 = axis.plant.position
                m_lo, m_hi, s_lo, s_hi = self._q
                if (m_lo < m1 < m_hi or m1 == self._m) and (s_lo < s1 < s_hi or s1 == self._s):
                    self._m, self._s = m1, s1
                    self.master_events = self.slave_events = _NONE
                    return
        m0, m1 = self._m, ctl.master.position
        s0, s1 = self._s, axis.plant.position
        if m0 == m1 and s0 == s1 and values[3319] < 2 and values[3320] < 2 and axis.mode != "sync":
            self.master_events = self.slave_events = _NONE
            return  # standing still: no index pulse can pass (sensors need external types 2/3 to matter)
        self._m, self._s = m1, s1
        if axis.scaling is not self._scaling:  # parameters were applied: the index period may have changed
            self._scaling = axis.scaling
            self._slave_period = max(1, axis.index_period())
        self._q_key = ()  # the channels' cells may change: the fast path's bounds are computed again
        master = self.master.tick(m0, m1, values[3319], 4 * max(1, values[3231]), ctl.io)  # 32-31 lines → qc
        slave = self.slave.tick(s0, s1, values[3320], self._slave_period, ctl.io)
        marker_sync = axis.sync.markers if axis.mode == "sync" or axis.mode == "cam" else None  # SYNCM / SYNCCM*
        if not master and not slave:
            self.master_events = self.slave_events = _NONE
            if marker_sync is None:
                return
        else:
            self.master_events = [(raw, s0 + f * (s1 - s0)) for raw, f in master]
            self.slave_events = [raw for raw, _ in slave]
        if marker_sync is not None:
            marker_sync.tick(self.master_events, self.slave_events, m1, s1)

    # the fast path of tick(): the key it was computed for and the position bounds (see _quiet)
    _q_key: tuple = ()
    _q: tuple = (0.0, 0.0, 0.0, 0.0)

    def _quiet(self, key: tuple) -> bool:
        """The fast path of tick() applies without a sensor on either side, with marker types 0/1 (index pulse) and
        no marker synchronisation: then tick() would find no marker and change nothing but the remembered positions
        while each side stands or stays between the same index-pulse edges as at its last evaluation (the
        channel's cells). For a new key (scaling, 32-31, 33-19, 33-20) or after the channels ran (their cells may
        have changed; tick() then forgets the key) this computes those position bounds (½ qc of margin against
        rounding); False when the fast path does not apply."""
        scaling, lines, master_type, slave_type = key
        if (master_type >= 2 or slave_type >= 2 or scaling is not self._scaling
                or self.master.sensor is not None or self.slave.sensor is not None):
            return False
        self._q = (*_between(self.master._cells, 4 * max(1, lines)),
                   *_between(self.slave._cells, self._slave_period))
        self._q_key = key
        return True

    # --- readouts -------------------------------------------------------------------------------------------
    def mipos(self) -> int:
        """MIPOS / 34-54: the last master marker relative to the master zero (qc)."""
        raw = self.master.latched_raw
        return 0 if raw is None else raw - self.ctl.master.origin

    def ipos_qc(self) -> int:
        """IPOS / 34-53 in axis qc (the program sees UU relative to the temporary zero)."""
        raw = self.slave.latched_raw
        return 0 if raw is None else raw - self.ctl.axis.origin


class _Side:
    """Window monitoring and counting of one side's markers (DG 9610-9662)."""

    def __init__(self, hit: int, err: int):
        self.hit, self.err = hit, err
        self.ref: float | None = None   # last accepted marker, or where the missing one was expected
        self.count = 0

    def accept(self, pos: float, distance: float, window: int) -> bool:
        if self.ref is not None and window > 0 and abs(abs(pos - self.ref) - distance) > window:
            return False  # outside the tolerance window (also a second marker inside the same window)
        self.ref = pos
        self.count += 1
        return True

    def missing(self, pos: float, direction: float, distance: float, window: int) -> bool:
        """True once per expected marker that did not come inside its window."""
        if self.ref is None or window <= 0 or abs(pos - self.ref) <= distance + window:
            return False
        self.ref += math.copysign(distance, direction or 1.0)
        return True


class MarkerSync:
    """The marker correction of one SYNCM (33-15 … 33-30 read from `params`, windows live)."""

    def __init__(self, ctl, motion, start_mode: int):
        self.ctl = ctl
        self.motion = motion
        self.start_param = start_mode
        self.start_mode = start_mode % 1000 if start_mode < 2000 else 0  # 2000 acts in CAM only (DG 9716)
        self.offset_active = start_mode < 1000 or start_mode >= 2000     # 1000-1007: after the 1st correction
        self.master = _Side(MMHIT, MMERR)
        self.slave = _Side(SMHIT, SMERR)
        self.started = False
        self.pending_master: float | None = None   # e-base of an evaluation master marker still unpaired
        self.pending_slave: float | None = None    # slave marker position still unpaired
        self.last_master: float | None = None      # e-base of the latest evaluation master marker
        self.before_master: float | None = None    # start 5/7: the master marker before the waiting slave one
        self.drop_master = self.drop_slave = False
        self.ready_count = self.fault_count = 0
        self.ready = self.fault = False
        self.corrections: list[int] = []           # errors evaluated (slave qc), for tests and the scope
        values = ctl.params.values
        if values[3325] <= 0:
            self.ready = True

    def _p(self, index: int) -> int:
        return self.ctl.params.values[index]

    def restart(self) -> None:
        """SYNCMARKERSTART: forget the markers seen and start the marker handling again (DG 7242)."""
        type(self).__init__(self, self.ctl, self.motion, self.start_param)

    def shift(self, delta: int) -> None:
        """The slave origin moved: stored slave positions are raw counts and need nothing."""

    def status_bits(self) -> int:
        return (SYNCSTAT_READY if self.ready else 0) | (SYNCSTAT_FAULT if self.fault else 0)

    # --- per tick -------------------------------------------------------------------------------------------
    def tick(self, master_events, slave_events, master_pos: float, slave_pos: float) -> None:
        flags = 0
        for raw, slave_then in master_events:
            if self.master.accept(raw, self._p(3317), self._p(3321)):
                flags |= MMHIT
                if (self.master.count - 1) % max(1, self._p(3315)) == 0:
                    self._on_master(slave_then)
        for raw in slave_events:
            if self.slave.accept(raw, self._p(3318), self._p(3322)):
                flags |= SMHIT
                if (self.slave.count - 1) % max(1, self._p(3316)) == 0:
                    self._on_slave(raw)
        m = self.ctl.master
        if self.master.missing(master_pos, m.velocity, self._p(3317), self._p(3321)):
            flags |= MMERR
            self.drop_slave, self.pending_master = True, None  # no correction, the partner is ignored too
        if self.slave.missing(slave_pos, self.ctl.axis.plant.velocity, self._p(3318), self._p(3322)):
            flags |= SMERR
            self.drop_master, self.pending_slave = True, None
        if flags:
            self.ctl.program_data.syncstat_flags |= flags

    def _e_base(self, slave_then: float) -> float:
        """offset − A: A = slave position at the master marker plus what the command still has to move."""
        mo = self.motion
        ahead = mo.target + mo.pending_qc() - self.ctl.axis.profile.position
        return mo._offset * mo.gear.ratio - (slave_then + ahead)

    def _half(self) -> float:
        return abs(self._p(3318)) * max(1, self._p(3316)) / 2.0

    def _on_master(self, slave_then: float) -> None:
        base = self._e_base(slave_then)
        if self.drop_master:
            self.drop_master = False
            return
        self.last_master = base
        if self.started:
            if self.pending_slave is not None and abs(self.pending_slave + base) <= self._half():
                self._evaluate(self.pending_slave + base)
            else:
                self.pending_master = base
            return
        mode, s = self.start_mode, self.pending_slave
        if s is not None and mode in (1, 2, 4, 6):   # the slave marker waits for this master marker
            self._evaluate(s + base)
        elif s is not None and mode in (5, 7):       # the closer of the master markers around it
            before = self.before_master
            self._evaluate(s + (base if before is None or abs(s + base) <= abs(s + before) else before))
        elif self.pending_master is None and (mode in (0, 6) or (mode == 2 and self.motion.locked)):
            self.pending_master = base               # the first master marker (after lock for 2)

    def _on_slave(self, s: float) -> None:
        if self.drop_slave:
            self.drop_slave = False
            return
        if self.started:
            if self.pending_master is not None and abs(s + self.pending_master) <= self._half():
                self._evaluate(s + self.pending_master)
            else:
                self.pending_slave = s
            return
        mode, locked = self.start_mode, self.motion.locked
        if self.pending_master is not None and mode in (0, 2, 6):
            self._evaluate(s + self.pending_master)
        elif mode == 3 and locked and self.last_master is not None:
            self._evaluate(s + self.last_master)     # the master marker in front: forward correction
        elif mode in (5, 7) and locked and self.pending_slave is None:
            before = self.last_master
            if before is not None and abs(s + before) <= self._half():
                self._evaluate(s + before)
            else:
                self.before_master, self.pending_slave = before, s
        elif self.pending_slave is None and (mode in (1, 6) or (locked and mode in (2, 4))):
            self.pending_slave = s                   # the first slave marker waits for its master marker

    def _evaluate(self, error: float) -> None:
        """One marker evaluation: count READY/FAULT (DG 9723-9761), clamp (DG 10004-10032), correct."""
        e = round(error)
        first = not self.started
        self.started = True
        self.pending_master = self.pending_slave = None
        self.before_master = None
        self.corrections.append(e)
        if not first:  # the start correction is expected to be large; only later evaluations count
            if abs(e) <= abs(self.motion.accuracy):
                self.ready_count += 1
                self.ready = self.ready or self.ready_count >= self._p(3325)
            else:
                self.ready_count = 0
                self.ready = self._p(3325) <= 0
                self.fault_count += 1
                self.fault = self.fault or self.fault_count > self._p(3324)
        maxcorr = self._p(3330)
        if maxcorr < 0:
            return  # MCO ≥ 5.00: marker correction switched off, only monitoring
        if maxcorr > 0:
            e = max(-maxcorr, min(maxcorr, e))
        if first and not self.offset_active:
            self.offset_active = True  # 1000-1007: SYNCPOSOFFS joins with the first correction
        self.motion.correct(e)
