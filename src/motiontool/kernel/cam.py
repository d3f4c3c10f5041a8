"""CAM control: the active curve (SETCURVE), the curve master position and the CAM synchronisation (SYNCC…).

The curve array is decoded with `motiontool.camcurve.layout.decode` — the same Qt-free module the CAM editor
encodes with (docs/formats/cam-array.md); a malformed array is controller error 191 (DG 11816-11830).

How the slave position follows from the curve (kernel-spec g.1):
* arrays with interpolation points (firmware < 5.00): "The CAM-Editor performs a linear interpolation between
  the interpolation points" (DG 1366) — the controller follows the stored points with straight lines;
* arrays of fix points only (MCO ≥ 5.00, "no interpolation points are used anymore", CR 3955-3958): the curve is
  evaluated from the fix points with `camcurve.spline` — the editor's own piecewise polynomial, whose
  coefficients are evaluated here with Horner's rule (no numpy per tick).

Curve master position (CMASTERCPOS, SYSVAR 4230, MU): M = p + (MAPOS + ΣMOVESYNCORIGIN − a) · SYNCFACTS /
SYNCFACTM with (p, a) the last DEFMCPOS relation (default (0, 0)): 1 MU = SYNCFACTM/SYNCFACTS master qc (DG
1390-1431). It is computed from MAPOS, so DEFMORIGIN changes it too (CR 687). The in-cycle value is M mod
MasterCycleLen. The slave follows T = C + F(M), F(M) = f(M mod L) + ⌊M/L⌋ · SlaveCycleLen, where C (the
"csstart" of CR 913-925) places the curve into the slave's current cycle when SYNCC starts. SYNCCMM corrections
and the SYNCMSTART 2000 start add a shift to M; SYNCCMS corrections move C (kernel/cam_markers.py).

Engage/disengage use the start/stop pairs and the path shapes stored in the array (layout: normalised weight
w(u) × 100000): engaging forward from the slave's position P0 at Start: y = P0 + w(u)·(T − P0), u = (M − Start)/span;
disengaging to the stop position S: y = S + (1 − w(u))·(T − S). Start = Stop engages/stops at once with
VEL/ACC/DEC ("maximum velocity", DG 4050); pair 0 and curves without pairs engage immediately (DG 1485, 4052).
"""

from __future__ import annotations

import bisect
import math
from typing import TYPE_CHECKING

from motiontool.kernel.errors import ControllerError

if TYPE_CHECKING:
    from motiontool.kernel import cam_markers, profile

# camcurve (numpy/scipy, ~0.8 s to import) is imported on the first SETCURVE, not with the kernel.

MAX_CURVE_ARRAY = 2000  # "For that reason the maximum array size is 2000" (CR 3949-3952)
SYNCSTAT_READY, SYNCSTAT_ACCURACY = 1, 4

# CurveFunction._piece of a curve with interpolation points: no x is inside it, `at` evaluates
_NO_PIECE = (math.inf, -math.inf, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)

# CamMotion states
CATCHUP, CURVE, WAIT_START, ENGAGE, WAIT_STOP, DISENGAGE = "catchup", "curve", "wait", "engage", "waitstop", "disengage"


