"""The Design Guide's positioning application programs (palletizer, touch probe, brake control) and the Command
Reference's NOWAIT/AXEND example on the simulated controller, driven through their inputs like the machine's
operator: positions reached, outputs set, errors handled."""

from __future__ import annotations

import pytest

from .helpers import run_manual, variables

# The palletizers' axis: the default plant's home switch (input 3, I_FUNCTION_3 1 in the programs) sits at 20000 qc,
# so HOME (HOME_TYPE 0: switch, back off slowly, index) takes about 13 s.
HOMED_MS = 14000


def _at(run, qc: float, tolerance: float = 5) -> bool:
    return abs(run.controller.axis.apos - qc) <= tolerance


def test_d01_palletizer_goes_to_the_pick_up_and_deliver_positions_and_handles_a_limit_error():
    """DG 564-616: after HOME, input 1 alone moves to the "Pick up Position" (19-00) and sets output 1, input 2 alone to
    the "Deliver Position" (19-01) and sets output 2; the error handler sets output 8 until input 8 clears the error.
    A deliver position beyond the active positive software limit is refused with error 111 (DG 10200-10211)."""
    settings = {"1900": 50000, "1901": 150000, "SWPOSLIMACT": 1, "POSLIMIT": 100000}
    inputs = [(1, 1, HOMED_MS), (1, 0, HOMED_MS + 3000), (2, 1, HOMED_MS + 3000), (2, 0, HOMED_MS + 4500),
              (8, 1, HOMED_MS + 5000)]
    run = run_manual("D01_palletizer_absolute.m", HOMED_MS + 2900, settings=settings, inputs=inputs)
    ctl = run.controller
    assert ctl.homed and _at(run, 50000) and ctl.io.outputs.get(1) == 1 and ctl.io.outputs.get(2, 0) == 0
    run.advance(1000)                                     # input 2: the deliver position is beyond POSLIMIT
    assert [e.number for e in run.errors] == [111] and ctl.io.outputs[8] == 1 and ctl.io.outputs[1] == 0
    assert _at(run, 50000)                                # refused before the move (DG 10211)
    run.advance(2000)                                     # input 2 released, then input 8 clears the error
    assert ctl.io.outputs[8] == 0 and ctl.error == 0 and run.state == "running"
    assert [e.number for e in run.errors] == [111] and _at(run, 50000)


def _relative(name: str, ms: int):
    # input 1 held for 3 s from HOMED_MS… (no HOME in these programs: the axis starts at 0)
    return run_manual(name, ms, settings={"1900": 20000}, inputs=[(1, 1, 1000), (1, 0, 4000), (1, 1, 6000)])


@pytest.mark.slow  # several seconds on an idle machine: make test runs it, make test-fast does not
def test_d02_palletizer_as_printed_repeats_the_box_height_while_input_1_is_held():
    """DG 637-681: "IF (IN 1 == 1) AND (flag == 0) THEN … POSR (GET 1900) … flag = 1 ELSE MOTOR STOP … flag = 0":
    while input 1 stays high the ELSE branch resets the flag on the next pass, so the palletizer goes on moving by the
    box height (20000) — as printed; the corrected copy moves once per press."""
    run = _relative("D02_palletizer_relative.m", 4000)
    assert run.controller.axis.apos > 2 * 20000 + 10000           # several box heights in 3 s
    fixed = _relative("D02_palletizer_relative_corrected.m", 5900)
    assert _at(fixed, 20000) and fixed.controller.io.outputs[1] == 1
    fixed.advance(3000)                                            # the second press: one more box height
    assert _at(fixed, 40000) and not fixed.errors


def test_d03_touch_probe_travels_the_probe_distance_from_where_the_probe_fired():
    """DG 683-790: input 1 starts the axis at CVEL 80; the touch probe (input 2, ON INT 2) makes the handler travel the
    "Touch probe distance" (19-00) relative to where the probe fired, then sets output 1 ("In position"). As printed
    the ELSE branch stops the axis on the next pass (CSTART and MOTOR STOP alternate), so the corrected copy is the
    one that runs as described."""
    inputs = [(1, 1, 100), (2, 1, 1500), (2, 0, 1600)]
    printed = run_manual("D03_touch_probe.m", 1400, settings={"1900": 30000}, inputs=inputs)
    assert abs(printed.controller.axis.apos) < 5000                  # hardly moves
    run = run_manual("D03_touch_probe_corrected.m", 1500, settings={"1900": 30000}, inputs=inputs)
    ctl = run.controller
    run.advance(1)
    probe = ctl.axis.apos
    assert probe > 50000 and ctl.io.outputs.get(1, 0) == 0
    run.advance(3000)
    assert ctl.io.outputs[1] == 1 and ctl.axis.mode == "idle"
    assert abs(ctl.axis.apos - (probe + 30000)) < 300             # from the handler's position (DG 518-522)
    assert variables(run, "tp_active") == [1] and not run.errors


