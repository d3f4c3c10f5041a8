"""Many milliseconds of a synchronised CAM line at once (issue 30 item 1: 32 CAM axes ≥ 20× real time).

While every node of a Simulation is in the steady state of kernel/tick.py — its axis locked on its CAM curve in one
master cycle, its master counter at a constant speed, its program waiting on an input or a time no tick can change
(or not running), nothing else armed — the next ticks differ only by the master's increments. `run` then runs a
stretch of them node by node instead of tick by tick:

* the master positions and every axis's CAM targets, which do not feed back, for the whole stretch at once with
  numpy — the same IEEE operations element by element (np.add.accumulate adds in sequence like the tick does;
  integers stay below 2^50, where float64 and Python's ints agree);
* the position law and the plant, which feed back, in one tight loop per axis (the statements of
  steady_cam_tick);
* the marker inputs' test per tick, calling Markers.tick itself where an index pulse passes.

The stretch ends before the first tick where any node leaves that state (a new curve cycle, an unlock, a tracking
error beyond POSERR, the wait's end); that tick runs generally. Nothing crosses between nodes in that state but
the master signal (CAN idle, no PRINT output), so running node after node gives the ticks' results.
tests/kernel/test_steady_line.py holds a stretch and the same ticks one by one identical (decisions K129).
"""

from __future__ import annotations

import math

import numpy as np

from motiontool.kernel.cam import CURVE
from motiontool.kernel.command_base import Deadline, InputWait
from motiontool.kernel.markers import _NONE
from motiontool.kernel.plant import Plant

MIN_TICKS = 16      # below this numpy's per-call cost exceeds what a stretch saves
MAX_TICKS = 2048    # one stretch's arrays stay small
_EXACT = 2.0 ** 50  # float64 holds every integer below 2^53 exactly; sums of four such stay below it
_floor = math.floor
_copysign = math.copysign


def _number(x) -> bool:
    return type(x) in (int, float) and abs(x) < _EXACT


def _marker_key(ctl) -> tuple:
    """What the markers' fast path was computed for (controller_tick's key: scaling, 32-31, 33-19, 33-20)."""
    values = ctl.params.values
    return ctl.axis.scaling, values[3231], values[3319], values[3320]