class CurveFunction:
    """f(x): slave position (UU) at in-cycle master position x (MU) of one decoded curve array."""

    def __init__(self, decoded):
        from motiontool.camcurve.model import CurveError
        from motiontool.camcurve.spline import profile

        self.decoded = decoded
        self.length = float(decoded.master_length)
        self.slave_length = float(decoded.slave_length)
        if decoded.interpolation:  # linear between the stored interpolation points (DG 1366)
            self.points = [float(v) for v in decoded.interpolation_points]
            self.step = self.length / (len(self.points) - 1)
            self.linear = True
            self._piece = _NO_PIECE
        else:
            try:
                pp = profile(decoded.to_curve()).ppoly
            except CurveError as exc:
                raise ControllerError(191, f"curve cannot be evaluated: {exc}") from None
            self.breaks = [float(b) for b in pp.x]
            self.coeffs = [tuple(float(c) for c in pp.c[:, i]) for i in range(pp.c.shape[1])]
            self.linear = False
            # per piece: the range of x it is used for (the first and last piece extrapolate), its start and
            # coefficients; evaluation tries the piece of the last call first (the master moves a little per tick)
            last = len(self.coeffs) - 1
            self._pieces = [(-math.inf if j == 0 else self.breaks[j], math.inf if j == last else self.breaks[j + 1],
                             self.breaks[j], *self.coeffs[j]) for j in range(last + 1)]
            self._piece = self._pieces[0]
        self._start = self._shape(decoded.start_path, decoded.interpolation)
        self._stop = self._shape(decoded.stop_path, decoded.interpolation)

    @staticmethod
    def _shape(values, linear: bool):
        """The path weight w(u) for u in 0..1 from the array's stored shape.

        With interpolation points the controller works linearly between stored points, so the shape is followed
        linearly between its M values too; a fix-point curve uses the quintic blend the values were sampled from
        (camcurve.spline.blend) so that velocity and acceleration stay continuous at both ends.
        """
        from motiontool.camcurve.layout import PATH_SCALE

        pts = [v / PATH_SCALE for v in values]
        if not linear:
            rising = pts[-1] > pts[0]
            return _blend if rising else (lambda u: 1.0 - _blend(u))
        n = len(pts) - 1

        def w(u: float) -> float:
            if u <= 0.0:
                return pts[0]
            if u >= 1.0:
                return pts[-1]
            q = u * n
            j = int(q)
            return pts[j] + (q - j) * (pts[j + 1] - pts[j])
        return w

    def engage_weight(self, u: float) -> float:
        return self._start(u)

    def disengage_weight(self, u: float) -> float:
        return self._stop(u)

    def __call__(self, x: float) -> float:
        """f at 0 <= x <= L."""
        return self.at(x)

    def at(self, x: float) -> float:
        """f at 0 <= x <= L (a plain method: the CAM step calls it every tick)."""
        if self.linear:
            q = x / self.step
            j = int(q)
            pts = self.points
            if j >= len(pts) - 1:
                j = len(pts) - 2
            elif j < 0:
                j = 0
            return pts[j] + (q - j) * (pts[j + 1] - pts[j])
        # the piece bisect_right(breaks, x) - 1 (clamped to the pieces) picks: the last one when x is in its range
        lo, hi, start, c0, c1, c2, c3, c4, c5 = self._piece
        if not lo <= x < hi:
            j = bisect.bisect_right(self.breaks, x) - 1
            pieces = self._pieces
            lo, hi, start, c0, c1, c2, c3, c4, c5 = self._piece = pieces[
                0 if j < 0 else j if j < len(pieces) else len(pieces) - 1]
        dx = x - start
        return ((((c0 * dx + c1) * dx + c2) * dx + c3) * dx + c4) * dx + c5

    def periodic(self, m: float) -> float:
        """F(M): the curve continued over cycles, the slave advancing SlaveCycleLen per master cycle."""
        length = self.length
        cycle = math.floor(m / length)
        return self.at(m - cycle * length) + cycle * self.slave_length


def _blend(u: float) -> float:
    """camcurve.spline.blend for one float (no numpy per tick): w = 10u³ − 15u⁴ + 6u⁵ on 0..1."""
    u = 0.0 if u < 0.0 else 1.0 if u > 1.0 else u
    return u * u * u * (10.0 - 15.0 * u + 6.0 * u * u)


def decode_curve_array(name: str, values: list) -> CurveFunction:
    """SETCURVE: validate and pre-calculate; any fault is error 191 naming the APOSS element (1-based)."""
    from motiontool.camcurve.layout import CurveArrayError, decode

    if len(values) > MAX_CURVE_ARRAY:
        raise ControllerError(191, f"SETCURVE {name}: {len(values)} elements, at most {MAX_CURVE_ARRAY}")
    try:
        decoded = decode([int(v) for v in values])
    except CurveArrayError as exc:
        raise ControllerError(191, f"SETCURVE {name}: {name}[{exc.index + 1}]: {exc.message}") from None
    return CurveFunction(decoded)


