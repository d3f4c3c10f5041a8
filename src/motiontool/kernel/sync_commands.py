"""The synchronisation commands: SYNCV, SYNCP, SYNCM, the virtual master, and CAM control (SETCURVE,
CURVEPOS, SYNCC...). Registered into `commands.COMMANDS` like every other command; the motion itself lives in
kernel/sync.py, kernel/markers.py, kernel/master.py and kernel/cam.py.
"""

from __future__ import annotations

from motiontool.kernel.cam import CamMotion, CamState, active_cam, decode_curve_array
from motiontool.kernel.cam_markers import CamMarkers
from motiontool.kernel.command_base import COMMANDS, command, motion_allowed, motion_limits, position_to
from motiontool.kernel.errors import ControllerError
from motiontool.kernel.markers import MarkerSync
from motiontool.kernel.sync import Gear, SyncMotion, velocity_filter_ms


# --- synchronisation (kernel-spec f; docs in kernel/sync.py and kernel/master.py) ----------------------------
def _gear(ctl, start: int = 0) -> Gear:
    return Gear(ctl.params["SYNCFACTS"], ctl.params["SYNCFACTM"], start)


def _sync_options(ctl) -> dict:
    """SYNCVELREL, velocity filter, SYNCOFFTIME, REVERS as of the SYNC command (DG 9462-9843, 8790)."""
    p = ctl.params
    vfilter = velocity_filter_ms(p["SYNCVFTIME"], p["MENCODER"])
    negative = p["SYNCVFTIME"] < 0  # DG 9800: "a negative number … also applies for … SYNCP and … SYNCM"
    return {"velrel": p["SYNCVELREL"], "vfilter_ms": vfilter, "pfilter_ms": vfilter if negative else 0.0,
            "offtime": p["SYNCOFFTIME"], "marker_distance": p["SYNCMPULSM"], "revers": p["REVERS"],
            "ffvel": p["SYNCFFVEL"], "spread_ms": 10 * vfilter if negative else 0.0}


@command("SYNCV")
def syncv(ctl, vm, args):
    motion_allowed(ctl, "SYNCV")
    ctl.axis.synchronise(SyncMotion("velocity", ctl.master, _gear(ctl), motion_limits(ctl), **_sync_options(ctl)))


@command("SYNCP")
def syncp(ctl, vm, args, markers: bool = False):
    """CR 891-975, DG 944-1140, 9411-9428: CPOS follows MAPOS × gear from the relation at the start (decision K17):
    "the actual slave position will be locked to the actual master position" (DG 948) — the slave's commanded
    position belongs to the current MAPOS; a SYNCP/SYNCM while one runs keeps the running relation; DEFSYNCORIGIN m s
    makes slave s belong to master m instead. SYNCPOSOFFS and MOVESYNCORIGIN (master qc) shift the slave from
    there, SYNCPOSOFFS "immediately when the command SYNCP follows" (DG 9418). With `markers` it is SYNCM
    (kernel/markers.py)."""
    motion_allowed(ctl, "SYNCM" if markers else "SYNCP")
    marker_sync = None
    data = ctl.program_data
    values = ctl.params.values
    offs_index = ctl.params.parameter("SYNCPOSOFFS").index

    def offset() -> int:
        if marker_sync is not None and not marker_sync.offset_active:  # SYNCMSTART 1000-1007
            return 0
        return values[offs_index]

    start_mode = ctl.params["SYNCMSTART"]
    if markers and 1000 <= start_mode < 2000:
        marker_sync = MarkerSync(ctl, None, start_mode)
    gear = _gear(ctl)
    shift, data.next_sync_shift = data.next_sync_shift, 0
    running = _position_sync(ctl)
    if data.sync_origin is not None:
        base_master, base_slave = data.sync_origin
        data.sync_origin = None
        shift = 0  # DEFSYNCORIGIN overrides an earlier MOVESYNCORIGIN (CR 903-906)
    elif running is not None:  # the running relation goes on: the slave is where its target is heading
        base_master = ctl.master.mapos
        base_slave = round(running.target + running.pending_qc()) - Gear(gear.s, gear.m, offset()).out
    else:
        base_master, base_slave = ctl.master.mapos, round(ctl.axis.cpos)
    gear = _gear(ctl, ctl.master.mapos - base_master + offset() + shift)
    motion = SyncMotion("position", ctl.master, gear, motion_limits(ctl), offset, base_slave,
                        ctl.params["SYNCACCURACY"], shift=shift, **_sync_options(ctl))
    if markers:
        marker_sync = marker_sync or MarkerSync(ctl, motion, start_mode)
        marker_sync.motion = motion
        motion.markers = marker_sync
    ctl.axis.synchronise(motion)


def _position_sync(ctl) -> SyncMotion | None:
    sync = ctl.axis.sync
    return sync if ctl.axis.mode == "sync" and isinstance(sync, SyncMotion) and sync.kind == "position" else None


@command("MOVESYNCORIGIN")
def movesyncorigin(ctl, vm, args):
    """CR 2397-2415: shifts the origin of synchronisation relatively (master qc): of the running SYNCP/SYNCM, else
    of the next one (decision K17); the curve master position moves with it in CAM (CR 3936)."""
    data = ctl.program_data
    data.sync_shift += args[0]
    running = _position_sync(ctl)
    if running is not None:
        running.origin_shift += args[0]
    else:
        data.next_sync_shift += args[0]


@command("DEFSYNCORIGIN")
def defsyncorigin(ctl, vm, args):
    ctl.program_data.sync_origin = (args[0], args[1])  # master qc, slave qc (CR 891-906)


@command("SYNCSTATCLR")
def syncstatclr(ctl, vm, args):
    ctl.program_data.syncstat_flags &= ~args[0]


