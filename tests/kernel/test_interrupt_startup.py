"""An interrupt starts from the state at its definition (issue 25): a bit, input or process-data bit that changes in
the tick right after the ON statement fires it. Sampling the start state one tick late missed exactly that change:
`ON STATBIT 17 GOSUB mv` directly followed by `POSA 5000` never called mv."""

from .helpers import run_source

HANDLER = "SUBMAINPROG\nSUBPROG h\nPRINT \"h \", TIME\nRETURN\nENDPROG\n"


def test_on_statbit_sees_moving_rise_in_the_tick_after_the_posa_that_follows_it():
    # CR 3022-3027: "Call up a subprogram when bit n of the FC 300 status is set … Bit 17 1 = MOVING"
    run = run_source("ON STATBIT 17 GOSUB h\nPRINT \"def \", TIME\nPOSA 5000\n" + HANDLER, 5000)
    assert run.prints == ["def 1", "h 2"]   # defined and POSA started in tick 1, MOVING set in tick 2


def test_on_int_sees_an_input_that_rises_in_the_tick_after_the_definition():
    # CR 2679-2750 (ON INT n): the subprogram is called on the rising edge of input n
    run = run_source("PRINT \"def \", TIME\nON INT 3 GOSUB h\nDELAY 50\n" + HANDLER, 200, inputs=[(3, 1, 2)])
    assert run.prints == ["def 1", "h 2"]


def test_on_int_does_not_fire_for_an_input_already_on_at_the_definition():
    # CR 2679-2750: an edge, not a level: an input that is on when ON INT is given has no rising edge
    run = run_source("DELAY 5\nON INT 3 GOSUB h\nDELAY 50\n" + HANDLER, 200, inputs=[(3, 1, 2)])
    assert run.prints == []


def test_on_combit_sees_a_bit_set_right_after_the_definition():
    # CR 2510-2511: "Call up a subprogram when Bit n of the communication buffer is set" (the PDO array, K53)
    run = run_source("PRINT \"def \", TIME\nON COMBIT 1 GOSUB h\nPDO[1001].1 = 1\nDELAY 50\n" + HANDLER, 200)
    assert run.prints == ["def 1", "h 2"]