class CamState:
    """A selected curve and the curve master position (SETCURVE; kernel-spec g.2)."""

    def __init__(self, curve: CurveFunction, master, data, facts: int, factm: int):
        if factm == 0:
            raise ControllerError(183, "SYNCFACTM must not be 0")
        if factm < 0:
            facts, factm = -facts, -factm
        self.curve = curve
        self.master = master
        self.data = data            # ProgramData: mc_ref (DEFMCPOS), sync_shift (MOVESYNCORIGIN)
        self.facts, self.factm = facts, factm
        self.slave_base_qc: float | None = None  # C of the last SYNCC (qc); None: CURVEPOS = f(M mod L)
        self.qc_per_uu = 1.0
        self.temp_origin = 0
        self.mu_shift = 0.0  # SYNCCMM corrections and the SYNCMSTART 2000 start (MU, kernel/cam_markers.py)

    def master_position(self) -> float:
        """Unwrapped curve master position M (MU). (CamMotion.step computes it inline: keep the two alike.)"""
        return self.master_position_at(self.master.mapos)

    def master_position_at(self, mapos: int) -> float:
        """M when MAPOS was `mapos` (a latched master marker), with the corrections made so far."""
        data = self.data
        p, a = data.mc_ref
        return p + (mapos + data.sync_shift - a) * self.facts / self.factm + self.mu_shift

    def cmastercpos(self) -> int:
        length = self.curve.length
        m = self.master_position()
        return math.floor(m - math.floor(m / length) * length)

    def curvepos_uu(self) -> float:
        """Slave curve position (UU, relative to the temporary zero) for the current curve master position."""
        m = self.master_position()
        if self.slave_base_qc is None:
            length = self.curve.length
            return self.curve(m - math.floor(m / length) * length)
        return (self.slave_base_qc + self.curve.periodic(m) * self.qc_per_uu) / self.qc_per_uu - self.temp_origin


def master_curve_position(ctl) -> int | None:
    """CMASTERCPOS / ON MCPOS: in-cycle after SETCURVE, the plain DEFMCPOS count before; None if neither."""
    cam = active_cam(ctl)
    if cam is not None:
        return cam.cmastercpos()
    data = ctl.program_data
    if not data.mc_defined:
        return None
    p, a = data.mc_ref
    s, m = ctl.params["SYNCFACTS"], ctl.params["SYNCFACTM"] or 1
    return math.floor(p + (ctl.master.mapos + data.sync_shift - a) * s / m)


def curve_cycle_length(ctl) -> float | None:
    """MasterCycleLen of the active curve (MU): ON MCPOS positions restart with every cycle."""
    cam = active_cam(ctl)
    return cam.curve.length if cam is not None else None


def active_cam(ctl) -> CamState | None:
    """The curve the running CAM synchronisation uses, else the program's last SETCURVE."""
    sync = ctl.axis.sync
    if isinstance(sync, CamMotion):
        return sync.cam
    return ctl.program_data.cam


