"""One millisecond of the simulated MCO 305, fused (issue 30: 32 synchronised axes fast).

`controller_tick` is Controller.tick: scripted inputs → machine switches → master counter → axis (profile, control,
plant, encoder, monitoring) → markers → recording → CAN → interrupts and a slice of the program → PRINT output
(kernel/controller.py's module docstring). It is one function because a call costs as much as a line of the
position law, and 32 axes tick 32 000 times per simulated second: the steady state of the common cases runs
inline — a counter fed by another node's (or its own virtual) master, and an axis locked on its CAM curve
(`steady_cam_tick`) — with the same floating-point operations in the same order as Master.tick, Axis.tick,
CamMotion.step and Plant.step, which every other case still calls. tests/kernel/test_trace_identity.py holds the
traces to today's row for row (decisions K127).
"""

from __future__ import annotations

import math

from motiontool.kernel.cam import CURVE
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.markers import _NONE
from motiontool.kernel.plant import Plant

INSTRUCTIONS_PER_TICK = 500  # program speed: machine instructions per ms (docs/decisions.md)
_floor = math.floor


def steady_cam_tick(axis) -> bool:
    """Axis.tick of an axis in CAM mode locked on its curve in the same master cycle, with no markers, no cycle
    count to watch, no moved relation, no homing and the control on (nearly every tick of a CAM line): CamMotion.step
    and the rest of Axis.tick inline; False, having changed nothing, in any other case."""
    sync = axis.sync
    if (sync.state is not CURVE or not sync.locked or sync.markers is not None or sync.finish is not None
            or (sync.cycles and not sync._final) or not axis.control_on or axis.homing is not None):
        return False
    plant = axis.plant
    if type(plant) is not Plant:
        return False
    cam = sync.cam
    data, master = cam.data, cam.master
    mc_ref = data.mc_ref
    relation = sync._relation
    if mc_ref is not relation[0] or data.sync_shift != relation[1]:
        return False
    p, a = mc_ref
    m = p + (master.raw - master.origin + data.sync_shift - a) * cam.facts / cam.factm + cam.mu_shift
    curve = cam.curve
    length = curve.length
    cycle = _floor(m / length)
    if cycle != sync._cycle:
        return False
    x = m - cycle * length
    lo, hi, start, c0, c1, c2, c3, c4, c5 = curve._piece
    if lo <= x < hi:
        dx = x - start
        y = ((((c0 * dx + c1) * dx + c2) * dx + c3) * dx + c4) * dx + c5
    else:
        y = curve.at(x)
    t = sync.base + (y + cycle * curve.slave_length) * sync.k
    last = sync._last_t
    vt = t - last
    if not abs(vt) <= sync.vel * (1 + 1e-9):
        return False  # unlocks (or is not a number): CamMotion._follow
    # CamMotion.step, locked on the curve
    sync.ticks += 1
    sync._last_m = m
    sync._prev_t = last
    sync._last_t = sync.target = t
    pg = axis.profile
    v0 = pg.velocity
    pg.position = t
    pg.acceleration = vt - v0
    pg.velocity = vt
    # the position law, every TIMER ms (kernel/axis.py)
    g = axis.gains
    ticks = axis._tick + 1
    if ticks >= g.timer:
        axis._tick = 0
        e = t - axis.apos
        if g.window and axis._posfloat(pg, e):
            reference = 0.0
        else:
            reference = g.bandwidth_1000 * (g.kprop_1000 * e + (axis._integral_term(e) if g.integrating else 0.0))
            if g.ffvel:
                reference += g.ffvel_1000 * vt
            if g.kder:
                reference -= g.kder_1000 * plant.velocity
            if g.ffacc:
                reference += g.ffacc_1000 * pg.acceleration
        axis.reference = reference
    else:
        axis._tick = ticks
        reference = axis.reference
    cfg = plant.config
    if cfg.blocked:  # Plant.step
        plant.velocity = 0.0
    else:
        limit = cfg.speed_limit * axis.scaling.vmax
        ref = limit if reference > limit else (-limit if reference < -limit else reference)
        v = plant.velocity
        v = v + (ref - v) * plant._alpha
        if cfg.friction:
            v = math.copysign(max(abs(v) - cfg.friction, 0.0), v)
        plant.velocity = v
        plant.position += v
    origin = axis.origin
    axis.apos = apos = _floor(plant.position) - origin
    axis.raw_history.append(apos + origin)
    if abs(t - apos) > g.poserr:  # Axis._monitor's common case inline
        axis._monitor()
    else:
        axis._poserr_count = 0
    return True