class _Node:
    """One controller's part of a stretch: its constants, then its computed ticks."""

    state: tuple | None  # the closed loop's state after the ticks `follow` was asked for (None: it stopped earlier)

    def __init__(self, ctl, velocity: float):
        self.ctl, self.v = ctl, velocity
        self.axis = ctl.axis
        self.sync = ctl.axis.sync
        self.markers = ctl.markers
        self.key = _marker_key(ctl)

    # --- the open-loop part: master and CAM targets --------------------------------------------------------
    def targets(self, k: int) -> int:
        """The master positions and CAM targets of up to k ticks; how many of them stay in the steady state."""
        master, sync = self.ctl.master, self.sync
        cam = sync.cam
        data, curve = cam.data, cam.curve
        p, a = data.mc_ref
        shift, origin, facts, factm, mu_shift = data.sync_shift, master.origin, cam.facts, cam.factm, cam.mu_shift
        if not all(_number(x) for x in (p, a, shift, origin, facts, factm, mu_shift, master.position)):
            return 0
        if not factm or not curve.length:  # the tick divides by them: its ZeroDivisionError, not numpy's inf
            return 0
        steps = np.empty(k + 1)
        steps[0], steps[1:] = master.position, self.v
        position = np.add.accumulate(steps)[1:]          # position = position + v, tick after tick
        raw = np.floor(position)
        counts = raw - origin + shift - a
        product = counts * facts
        if not (np.abs(position).max() < _EXACT and np.abs(product).max() < _EXACT * 8):
            return 0
        m = p + product / factm + mu_shift
        length = curve.length
        cycle = np.floor(m / length)
        k = _first(cycle != sync._cycle, k)               # a new cycle: CamMotion._restart's work
        x = m - cycle * length
        if curve.linear:
            pts = np.array(curve.points)
            q = x / curve.step
            j = np.clip(np.trunc(q), 0, len(pts) - 2).astype(np.intp)  # int(q), then clamped as curve.at does
            y = pts[j] + (q - j) * (pts[j + 1] - pts[j])
        else:
            pieces = curve._pieces
            j = np.clip(np.searchsorted(curve.breaks, x, side="right") - 1, 0, len(pieces) - 1)
            c = np.array([piece[2:] for piece in pieces])[j]
            dx = x - c[:, 0]
            y = ((((c[:, 1] * dx + c[:, 2]) * dx + c[:, 3]) * dx + c[:, 4]) * dx + c[:, 5]) * dx + c[:, 6]
        t = sync.base + (y + cycle * curve.slave_length) * sync.k
        before = np.empty(len(t))
        before[0], before[1:] = sync._last_t, t[:-1]
        vt = t - before
        k = _first(~(np.abs(vt) <= sync.vel * (1 + 1e-9)), k)  # unlocks (or is not a number): CamMotion._follow
        accel = np.empty(k)
        if k:
            accel[0] = vt[0] - self.axis.profile.velocity
            accel[1:] = vt[1:k] - vt[:k - 1]
        self.position, self.raw, self.m = position[:k].tolist(), raw[:k].tolist(), m[:k].tolist()
        self.t, self.vt, self.accel = t[:k].tolist(), vt[:k].tolist(), accel.tolist()
        self.pieces = None if curve.linear else j[:k]  # each tick's piece: curve.at keeps the last one
        return k

    # --- the closed loop: position law and plant ------------------------------------------------------------
    def follow(self, k: int) -> int:
        """The position law and the plant for k ticks (steady_cam_tick's statements), from the axis's state;
        stops before a tick whose tracking error is beyond POSERR. Keeps its result, changes nothing."""
        axis = self.axis
        plant, g, cfg = axis.plant, axis.gains, axis.plant.config
        ticks, reference, integral = axis._tick, axis.reference, axis.integral
        v, pos, apos, origin = plant.velocity, plant.position, axis.apos, axis.origin
        timer, poserr, alpha = g.timer, g.poserr, plant._alpha
        bw, kp, integrating = g.bandwidth_1000, g.kprop_1000, g.integrating
        ffvel, ffvel_k, kder, kder_k, ffacc, ffacc_k = g.ffvel, g.ffvel_1000, g.kder, g.kder_1000, g.ffacc, g.ffacc_1000
        kint, ilimit = g.kint, g.kilim / 1000.0 * axis.scaling.vmax
        blocked, friction = cfg.blocked, cfg.friction
        limit = cfg.speed_limit * axis.scaling.vmax
        self.asked = k
        positions: list[float] = []
        keep = positions.append
        for t, vt, acc in zip(self.t[:k], self.vt[:k], self.accel[:k], strict=True):
            ticks += 1
            if ticks >= timer:
                ticks = 0
                e = t - apos
                if integrating:  # Axis._integral_term
                    integral += e
                    term = kint * integral / 1e6
                    if abs(term) > ilimit:
                        term = _copysign(ilimit, term)
                        integral = term * 1e6 / kint
                    reference = bw * (kp * e + term)
                else:
                    reference = bw * (kp * e + 0.0)
                if ffvel:
                    reference += ffvel_k * vt
                if kder:
                    reference -= kder_k * v
                if ffacc:
                    reference += ffacc_k * acc
            if blocked:
                v = 0.0
            else:
                ref = limit if reference > limit else (-limit if reference < -limit else reference)
                v = v + (ref - v) * alpha
                if friction:
                    v = _copysign(max(abs(v) - friction, 0.0), v)
                pos += v
            apos = _floor(pos) - origin
            if abs(t - apos) > poserr:
                break  # Axis._monitor: this tick runs generally
            keep(pos)
        else:
            self.state, self.slave = (ticks, reference, integral, v, apos), positions
            return k
        self.state, self.slave, self.asked = None, positions, -1  # stopped: run again to the stretch's end
        return len(positions)

    # --- the marker inputs ----------------------------------------------------------------------------------
    def mark(self, k: int) -> None:
        """controller_tick's marker test for k ticks; Markers.tick where it does not hold."""
        markers, key, master, plant = self.markers, self.key, self.ctl.master, self.axis.plant
        m_lo, m_hi, s_lo, s_hi = markers._q
        quiet = True  # _steady_controller found the key quiet
        for m1, s1 in zip(self.position[:k], self.slave, strict=True):
            if not quiet:  # after Markers.tick: the tick's test of the key, as controller_tick does it
                quiet = key == markers._q_key or markers._quiet(key)
                m_lo, m_hi, s_lo, s_hi = markers._q
            if quiet and (m_lo < m1 < m_hi or m1 == markers._m) and (s_lo < s1 < s_hi or s1 == markers._s):
                markers._m, markers._s = m1, s1
                markers.master_events = markers.slave_events = _NONE
                continue
            master.position, plant.position = m1, s1  # what Markers.tick reads
            markers.tick()
            quiet = False

    # --- the result -----------------------------------------------------------------------------------------
    def commit(self, k: int) -> None:
        ctl, axis, sync, master = self.ctl, self.axis, self.sync, self.ctl.master
        ctl.time_ms += k
        master.velocity = self.v
        master.position = self.position[k - 1]
        master.raw = int(self.raw[k - 1])
        master._history.extend(int(r) for r in self.raw[max(0, k - master._history.maxlen):k])
        sync.ticks += k
        sync._last_m = self.m[k - 1]
        sync._prev_t = self.t[k - 2] if k > 1 else sync._last_t
        sync._last_t = sync.target = t = self.t[k - 1]
        if self.pieces is not None:  # the stretch may end before the ticks this node planned
            sync.cam.curve._piece = sync.cam.curve._pieces[int(self.pieces[k - 1])]
        pg = axis.profile
        pg.position, pg.acceleration, pg.velocity = t, self.accel[k - 1], self.vt[k - 1]
        assert self.state is not None  # run() followed every node to the stretch's end
        ticks, reference, integral, v, apos = self.state
        axis._tick, axis.reference, axis.apos, axis._poserr_count = ticks, reference, apos, 0
        if axis.gains.integrating:
            axis.integral = integral
        plant = axis.plant
        plant.velocity, plant.position = v, self.slave[k - 1]
        origin = axis.origin
        axis.raw_history.extend(_floor(s) - origin + origin for s in self.slave[max(0, k - axis.raw_history.maxlen):k])