class CamMotion:
    """One running SYNCC (axis mode "cam"); stepped by the axis every tick like SyncMotion."""

    kind = "cam"
    # slots: eight axes step their CamMotion every tick; attribute access without an instance dict is faster
    __slots__ = ("cam", "markers", "cycles", "cycles_done", "limits", "vel", "acc", "dec", "accuracy", "k", "temp_qc",
                 "base", "_cycle", "_last_m", "state", "ticks", "locked", "pair", "x_start", "span", "direction", "p0",
                 "stop_qc", "stop_uu", "pending_mcpos", "pending_cam", "finish", "target", "_last_t", "_prev_t",
                 "_relation", "_final")

    def __init__(self, cam: CamState, cycles: int, limits, accuracy: int, slave_qc: float, temp_origin: int,
                 qc_per_uu: float, sync_origin: tuple[int, int] | None = None):
        self.cam = cam
        self.markers: cam_markers.CamMarkers | None = None  # SYNCCMM/SYNCCMS marker correction, SYNCMSTART 2000 start
        self.cycles = max(0, cycles)
        self.cycles_done = 0
        self.limits = limits
        self.vel, self.acc, self.dec = limits.vel, limits.acc, limits.dec
        self.accuracy = accuracy
        self.k = qc_per_uu
        self.temp_qc = temp_origin * qc_per_uu
        cam.qc_per_uu, cam.temp_origin = qc_per_uu, temp_origin
        curve = cam.curve
        if sync_origin is not None:  # DEFSYNCORIGIN mcpos spos with curves (CR 905-945)
            mcpos, spos = sync_origin
            data = cam.data
            data.mc_ref = (mcpos, cam.master.mapos + data.sync_shift)
            data.mc_defined = True
            cam.mu_shift = 0.0
        m = cam.master_position()
        length, sl = curve.length, curve.slave_length
        cycle = math.floor(m / length)
        slave_uu = slave_qc / qc_per_uu - temp_origin          # relative to the temporary zero
        if sync_origin is not None and abs(spos) < abs(sl):
            c = slave_uu - spos - cycle * sl                   # the slave is at curve position spos
        elif sync_origin is not None:
            c = slave_uu - curve.periodic(m)                   # the slave is correct for mcpos
        else:
            # CR 913-925: the slave's cycle start is ⌊slave / SlaveCycleLen⌋ · SlaveCycleLen ("csstart")
            csstart = math.floor(slave_uu / sl) * sl if sl else 0.0
            c = csstart - cycle * sl
        self.base = (c + temp_origin) * qc_per_uu              # C in axis qc
        cam.slave_base_qc = self.base
        self._cycle = cycle
        self._last_m = m
        self.state = CATCHUP
        self.ticks = 0
        self.locked = False
        self.pair: tuple[float, float] | None = None
        self.x_start = 0.0                                     # unwrapped master position of the pair's Start
        self.span = 0.0
        self.direction = 1                                     # the master's direction when the path began
        self.p0 = slave_qc
        self.stop_qc = 0.0
        self.stop_uu = 0.0                                     # SYNCCSTOP's slave stop position (UU)
        self.pending_mcpos: float | None = None
        self.pending_cam: CamState | None = None
        self.finish: tuple[float, profile.Limits] | None = None  # (target qc, limits): the axis positions there
        self.target = self._curve_qc(m)
        self._last_t = self._prev_t = self.target
        self._relation = (cam.data.mc_ref, cam.data.sync_shift)
        self._final = False                                    # SYNCC n: the end of the n cycles is handled

    # --- commands ------------------------------------------------------------------------------------------
    def start(self, pnum: int) -> None:
        """SYNCCSTART pnum (DG 4026-4054): arm the engage unless the slave is already engaged."""
        if self.state in (CURVE, CATCHUP) and self.ticks:
            return  # already on the curve: nothing to engage
        pair = self._pair(pnum)
        if pair is None:
            self.state = CATCHUP
            return
        self.pair = pair
        self.state = WAIT_START
        self.target = self._last_t = self._prev_t = self.p0  # the slave waits where it stands

    def stop(self, pnum: int, slave_pos_uu: float) -> None:
        """SYNCCSTOP pnum slavepos: disengage with pair pnum and stop at slavepos."""
        pair = self._pair(pnum)
        if self.state == DISENGAGE:  # already on the way to a stop position
            return
        self.stop_uu = slave_pos_uu
        if self.state == WAIT_START:  # never engaged: stop where it stands
            self.finish = (self.p0, self.limits)
            return
        if pair is None:
            self._stop_now()
            return
        self.pair = pair
        self.state = WAIT_STOP

    def program_ended(self) -> bool:
        """The program ends in CAM mode (K49): "If the program is closed without the explicit command SYNCCSTOP pnum
        slavepos, then the second point pair will always be used for disengaging" (DG 4054), to the Slave Stop
        Position (DG 3754-3757); without a second pair the slave stops there at once. A stop under way goes on
        (False)."""
        if self.state in (WAIT_STOP, DISENGAGE) or self.finish is not None:
            return False
        self._final = True
        self.stop(2 if len(self.cam.curve.decoded.start_stop_pairs) > 2 else 0,
                  self.cam.curve.decoded.slave_stop_position)
        return True

    def _pair(self, pnum: int) -> tuple[float, float] | None:
        pairs = self.cam.curve.decoded.start_stop_pairs
        if pnum == 0 or len(pairs) <= 1:
            return None  # pair 0 / no pairs: at once with the set maximum velocity (DG 1485, 4052)
        if not 0 < pnum < len(pairs):
            raise ControllerError(183, f"start/stop pair {pnum}: the curve has pairs 1..{len(pairs) - 1}")
        pair = pairs[pnum]
        return float(pair.start), float(pair.stop)

    def _stop_now(self) -> None:
        """Stop at the stop position nearest to where the slave runs to with VEL/DEC."""
        v = self._last_t - self._prev_t
        braking = v * abs(v) / (2 * self.dec)  # signed braking distance
        self.finish = (self._stop_target(self.target + braking), self.limits)

    def _stop_target(self, near_qc: float) -> float:
        """The stop position (UU) in the slave cycle nearest to near_qc, in axis qc."""
        sl = self.cam.curve.slave_length
        s = self.stop_uu
        near_uu = near_qc / self.k - self.temp_qc / self.k
        if sl:
            s += round((near_uu - s) / sl) * sl
        return (s * self.k) + self.temp_qc

    # --- one tick ------------------------------------------------------------------------------------------
    def _curve_qc(self, m: float) -> float:
        return self.base + self.cam.curve.periodic(m) * self.k

    def step(self, pg) -> None:
        # kernel/tick.py repeats the locked CURVE case (steady_cam_tick) operation for operation: change both
        self.ticks += 1
        if self.markers is not None:  # marker corrections inside the correction window (kernel/cam_markers.py)
            self.markers.realise()
        cam = self.cam
        data, master = cam.data, cam.master
        p, a = data.mc_ref  # cam.master_position() inline: this runs every tick on every axis
        m = p + (master.raw - master.origin + data.sync_shift - a) * cam.facts / cam.factm + cam.mu_shift
        curve = cam.curve
        length = curve.length
        cycle = math.floor(m / length)
        if cycle != self._cycle:
            m = self._restart(cycle, m)
            curve, length = self.cam.curve, self.cam.curve.length
            cycle = math.floor(m / length)
        if self.cycles and not self._final:
            self._check_cycles()
        state = self.state
        if state is CURVE or state is CATCHUP:
            x = m - cycle * length
            lo, hi, start, c0, c1, c2, c3, c4, c5 = curve._piece
            if lo <= x < hi:  # curve.at(x) inline for the piece of the last call (nearly every tick)
                dx = x - start
                y = ((((c0 * dx + c1) * dx + c2) * dx + c3) * dx + c4) * dx + c5
            else:
                y = curve.at(x)
            t = self.base + (y + cycle * curve.slave_length) * self.k
        elif state in (WAIT_START, WAIT_STOP):
            t = self.p0 if state == WAIT_START else self._curve_qc(m)
            assert self.pair is not None  # start() and stop() set it with these states
            start, stop = self.pair
            span = (stop - start) % length
            # DG 4040-4046: forward the pair runs Start → Stop; backward it begins at Stop and ends at Start
            if m >= self._last_m:
                direction, crossing = 1, self._crossed(start, m)
            else:
                direction, crossing = -1, self._crossed(stop, m)
            if crossing is not None:
                x_a = crossing if direction > 0 else crossing - span
                if state == WAIT_START:
                    self._place_curve(crossing)
                    if span == 0:
                        self.state = CATCHUP
                    else:
                        self.state, self.x_start, self.span, self.direction = ENGAGE, x_a, span, direction
                elif span == 0:
                    self._stop_now()
                else:
                    self.state, self.x_start, self.span, self.direction = DISENGAGE, x_a, span, direction
                    end = x_a + span if direction > 0 else x_a
                    self.stop_qc = self._stop_target(self._curve_qc(end))
                return self.step_again(pg, m)
        elif state == ENGAGE:
            # u runs 0 → 1 from Start to Stop; backward, engaging follows the disengage path from Stop to Start
            u = (m - self.x_start) / self.span
            curve_t = self._curve_qc(m)
            if self.direction > 0:
                w, done = cam.curve.engage_weight(u), u >= 1.0
            else:
                w, done = cam.curve.disengage_weight(u), u <= 0.0
            t = self.p0 + w * (curve_t - self.p0)
            if done:
                self.state = CATCHUP
                t = curve_t
        else:  # DISENGAGE (backward along the engage path)
            u = (m - self.x_start) / self.span
            s = self.stop_qc
            if self.direction > 0:
                w, done = cam.curve.disengage_weight(u), u >= 1.0
            else:
                w, done = cam.curve.engage_weight(u), u <= 0.0
            t = s + w * (self._curve_qc(m) - s)
            if done:
                t = s
                self.finish = (s, self.limits)
        self._last_m = m
        data = cam.data
        if data.mc_ref is not self._relation[0] or data.sync_shift != self._relation[1]:
            relation = (data.mc_ref, data.sync_shift)
            if relation != self._relation:  # DEFMCPOS / MOVESYNCORIGIN moved the curve: caught up within the limits
                self.locked = False
                self._last_t = self._prev_t = pg.position
            self._relation = relation
        last = self._last_t
        vt = t - last
        if self.locked and abs(vt) <= self.vel * (1 + 1e-9):  # _follow's locked case inline (every tick on the curve)
            self._prev_t = last
            self._last_t = self.target = t
            v0 = pg.velocity
            pg.position = t
            pg.acceleration = vt - v0
            pg.velocity = vt
        else:
            self._follow(pg, t)
        if self.state == CATCHUP and self.locked:
            self.state = CURVE

    def _place_curve(self, x: float) -> None:
        """Engaging at master x: the engage path runs from the slave stop position to the curve in the same slave
        cycle (DG 3916-3930: "the slave stop position … is the position where the engage curve starts"), so the
        curve is placed into the cycle whose stop position is nearest to where the slave stands."""
        curve = self.cam.curve
        sl = curve.slave_length
        if not sl:
            return
        k = self.k
        stop_qc = curve.decoded.slave_stop_position * k + self.temp_qc
        n = round((self.p0 - stop_qc) / (sl * k))
        self.base = n * sl * k + self.temp_qc - math.floor(x / curve.length) * sl * k
        self.cam.slave_base_qc = self.base

    def step_again(self, pg, m: float) -> None:
        """A state change in this tick: evaluate the new state without counting another tick."""
        self.ticks -= 1
        self._last_m = m
        self.step(pg)

    def _crossed(self, x: float, m: float) -> float | None:
        """The unwrapped master position ≡ x (mod L) passed between the last tick and m (either way), if any."""
        last = self._last_m
        length = self.cam.curve.length
        if m > last:
            at = x + math.floor((last - x) / length + 1) * length  # first x + jL above last
            return at if at <= m else None
        if m < last:
            at = x + math.ceil((last - x) / length - 1) * length   # first x + jL below last
            return at if at >= m else None
        return None

    def _restart(self, cycle: int, m: float) -> float:
        """The curve restarts (master passed a cycle end): count the cycle, apply a DEFMCPOS or SETCURVE that
        waited for it (CR 3936-3944), keeping the slave's target position continuous."""
        forward = cycle > self._cycle
        self._cycle = cycle
        if self.pending_mcpos is not None or self.pending_cam is not None:
            before = self._curve_qc(m)
            if self.pending_cam is not None:
                new = self.pending_cam
                new.qc_per_uu, new.temp_origin = self.cam.qc_per_uu, self.cam.temp_origin
                new.mu_shift = self.cam.mu_shift  # CMASTERCPOS is not changed by SETCURVE in SYNCC (CR 3936)
                self.cam, self.pending_cam = new, None
            if self.pending_mcpos is not None:
                data = self.cam.data
                into = m - cycle * self.cam.curve.length
                data.mc_ref = (self.pending_mcpos + into, self.cam.master.mapos + data.sync_shift)
                self.cam.mu_shift = 0.0
                self.pending_mcpos = None
            m = self.cam.master_position()
            self.base += before - self._curve_qc(m)
            self.cam.slave_base_qc = self.base
            self._cycle = math.floor(m / self.cam.curve.length)
            self._last_m = m
        if forward and self.state in (CURVE, CATCHUP, ENGAGE):  # cycles run on the curve count (SYNCC n)
            self.cycles_done += 1
        if self.markers is not None:  # marker distances and numbers are taken over at the restart (CR 3936)
            self.markers.read_parameters()
        return m

    def _check_cycles(self) -> None:
        """SYNCC n: in the n-th cycle the second pair disengages to the Slave Stop Position; without it the slave
        stops at that position after the n-th cycle (DG 3754-3760, 4054)."""
        n = self.cycles
        if self.state not in (CURVE, CATCHUP):
            return
        pairs = self.cam.curve.decoded.start_stop_pairs
        has_second = len(pairs) > 2 and pairs[2].start != pairs[2].stop
        if has_second and self.cycles_done >= n - 1:
            self._final = True
            self.stop(2, self.cam.curve.decoded.slave_stop_position)
        elif self.cycles_done >= n and not has_second:
            self._final = True
            self.stop_uu = self.cam.curve.decoded.slave_stop_position
            self._stop_now()

    def _follow(self, pg, t: float) -> None:
        """Track the target within VEL and ACC/DEC (kernel-spec f.0); lock onto it when caught up."""
        last = self._last_t
        vt = t - last
        # The curve's own change of velocity is the editor's business (Curve Info checks it against the limits,
        # DG 3799-3833), and the master counts whole qc: once locked the slave follows the target exactly (its
        # velocity is the target's) and only VEL unlocks it; ACC/DEC limit catching up (engage at maximum velocity,
        # a moved curve master position).
        prev = self._prev_t
        self._prev_t, self._last_t = last, t
        self.target = t
        v0 = pg.velocity
        locked = self.locked
        if locked and abs(vt) > self.vel * (1 + 1e-9):
            locked = self.locked = False
        if locked:
            v = vt
            pg.position = t
        else:
            own = abs(vt - (last - prev)) + 1e-9
            gap = t - pg.position
            d = gap - vt
            brake = min(self.acc, self.dec)
            w = math.copysign(min(abs(d), brake * (math.sqrt(0.25 + 2.0 * abs(d) / brake) - 0.5)), d)
            v = self._ramp(v0, max(-self.vel, min(self.vel, vt + w)))
            if abs(gap - v) <= 1.0 and abs(vt - v0) <= self._acc_limit(v0, vt) + own and abs(vt) <= self.vel:
                self.locked = True
                v = vt
                pg.position = t
            else:
                pg.position += v
        pg.acceleration = v - v0
        pg.velocity = v

    def _acc_limit(self, v0: float, v1: float) -> float:
        return self.acc if abs(v1) > abs(v0) and v1 * v0 >= 0 else self.dec

    def _ramp(self, v0: float, v1: float) -> float:
        lim = self._acc_limit(v0, v1)
        return v0 + max(-lim, min(lim, v1 - v0))

    # --- the interface controller.syncerr / syncstat use ----------------------------------------------------
    def shift(self, delta: float) -> None:
        """The slave's origin moved (DEFORIGIN during SYNCC): the curve moves with it."""
        self.base += delta
        self.cam.slave_base_qc = self.base
        self.target += delta
        self._last_t += delta
        self.p0 += delta
        self.stop_qc += delta

    def error_qc(self, apos: int) -> float:
        return self.target - apos

    def status(self, apos: int) -> int:
        markers = self.markers
        bits = SYNCSTAT_READY if self.state == CURVE and (markers is None or markers.ready) else 0
        if markers is not None:
            bits |= markers.fault_bit()
        if self.state in (CURVE, CATCHUP, ENGAGE) and abs(self.target - apos) <= abs(self.accuracy):
            bits |= SYNCSTAT_ACCURACY
        return bits