def test_d11_brake_control_as_printed_addresses_output_11_and_the_controller_reports_171():
    """DG 1783-1856: "OUT 11 0 // Close mechanical brake" — there is no output 11 (outputs 1-8, 27, relays 21/22,
    CR 3097-3106); the controller reports error 171 (CR 3127-3128) at the first OUT 11 and the error handler sets
    output 8."""
    run = run_manual("D11_brake_control.m", 500)
    assert run.errors and {e.number for e in run.errors} == {171}
    assert run.controller.io.outputs.get(8) == 1 and run.state == "running"


def test_d11_brake_control_opens_the_brake_moves_the_box_height_and_closes_it_again():
    """DG 1783-1856 (corrected copy, relay 1 = output 21): the brake is closed at power up (MOTOR OFF after the close
    delay); input 1: MOTOR ON, open delay, brake open, POSR box height, output 1; input 1 low: MOTOR STOP, brake
    closed, MOTOR OFF after the close delay."""
    settings = {"1900": 30000, "1901": 200, "1902": 300}
    run = run_manual("D11_brake_control_corrected.m", 800, settings=settings, inputs=[(1, 1, 1000), (1, 0, 5000)])
    ctl = run.controller
    assert ctl.io.outputs[21] == 0 and not ctl.axis.control_on       # closed and coasting after power up
    run.advance(400)
    assert ctl.axis.control_on and ctl.io.outputs[21] == 0           # motor on, waiting the open delay
    run.advance(200)
    assert ctl.io.outputs[21] == 1                                    # brake open after 300 ms
    run.advance(3500)
    assert _at(run, 30000, 50) and ctl.io.outputs[1] == 1
    run.advance(1000)                                                 # input 1 low at 5000 ms
    assert ctl.io.outputs[21] == 0 and not ctl.axis.control_on and not run.errors


def test_c03_nowait_axend_loop_speeds_up_the_running_move_on_input_1():
    """CR 334-348 (corrected copy, `IF IN 1` / `WAITI 1 OFF`): with NOWAIT ON the program polls AXEND bit 1
    (positioning active); input 1 raises VEL to 100 % and repeats POSA 100000, which changes the speed of the running
    move (CR 334-342: "The velocity … can be changed"); afterwards AXEND bit 6 (controller off) is clear, so output 1
    is reset. Without input 1 the move runs at DFLTVEL (50 %, CR 3456-3458)."""
    peaks = []
    for inputs in ([], [(1, 1, 500), (1, 0, 600)]):
        run = run_manual("F_C03_nowait_axend_corrected.m", 0, inputs=inputs)
        ctl = run.controller
        peak = 0.0
        while run.state == "running" and ctl.time_ms < 10000:
            run.advance(10)
            peak = max(peak, ctl.axis.profile.velocity)
        assert run.state == "ended" and ctl.axis.cpos == 100000 and ctl.io.outputs[1] == 0 and not run.errors
        peaks.append(peak / ctl.axis.scaling.velocity(100))
    assert peaks[0] == pytest.approx(0.5) and peaks[1] > 0.65   # faster than VEL 50 (DFLTACC limits the 100 %)


@pytest.mark.parametrize("name", ["D02_palletizer_relative.m", "D03_touch_probe_corrected.m", "D11_brake_control.m"])
def test_the_error_handlers_clear_with_input_8(name):
    """DG 600-616 and the same handlers in D2, D3, D11: an error sets output 8 until input 8 clears it (ERRCLR). The
    error here: the tracking error of a blocked motor (error 108, DG 11464-11477) for D2/D3, the OUT 11 of D11 as
    printed."""
    from motiontool.kernel.plant import PlantConfig

    run = run_manual(name, 3000, settings={"1900": 30000}, inputs=[(1, 1, 100), (8, 1, 2500)],
                     plant=PlantConfig(blocked=True))
    ctl = run.controller
    assert run.errors and ctl.io.outputs.get(8) == 0 and run.state == "running"