def controller_tick(ctl) -> None:
    """Advance one millisecond; then the link takes PRINT output (all, or output_per_tick lines)."""
    ctl.time_ms = time_ms = ctl.time_ms + 1
    if ctl.io.events:
        ctl.io.apply_events(time_ms)
    try:
        functions = ctl._functions
        if functions is None or functions:
            ctl._machine_inputs()
        master = ctl.master
        feed = master.feed
        if not master.virtual and feed is not None:  # Master.tick of a counter on another node's master signal
            v = feed.velocity if feed.virtual or not master.feed_virtual_only else 0.0
            master.velocity = v
            master.position = position = master.position + v
            master.raw = raw = _floor(position)
            master._history.append(raw)
        else:
            master.tick(time_ms)
        axis = ctl.axis
        if axis.mode != "cam" or not steady_cam_tick(axis):
            axis.tick()
        markers = ctl.markers
        sync = axis.sync
        if sync is None or sync.markers is None:  # Markers.tick's fast path inline: no marker can come this tick
            values = ctl.params.values
            key = (axis.scaling, values[3231], values[3319], values[3320])
            if key == markers._q_key or markers._quiet(key):
                m1 = master.position
                s1 = axis.plant.position
                m_lo, m_hi, s_lo, s_hi = markers._q
                if (m_lo < m1 < m_hi or m1 == markers._m) and (s_lo < s1 < s_hi or s1 == markers._s):
                    markers._m, markers._s = m1, s1
                    markers.master_events = markers.slave_events = _NONE
                else:
                    markers.tick()
            else:
                markers.tick()
        else:
            markers.tick()
        if axis.homing is not None and axis.homing.done:
            ctl._homing_finished()
        if ctl.soft_limits != (None, None) and axis.mode not in ("idle", "positioning"):
            ctl._soft_limits_while_moving()
        if ctl.limit_blocked_direction and ctl._inside_soft_limits():
            ctl.limit_blocked_direction = 0
    except ControllerError as exc:
        ctl.raise_error(exc)
    if ctl.recorder.active is not None:
        ctl.recorder.sample(time_ms)
    can = ctl.can
    if (can.inbox or can.busy or can.heartbeat_ms or can.pdo.active or can.sdo.channels
            or (can.own_bus and (can.bus.pending or can.bus.injected))):  # CanPort.tick's idle test inline
        can.tick(time_ms)
    if ctl.program_state == "running":  # a slice of the program (inline: every tick)
        vm = ctl.vm
        try:
            if ctl.interrupts.sources or ctl.error:
                ctl._serve_interrupts(vm)
            wait = vm.wait
            if wait is None or vm.ended:
                vm.run(INSTRUCTIONS_PER_TICK)
            elif wait.done():  # VM.run's test of the wait inline: a waiting program costs one test per tick
                vm.wait = None
                if wait.value is not None:
                    vm.stack.append(wait.value)
                vm.run(INSTRUCTIONS_PER_TICK)
        except ControllerError as exc:
            ctl.raise_error(exc)
        except Exception as exc:  # noqa: BLE001 - a fault of the simulator itself (decisions K81)
            ctl.internal_fault(exc)
        else:
            if vm.ended and ctl.program_state == "running":
                ctl._end_program("ended")
    if ctl.output:
        ctl.send_output(ctl.output_per_tick)
