"""The Design Guide's marker applications on the simulator: "Printing of Cardboard Boxes with Marker Correction"
(SYNCCMM, DG 1493-1566), "Slave Synchronization with Marker" (SYNCCMS, DG 1608-1746) and "Packaging with Varying
Product Distance and Slip" (SYNCM, DG 1166-1340). The programs are the compiler tests' copies of the manual's,
tests/aposs/manual/D08_cam_marker_correction.m, D09_cam_slave_marker.m and D06_marker_sync.m (the same program
is not kept twice); the curves are the manual's (tests/camcurve/conftest.py), restored as a .zbc download would.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from motiontool.kernel.master import MasterConfig
from motiontool.kernel.plant import PlantConfig
from tests.camcurve.conftest import marker_curve, slavesync_curve
from tests.kernel.helpers import start
from tests.kernel.test_cam_examples import MARKER, QC_PER_MU, SLAVESYNC, SLAVESYNC_PRINTED, run_example, start_conveyor

D06 = Path(__file__).parents[1] / "aposs" / "manual" / "D06_marker_sync.m"


def _window(m: float, start: float, end: float, length: float, slack: float) -> bool:
    return (m - start) % length <= (end - start) % length + slack


# --- printing with marker correction (SYNCCMM) -------------------------------------------------------------------
BOX_DEVIATION = (0, 80, -60, 30, 90, -40, 10, 0)  # MU: the boxes do not lie at exactly 4000 MU from each other


def test_printing_with_marker_correction_prints_every_irregular_box_at_its_front_edge():
    """DG 1495: "If the boxes are not always transported at the exact same distance from each other, markers will be
    required that can recognize a box and correct the synchronization." Photoelectric beam 2375 before the processing
    point, window 200, master marker position 1000 (OCR "100", spec o.19), "Correction Start = 3000 Correction End =
    1000" (DG 1539-1541): "At the earliest, the correction may begin when the printing of a box has been completed …
    The correction must be finished completely when the next cardboard box reaches the processing point." Every box
    reaches the processing point when the curve master position is 1000; the curve master position is corrected only
    between 3000 and 1000, never while printing (1500 … 2500)."""
    first = 20000.0
    positions = tuple(first + (4000 * k + d) * QC_PER_MU for k, d in enumerate(BOX_DEVIATION))
    run = run_example(MARKER, marker_curve(), settings={"SYNCMPULSM": 2375, "SYNCMWINM": 200, "SYNCMTYPM": 2},
                      master=MasterConfig(marker_positions_qc=positions))
    ctl = run.controller
    start_conveyor(ctl, ramp_ms=200)
    at_processing = []     # curve master position (in the cycle) when a box's front edge reaches the stamp
    shifts = []            # (curve master position in the cycle, change of the correction in this ms)
    due = [p + 2375 * QC_PER_MU for p in positions]
    last_shift, end, status = 0.0, ctl.time_ms + 9000, 0
    while ctl.time_ms < end:
        counting = not ctl.axis.sync.markers.waiting
        run.advance(1)
        cam = ctl.axis.sync.cam
        m = cam.master_position() % 4000
        if not counting:  # SYNCMSTART 2000: standing until the first box, then counting from there
            last_shift = cam.mu_shift
        elif cam.mu_shift != last_shift:
            shifts.append((m, cam.mu_shift - last_shift))
            last_shift = cam.mu_shift
        while due and ctl.master.position >= due[0]:
            overshoot = (ctl.master.position - due.pop(0)) / QC_PER_MU  # the box passed within this ms
            at_processing.append((m - overshoot) % 4000)
            status = ctl.syncstat()
    assert not run.errors
    markers = ctl.axis.sync.markers
    assert len(at_processing) == 8 and markers.master.count == 8
    assert all(abs(m - 1000) <= 0.1 for m in at_processing)                  # every box printed at its edge
    expected = [b - a for a, b in zip(BOX_DEVIATION, BOX_DEVIATION[1:], strict=False)]
    assert markers.errors[:7] == pytest.approx(expected, abs=0.1)            # the spacing error of each box
    assert shifts and all(_window(m, 3000, 1000, 4000, 4.1) for m, _ in shifts)  # + the ms that leaves it (4 MU)
    assert not any(1500 <= m <= 2500 for m, _ in shifts)                      # never while printing
    assert status & (8 | 32) == 8                                             # MMHIT, no marker missing …
    assert ctl.syncstat() & 32                                                # … until the boxes run out


# --- slave synchronisation with marker (SYNCCMS) ----------------------------------------------------------------
# DG 1624-1660: master = stamp roller (25:9, 1 MU = 25/9 qc, 3600 MU = one turn = 10000 qc); slave = conveyor
# (2048:55, 1 UU = 2048/55 qc); "Cycles/min Master = 20" → 10000 qc in 3 s.
ROLLER = {"SYNCFACTM": 25, "SYNCFACTS": 9, "MENCODER": 500, "POSFACT_Z": 2048, "POSFACT_N": 55, "ENCODER": 4096,
          "FFVEL": 1000, "DFLTVEL": 100, "DFLTACC": 100, "I_FUNCTION_1": 1, "HOME_VEL": 50, "HOME_RAMP": 50,
          "SYNCMPULSS": 3900, "SYNCMWINS": 200, "SYNCMTYPS": 2, "SYNCMTYPM": 2}
UU = 2048 / 55
SLIP = (0, 120, 40, 100, -50, 40, -60, 0, 30)  # UU: the boxes slip on the belt


def test_slave_synchronisation_with_marker_as_printed_ends_and_does_not_engage():
    """D9 as printed ends right after SYNCCSTART 1; DG 4054: "If the program is closed without the explicit command
    SYNCCSTOP pnum slavepos, then the second point pair will always be used for disengaging" — the curve has no
    second pair, so the conveyor stops where it stands and does not follow the roller (K49). The corrected copy adds
    D7's empty main loop (DG 1488)."""
    boxes = (30000.0,)
    run = run_example(SLAVESYNC_PRINTED, slavesync_curve(), settings=ROLLER,
                      master=MasterConfig(marker_period_qc=10000, marker_offset_qc=3000),
                      plant=PlantConfig(home_switch_qc=2000, slave_marker_positions_qc=boxes))
    ctl = run.controller
    assert run.state == "ended" and not run.errors
    start_conveyor(ctl, ramp_ms=500, speed=10000 / 3000)
    run.advance(300)
    stop = ctl.axis.cpos
    run.advance(5000)
    assert ctl.axis.mode == "idle" and ctl.axis.cpos == stop and ctl.master.mapos > 10000


