"""Interrupts (spec §6): kinds, priorities, re-triggering, DISABLE/ENABLE, NOWAIT inside handlers."""

from motiontool.kernel.canbus import CanFrame

from .can_helpers import bus, prints
from .helpers import run_source

HANDLERS = """
SUBMAINPROG
SUBPROG rise
  PRINT "rise ", TIME
RETURN
SUBPROG fall
  PRINT "fall ", TIME
RETURN
SUBPROG tick
  n = n + 1
RETURN
SUBPROG once
  PRINT "once ", TIME
RETURN
SUBPROG pos
  PRINT "pos ", APOS >= 10000
RETURN
ENDPROG
"""


def test_on_int_rising_and_falling_edges():
    """CR 2679-2750: ON INT n on a rising edge, ON INT -n on a falling edge; called within 2 ms."""
    run = run_source("ON INT 3 GOSUB rise\nON INT -3 GOSUB fall\nDELAY 500\n" + HANDLERS, 1000,
                     inputs=[(3, 1, 100), (3, 0, 300)])
    times = [int(p.split()[1]) for p in run.prints]
    assert [p.split()[0] for p in run.prints] == ["rise", "fall"]
    assert 100 <= times[0] <= 102 and 300 <= times[1] <= 302


def test_on_time_once_and_on_period_fixed_rate():
    """CR 3069-3091: ON TIME n fires once n ms later; DG 6325-6351: ON PERIOD n every n ms."""
    run = run_source("n = 0\nON TIME 250 GOSUB once\nON PERIOD 100 GOSUB tick\nDELAY 1050\nPRINT n\n" + HANDLERS,
                     2000)
    assert run.prints[0].startswith("once ")
    assert 250 <= int(run.prints[0].split()[1]) <= 252
    assert run.prints[1] == "10"


def test_position_interrupt_on_apos():
    """CR 2883-2984: ON +APOS p fires when the position passes p in positive direction."""
    run = run_source("VEL 50\nACC 100\nDEC 100\nON +APOS 10000 GOSUB pos\nPOSA 20000\nDELAY 100\n" + HANDLERS,
                     5000)
    assert run.prints == ["pos 1"]


def test_position_interrupt_setout_sets_the_output_in_the_background():
    """CR 2985-3016: ON +APOS p SETOUT n sets output n without calling a subprogram."""
    run = run_source("VEL 50\nACC 100\nDEC 100\nON +APOS 10000 SETOUT 2\nON -APOS 5000 SETOUT -2\n"
                     "POSA 20000\nPRINT IN 1, \" \", 1\nPOSA 0\n", 8000)
    outputs = run.controller.io.outputs
    assert outputs.get(2) == 0  # set on the way out, reset on the way back
    assert run.state == "ended"


def test_edge_interrupt_while_disabled_is_lost_but_timer_is_kept():
    """CR 1084-1133: edge interrupts arriving while selectively disabled are discarded; ON TIME is kept."""
    src = "ON INT 4 GOSUB rise\nON TIME 100 GOSUB once\nDISABLE INT\nDISABLE TIME\nDELAY 300\n" \
          "ENABLE INT\nENABLE TIME\nDELAY 100\n" + HANDLERS
    run = run_source(src, 1000, inputs=[(4, 1, 50)])
    assert [p.split()[0] for p in run.prints] == ["once"]
    assert 300 <= int(run.prints[0].split()[1]) <= 302


def test_disable_all_keeps_every_request():
    """CR 1116-1122: during DISABLE ALL requests are stored and run after ENABLE ALL."""
    src = "ON INT 4 GOSUB rise\nDISABLE ALL\nDELAY 300\nENABLE ALL\nDELAY 50\n" + HANDLERS
    run = run_source(src, 1000, inputs=[(4, 1, 50)])
    assert run.prints and run.prints[0].startswith("rise ")
    assert 300 <= int(run.prints[0].split()[1]) <= 302


def test_nowait_is_forced_on_inside_a_handler():
    """DG 6387-6391: POSA inside an interrupt handler does not wait; WAITAX does."""
    src = """
VEL 100
ACC 100
DEC 100
ON TIME 10 GOSUB move
DELAY 3000
SUBMAINPROG
SUBPROG move
  POSA 50000
  PRINT "after posa ", AXEND & 2
  WAITAX
  PRINT "after waitax ", CPOS
RETURN
ENDPROG
"""
    run = run_source(src, 4000)
    assert run.prints == ["after posa 2", "after waitax 50000"]


def test_delay_counts_the_time_spent_in_handlers():
    """C:980-989: interrupt time counts toward DELAY, so the total stays t."""
    src = "ON TIME 50 GOSUB slow\nt = TIME\nDELAY 200\nPRINT TIME - t\nSUBMAINPROG\nSUBPROG slow\nDELAY 100\n" \
          "RETURN\nENDPROG\n"
    run = run_source(src, 1000)
    assert 200 <= int(run.prints[0]) <= 202


def test_error_interrupt_has_priority_and_is_called_again_if_not_cleared():
    """CR 2634-2678: if the handler returns with the error still pending it is called again."""
    src = """
ON ERROR GOSUB handler
calls = 0
SET SWPOSLIMACT 1
POSA 600000
PRINT "calls ", calls
SUBMAINPROG
SUBPROG handler
  calls = calls + 1
  IF calls == 3 THEN
    ERRCLR
  ENDIF
RETURN
ENDPROG
"""
    run = run_source(src, 1000)
    assert run.prints == ["calls 3"]