def _first(bad: np.ndarray, k: int) -> int:
    """The index of the first True among the first k, else k."""
    hits = np.flatnonzero(bad[:k])
    return int(hits[0]) if hits.size else k


def _steady_axis(axis) -> bool:
    """steady_cam_tick's conditions that no tick of a stretch changes."""
    sync = axis.sync
    if (axis.mode != "cam" or sync is None or sync.state is not CURVE or not sync.locked or sync.markers is not None
            or sync.finish is not None or (sync.cycles and not sync._final) or not axis.control_on
            or axis.homing is not None or type(axis.plant) is not Plant or axis.gains.window):
        return False
    data = sync.cam.data
    return data.mc_ref is sync._relation[0] and data.sync_shift == sync._relation[1]


def _wait_limit(ctl) -> int | None:
    """How many ticks the program stays as it is (None: not steady)."""
    if ctl.program_state != "running":
        return MAX_TICKS
    vm = ctl.vm
    wait = vm.wait
    if wait is None or vm.ended or ctl.interrupts.sources or ctl.error:
        return None
    kind = type(wait)  # known kinds first: some waits' done() takes what it waits for (a CAN poll)
    if kind is InputWait and not wait.done():  # inputs change by events, requests or CAN: none in a stretch
        return MAX_TICKS
    if kind is Deadline and not wait.done():
        return wait.end - ctl.time_ms - 1
    return None


def _steady_controller(ctl) -> int | None:
    """The ticks this controller can run in a stretch apart from its axis's motion (None: none)."""
    axis, can = ctl.axis, ctl.can
    if (ctl.io.events or ctl._functions is None or ctl._functions or ctl.output or ctl.recorder.active is not None
            or ctl.soft_limits != (None, None) or ctl.limit_blocked_direction or not _steady_axis(axis)
            or can.inbox or can.busy or can.heartbeat_ms or can.pdo.active or can.sdo.channels
            or (can.own_bus and (can.bus.pending or can.bus.injected))):
        return None
    markers, key = ctl.markers, _marker_key(ctl)
    if not (key == markers._q_key or markers._quiet(key)):
        return None
    return _wait_limit(ctl)


def _master_velocity(master) -> float | None:
    """The constant increment of a master counter through a stretch (None: it is not constant)."""
    if master.virtual:  # Master.tick: at its target speed the virtual master stays there
        return master.virtual_target if master.virtual_speed == master.virtual_target else None
    feed = master.feed
    if feed is None:
        return None
    if feed.virtual:
        return _master_velocity(feed)
    return 0.0 if master.feed_virtual_only else None


def run(sim, ms: int) -> int:
    """Run up to `ms` ticks of the simulation as one stretch; the ticks run (0: the next tick runs generally)."""
    if ms < MIN_TICKS or sim.encoder is not None or sim.can_bus.pending or sim.can_bus.injected:
        return 0
    if not all(steady() for steady in sim.steady_tickers()):
        return 0
    k = min(ms, MAX_TICKS)
    nodes = []
    for n in sim.order:
        ctl = sim.controllers[n]
        limit = _steady_controller(ctl)
        v = _master_velocity(ctl.master)
        if limit is None or v is None or not _number(v):
            return 0
        nodes.append(_Node(ctl, v))
        k = min(k, limit)
    if k < 1:  # the next tick ends a DELAY
        return 0
    for node in nodes:
        k = min(k, node.targets(k))
        if k <= 0:
            return 0
    followed = []
    for node in nodes:
        k = min(k, node.follow(k))
        followed.append(node)
        if k == 0:
            return 0
    for node in followed:
        if node.asked != k:
            node.follow(k)  # the stretch ends earlier than this node was run: the same loop, to that tick
    for node in nodes:
        node.mark(k)
        node.commit(k)
    sim.time_ms += k
    return k