# --- marker synchronisation: SYNCM, SYNCMARKERSTART (docs in kernel/markers.py) ------------------------------
@command("SYNCM")
def syncm(ctl, vm, args):
    """DG 1143-1340, 9494-10032: SYNCP plus marker correction."""
    return syncp(ctl, vm, args, markers=True)


@command("SYNCMARKERSTART")
def syncmarkerstart(ctl, vm, args):
    """DG 7242: restarts the marker handling of a running SYNCM (both restart types alike)."""
    marker_sync = getattr(ctl.axis.sync, "markers", None)
    if marker_sync is not None:
        marker_sync.restart()
# --- end of marker synchronisation ------------------------------------------------------------------------


@command("PULSVEL")
def pulsvel(ctl, vm, args):
    ctl.master.pulsvel(args[0])


@command("PULSACC")
def pulsacc(ctl, vm, args):
    ctl.master.pulsacc(args[0])


@command("DEFMORIGIN")
def defmorigin(ctl, vm, args):
    ctl.master.defmorigin()


@command("SETMORIGIN")
def setmorigin(ctl, vm, args):
    ctl.master.setmorigin(args[0])


# --- CAM control (kernel-spec g; docs in kernel/cam.py) --------------------------------------------------------
def _cam_state(ctl, what: str):
    cam = active_cam(ctl)
    if cam is None:
        raise ControllerError(191, f"{what} needs a curve: SETCURVE first (CR 3913-3917)")
    return cam


def _cam_motion(ctl):
    sync = ctl.axis.sync
    return sync if ctl.axis.mode == "cam" and isinstance(sync, CamMotion) else None


@command("SETCURVE")
def setcurve(ctl, vm, args):
    """CR 3913-3947: select and pre-calculate; outside SYNCC CMASTERCPOS is recomputed from MAPOS, inside it the
    new curve takes over at the next curve restart."""
    array = args[0]
    p = ctl.params
    cam = CamState(decode_curve_array(array.name, array.data), ctl.master, ctl.program_data, p["SYNCFACTS"],
                   p["SYNCFACTM"])
    ctl.program_data.cam = cam
    motion = _cam_motion(ctl)
    if motion is not None:
        cam.data = motion.cam.data
        motion.pending_cam = cam


@command("CURVEPOS")
def curvepos(ctl, vm, args):
    cam = active_cam(ctl)
    return 0 if cam is None else round(cam.curvepos_uu())  # defined only after SETCURVE (CR 685)


@command("POSA CURVEPOS")
def posa_curvepos(ctl, vm, args):
    return position_to(ctl, vm, ctl.qc(round(_cam_state(ctl, "POSA CURVEPOS").curvepos_uu())), "POSA CURVEPOS")


@command("DEFMCPOS")
def defmcpos(ctl, vm, args):
    """CR 827-843: the current master position is curve master position p; in SYNCC at the next curve restart."""
    motion = _cam_motion(ctl)
    if motion is not None:
        motion.pending_mcpos = args[0]
        return
    data = ctl.program_data
    data.mc_ref = (args[0], ctl.master.mapos + data.sync_shift)
    data.mc_defined = True
    if data.cam is not None:
        data.cam.mu_shift = 0.0  # p is the curve master position now, without earlier marker corrections


def _syncc(ctl, vm, args, side: str | None = None):
    """SYNCC n / SYNCCMM n / SYNCCMS n: CAM mode for n curve cycles, 0 = until stopped (DG 7261-7263); SYNCCMM and
    SYNCCMS correct with master / slave markers, SYNCMSTART 2000 starts the count at a master marker
    (kernel/cam_markers.py)."""
    motion_allowed(ctl, "SYNCC")
    motion = _cam_motion(ctl)
    if motion is not None:  # already in CAM mode: a new cycle count from now, and the marker correction it names
        motion.cycles, motion.cycles_done, motion._final = max(0, args[0]), 0, False
        if side != (motion.markers.side if motion.markers is not None else None):  # decision K45
            motion.markers = CamMarkers(ctl, motion, side, 0) if side is not None else None
        return
    cam = _cam_state(ctl, "SYNCC")
    data = ctl.program_data
    origin, data.sync_origin = data.sync_origin, None
    axis = ctl.axis
    motion = CamMotion(cam, args[0], motion_limits(ctl), ctl.params["SYNCACCURACY"], axis.cpos, ctl.temp_origin,
                       axis.scaling.posfact_z / axis.scaling.posfact_n, origin)
    start_mode = ctl.params["SYNCMSTART"]
    if side is not None or start_mode == 2000:
        motion.markers = CamMarkers(ctl, motion, side, start_mode)
    axis.synchronise(motion, "cam")


COMMANDS["SYNCC"] = _syncc


@command("SYNCCMM")
def synccmm(ctl, vm, args):
    """DG 1493-1566: CAM mode with master marker correction (the curve master position is corrected)."""
    return _syncc(ctl, vm, args, "master")


@command("SYNCCMS")
def synccms(ctl, vm, args):
    """DG 1608-1746: CAM mode with slave marker correction (the slave position is corrected)."""
    return _syncc(ctl, vm, args, "slave")


@command("SYNCCSTART")
def synccstart(ctl, vm, args):
    """DG 4026-4054: engage with start/stop pair pnum (pair 0 / no pairs: at once); outside CAM mode it starts
    SYNCC 0 first."""
    if _cam_motion(ctl) is None:
        _syncc(ctl, vm, [0])
    _cam_motion(ctl).start(args[0])


@command("SYNCCSTOP")
def synccstop(ctl, vm, args):
    """DG 3754-3760, 4026-4054: disengage with pair pnum and stop at slavepos (UU)."""
    motion = _cam_motion(ctl)
    if motion is not None:
        motion.stop(args[0], args[1])