@pytest.mark.slow
def test_slave_synchronisation_with_marker_brings_every_box_to_the_stamp_at_slave_position_1000():
    """DG 1612: "here the slave position is being corrected instead of the curve"; DG 1700-1708: photoelectric beam
    3900 before the processing point, window 200, "Slave-Marker-Position = 1000" (the beginning of the box);
    "Correction Start = 2800 Correction End = 750"; DG 1727: "In order to determine the master position, a switch on
    the master is required that indicates the zero position" (input 5, SYNCMSTART 2000 counts from it). After the
    start correction each box is at the stamp when the conveyor is at curve slave position 1000; the slave is
    corrected only while the curve's slave position is between 2800 and 750 ("the slave positions at the end and
    beginning of a box are quite suitable", DG 1712), the curve master position is not corrected."""
    first = 30000.0
    boxes = tuple(first + (4000 * k + d) * UU for k, d in enumerate(SLIP))
    run = run_example(SLAVESYNC, slavesync_curve(), settings=ROLLER,
                      master=MasterConfig(marker_period_qc=10000, marker_offset_qc=3000),
                      plant=PlantConfig(home_switch_qc=2000, slave_marker_positions_qc=boxes))
    ctl = run.controller
    assert ctl.axis.mode == "cam"
    assert abs(ctl.uu(ctl.markers.ipos_qc()) - (first - ctl.axis.origin) / UU) <= 1   # the first box was found
    start_conveyor(ctl, ramp_ms=500, speed=10000 / 3000)                         # the roller: 20 turns/min
    motion = ctl.axis.sync
    base, anchor = motion.base, None
    moves = []
    stamped = []   # curve slave position (in the cycle) when a box's beginning reaches the stamp
    due = [b + 3900 * UU for b in boxes]
    while ctl.time_ms < 27500:  # the 9th box passes the sensor at ~25.3 s
        run.advance(1)
        m = motion.cam.master_position()
        if anchor is None and not motion.markers.waiting:
            anchor = motion.cam.mu_shift
        if motion.base != base:
            moves.append((motion.cam.curve.periodic(m) % 4000, motion.state))
            base = motion.base
        while due and ctl.axis.plant.position >= due[0]:
            stamped.append(((due.pop(0) - ctl.axis.origin - motion.base) / motion.k) % 4000)
    assert not run.errors
    markers = motion.markers
    assert motion.state == "curve" and len(markers.errors) >= 6
    assert all(abs(e - d) <= 1 for e, d in zip(markers.errors[1:], [b - a for a, b in zip(SLIP[1:], SLIP[2:],
                                                                                           strict=False)],
                                                   strict=False))
    assert len(stamped) >= 7 and all(abs(y - 1000) <= 1 for y in stamped[2:])  # at the stamp with its beginning
    assert moves and all(_window(y, 2800, 750, 4000, 3.0) for y, state in moves if state == "curve")
    assert motion.cam.mu_shift == anchor                                         # the curve is not corrected
    assert ctl.syncstat() & (16 | 64) == 16                                      # SMHIT, none missing