def test_retrigger_during_own_handler_runs_once_afterwards():
    """Decision K3: DG 6369-6371 "If the same input or interrupt occurs again while the procedure is being executed
    this is noted again and subsequently executed. Thus, an interrupt can only be lost if it occurs twice during the
    execution of an interrupt procedure"; CR 1119-1120 "keeps upcoming interrupt requests still in mind … the
    upcoming stored interrupts will be executed yet" (against the page notes, e.g. CR 2715-2717 "ignored and thus
    lost"). Three edges during the first 300 ms handler: the second runs afterwards, the third is lost."""
    src = "n = 0\nON INT 5 GOSUB slow\nDELAY 1000\nPRINT n\nSUBMAINPROG\nSUBPROG slow\nn = n + 1\nDELAY 300\n" \
          "RETURN\nENDPROG\n"
    inputs = [(5, 1, 10), (5, 0, 20), (5, 1, 30), (5, 0, 40), (5, 1, 50), (5, 0, 60)]
    run = run_source(src, 2000, inputs=inputs)
    assert run.prints == ["2"]


MAPOS_HANDLERS = """
SUBMAINPROG
SUBPROG up
  PRINT "up ", MAPOS
RETURN
SUBPROG down
  PRINT "down ", MAPOS
RETURN
ENDPROG
"""


def test_on_mapos_calls_the_subprogram_when_the_master_passes_the_position():
    """CR 2930-2931: "ON MAPOS .. GOSUB Call up a subprogram when the master position xxx … has been passed in
    positive or negative direction"; DG 7158: "ON MAPOS = when the master position xxx [qc] is passed", CR 2934
    "after Master has reached 2200 qc" (K46: qc, not the "(MU)" of CR 2930).
    The virtual master (PULSVEL 10000 = 40 qc/ms) passes 10000 qc forward, then backward; the gear 3:1 shows the
    position is in qc, not MU."""
    run = run_source("ON +MAPOS 10000 GOSUB up\nON -MAPOS 10000 GOSUB down\nPULSVEL 10000\nDELAY 500\n"
                     "PULSVEL -10000\nDELAY 500\n" + MAPOS_HANDLERS, 3000, settings={"SYNCFACTM": 3, "SYNCFACTS": 1})
    assert [p.split()[0] for p in run.prints] == ["up", "down"]
    up, down = (int(p.split()[1]) for p in run.prints)
    assert 10000 <= up <= 10000 + 2 * 40 and 10000 - 2 * 40 <= down <= 10000  # within 2 ms (CR 2706-2711)


def test_on_mapos_setout_switches_the_output_in_the_background():
    """CR 2985-3007: "ON +/- type position SETOUT outno" — all position interrupts, "handled in the background and
    do not interrupt the application program"."""
    run = run_source("ON +MAPOS 2000 SETOUT 4\nON +MAPOS 6000 SETOUT -4\nPULSVEL 10000\nDELAY 25\nPRINT GET 3441\n"
                     "DELAY 100\nPRINT GET 3441\nDELAY 100\nPRINT GET 3441\n", 1000)
    assert run.prints == ["0", "8", "0"]  # 34-41 digital outputs: output 4 is bit 3


def test_on_combit_calls_the_subprogram_when_a_bit_of_the_received_process_data_is_set():
    """CR 2510-2515: "Call up a subprogram when Bit n of the communication buffer is set … ON COMBIT refers to the
    first 32 Bits of the process data memory"; CR 3334: "Using ON COMBIT, a function is called up, as soon as the bit
    n of the PDO changes"; CR 2522-2523: "the subprogram assigned to the lowest bit is worked through first". Node 2
    receives its RxPDO 1 (COB-ID 0x202); ON COMBIT -n, as ON INT -n, fires when the bit is cleared (decision K53)."""
    sim = bus({2: """ON COMBIT 5 GOSUB set5
ON COMBIT -5 GOSUB clear5
ON COMBIT 2 GOSUB set2
WAITI 12 ON
SUBMAINPROG
SUBPROG set5
  PRINT "set 5 at ", TIME
RETURN
SUBPROG clear5
  PRINT "clear 5 at ", TIME
RETURN
SUBPROG set2
  PRINT "set 2 at ", TIME
RETURN
ENDPROG
"""})
    sim.run_for(50)
    sim.can_bus.inject(CanFrame(0x202, bytes([0x10, 0, 0, 0, 0, 0, 0, 0])))   # bit 5 of byte 1
    sim.run_for(50)
    sim.can_bus.inject(CanFrame(0x203, bytes([0x12, 0, 0, 0, 0, 0, 0, 0])))   # another node's PDO: not ours
    sim.run_for(50)
    sim.can_bus.inject(CanFrame(0x202, bytes([0x12, 0, 0, 0, 0, 0, 0, 0])))   # bit 2 comes, bit 5 stays
    sim.run_for(50)
    sim.can_bus.inject(CanFrame(0x202, bytes([0x00, 0, 0, 0, 0, 0, 0, 0])))
    sim.run_for(50)
    sim.can_bus.inject(CanFrame(0x202, bytes([0x12, 0, 0, 0, 0, 0, 0, 0])))   # both at once: bit 2 first
    sim.run_for(50)
    events = [p.rsplit(" at ", 1) for p in prints(sim, 2)]
    assert [e[0] for e in events] == ["set 5", "set 2", "clear 5", "set 2", "set 5"]
    times = [int(e[1]) for e in events]
    for when, expected in zip(times, (50, 150, 200, 250, 250), strict=True):
        assert expected <= when <= expected + 3