# --- packaging with varying product distance and slip (SYNCM) ----------------------------------------------------
BOXES = tuple(3000 + 12000 * k + d for k, d in enumerate((0, -250, 200, 100, -300, 0, 250, -100)))
TEDDIES = tuple(7000 + 12000 * k + d for k, d in enumerate((0, 300, -200, 250, -100, 150, 0, -300)))


def test_packaging_with_varying_product_distance_and_slip_puts_each_teddy_into_its_box():
    """DG 1166-1170: "Both boxes and teddies are moved by friction and can thus move on the conveyor belt. It means
    that there is no fixed relationship between the encoders and the position of box and teddy bear and the distance
    can vary. It is therefore necessary to use external marker detection on both boxes (master) and teddies (slave)
    in order to synchronize the teddy bear position to the box position." The D06 sample with input 1 (SYNCM): after
    each pair of markers the next teddy is as far past its sensor as its box is past the box sensor (gear 1:1,
    SYNCPOSOFFS 0), one teddy per box."""
    source = D06.read_text().replace("ELSE\nMOTOR STOP", "ELSEIF (IN 1 == 0) THEN\nMOTOR STOP")  # see test_markers
    run = start(source, settings={"FFVEL": 1000, "KPROP": 100, "SYNCMPULSM": 12000, "SYNCMPULSS": 12000},
                inputs=[(1, 1, 100)], master=MasterConfig(velocity=10.0, marker_positions_qc=BOXES),
                plant=PlantConfig(slave_marker_positions_qc=TEDDIES))
    ctl = run.controller
    pairs = []
    for i, box in enumerate(BOXES[1:-1], start=1):
        while ctl.master.position < box + 6000:  # half way to the next box: the correction is done
            run.advance(1)
        past_box = ctl.master.position - box
        offsets = [ctl.axis.plant.position - t - past_box for t in TEDDIES]
        j = min(range(len(TEDDIES)), key=lambda k: abs(offsets[k]))
        pairs.append((i, j, offsets[j]))
    assert not run.errors and ctl.axis.mode == "sync"
    teddy = [j for _, j, _ in pairs]
    assert teddy == list(range(teddy[0], teddy[0] + len(teddy)))             # one teddy per box, none skipped
    assert all(abs(offset) <= 30 for _, _, offset in pairs[1:])               # in its box (loop lag only)
