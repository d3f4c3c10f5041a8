"""Regression tests for the review of the controller (each names the manual line it protects)."""

import subprocess
import sys

import pytest

from motiontool.comms.protocol import LinkError
from motiontool.controller.embedded import EmbeddedLink
from motiontool.kernel.plant import PlantConfig

from .helpers import run_source, start

HANDLER = "\nSUBMAINPROG\nSUBPROG eh\nERRCLR\nRETURN\nENDPROG\n"


@pytest.mark.parametrize("line", ["y = x + IN 99", "y = 7 + 3 * a[10]"])
def test_error_inside_an_expression_keeps_the_program_running(line):
    """CR 2634-2678: after the error handler the program goes on with the next command."""
    run = run_source(f"DIM a[5]\nON ERROR GOSUB eh\nx = 5\n{line}\nPRINT \"after\"{HANDLER}", 500)
    assert run.prints == ["after"] and run.state == "ended"


def test_unknown_stream_signal_is_refused_at_the_request():
    link = EmbeddedLink()
    with pytest.raises(LinkError, match="unknown signal 'NOSUCH'"):
        link.call("stream", signals=["APOS", "NOSUCH"], interval_ms=1)
    link.advance(10)


def test_bad_request_values_are_refused_not_raised():
    link = EmbeddedLink()
    for op, args in (("read_variables", {"names": [5]}), ("write_parameter", {"key": "KPROP", "value": 1e400}),
                     ("read_array", {"index": -1})):
        with pytest.raises(LinkError):
            link.call(op, **args)


def test_continue_input_with_a_pending_error_is_an_error_not_a_crash():
    src = "VEL 50\nACC 50\nNOWAIT ON\nPOSA 100000\nDELAY 5000\n"
    run = run_source(src, 3000, settings={"I_FUNCTION_4": 9, "I_FUNCTION_5": 11},
                     inputs=[(4, 1, 200), (5, 1, 600)], plant=PlantConfig())
    assert run.state in ("break", "running", "error")


def test_home_ends_in_idle_so_waitax_and_axend_work():
    """CR 311-345: after HOME the axis is idle: AXEND bit 0 set, WAITAX returns."""
    run = run_source("HOME\nWAITAX\nPRINT AXEND & 1\n", 20000, settings={"I_FUNCTION_1": 1})
    assert run.prints == ["1"]


def test_hardware_limit_can_be_cleared_and_left():
    """DG 11618-11628: after ERRCLR the axis may stand on the switch and drive away from it."""
    src = "ON ERROR GOSUB eh\nVEL 50\nACC 100\nDEC 100\nPOSA 100000\nDELAY 200\nPOSA 0\nPRINT APOS < 1000" + HANDLER
    run = run_source(src, 10000, settings={"I_FUNCTION_2": 5}, plant=PlantConfig(pos_limit_switch_qc=30000))
    assert [e.number for e in run.errors] == [125]
    assert run.prints == ["1"]


def test_position_error_is_raised_once_and_switches_control_off():
    """DG 8752-8786: exceeding POSERR switches the position control off and raises 108 (once)."""
    run = run_source("VEL 100\nACC 100\nPOSA 100000\n", 3000, settings={"ERRCOND": 2},
                     plant=PlantConfig(blocked=True))
    assert [e.number for e in run.errors] == [108]
    assert not run.controller.axis.control_on


def test_set_values_revert_after_break_and_link_writes_stay():
    """CR 3896-3899: SET holds while the program runs; a value written from the IDE is the controller's."""
    run = run_source("SET KPROP 99\nmain:\nDELAY 10\nGOTO main\n", 200)
    run.link.write_parameter("KDER", 5)
    run.link.break_program()
    assert run.link.read_parameter("KPROP") == 30
    assert run.link.read_parameter("KDER") == 5


def test_next_program_does_not_inherit_cvel():
    """CR 624-648: CSTART without CVEL in a new program runs at velocity 0."""
    link = EmbeddedLink()
    run_source("CVEL 20\nCSTART\nDELAY 100\nCSTOP\nDELAY 500\n", 2000, link=link)
    second = run_source("CSTART\nDELAY 500\nPRINT AVEL\n", 2000, link=link)
    assert second.prints == ["0"]


def test_continue_does_not_resume_a_motion_that_was_replaced():
    """CR 564-578: CONTINUE resumes the motion MOTOR STOP interrupted — not after a newer move."""
    src = "VEL 50\nACC 100\nDEC 100\nNOWAIT ON\nPOSA 100000\nDELAY 500\nNOWAIT OFF\nMOTOR STOP\nPOSA 500\n" \
          "CONTINUE\nDELAY 500\nPRINT CPOS\n"
    run = run_source(src, 10000)
    assert run.prints == ["500"]


def test_fired_on_time_does_not_count_toward_the_limit():
    """DG 11764-11770: at most 12 ON TIME/ON PERIOD at once; spent one-shots free their place."""
    ons = "\n".join(f"ON TIME {5 + i} GOSUB t" for i in range(12))
    run = run_source(f"{ons}\nDELAY 100\nON TIME 5 GOSUB t\nDELAY 50\nPRINT \"ok\"\n"
                     "SUBMAINPROG\nSUBPROG t\nRETURN\nENDPROG\n", 1000)
    assert run.prints == ["ok"] and not run.errors


def test_cli_set_with_a_bad_number(tmp_path):
    program = tmp_path / "p.m"
    program.write_text("PRINT 1\n")
    proc = subprocess.run([sys.executable, "-m", "motiontool", "run", str(program), "--set", "KPROP=abc"],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 1 and "--set KPROP=abc: give a whole number" in proc.stderr


def test_endswmod_chooses_coasting_or_a_controlled_stop_at_a_limit_switch():
    """DG 10121-10134: 33-40 ENDSWMOD "defines the behavior when a positive or negative hardware end limit is
    activated": [0] Call error handler, [1] Controlled stop; DG 11624: "the controller (depending on the par. 33-40 …)
    is automatically switched off". Error 125 is raised either way and the handler is called; with 0 the ERRCOND
    reaction (default coast: control off), with 1 the axis brakes with the stop ramp and stays in position control.
    Before, no code read ENDSWMOD (K13)."""
    src = ("ON ERROR GOSUB eh\nVEL 50\nACC 100\nDEC 100\nPOSA 100000\n"
           "SUBMAINPROG\nSUBPROG eh\nPRINT AXEND & 64, \" \", AVEL\nERRCLR\nRETURN\nENDPROG\n")
    for endswmod, control in ((0, "64"), (1, "0")):
        run = run_source(src, 5000, settings={"I_FUNCTION_2": 5, "ENDSWMOD": endswmod},
                         plant=PlantConfig(pos_limit_switch_qc=30000))
        assert [e.number for e in run.errors] == [125]
        assert run.prints[0].split()[0] == control, endswmod     # AXEND bit 6: axis controller off


def test_a_motion_command_after_motor_off_says_why_the_program_does_not_go_on(tmp_path):
    """K11 (CR 624-648: "CSTART does not imply MOTOR ON"): after MOTOR OFF a POSA waits for the position control —
    issue 17 item 8: "whatever the drive does, the user needs to see why the program does not go on". The controller
    sends a message (the Communication window; `motiontool run` prints it on stderr)."""
    run = start("MOTOR OFF\nPOSA 1000\nPRINT \"never\"\n")
    messages = []
    run.link.subscribe(lambda e: messages.append((e.text, e.line)) if e.kind == "message" else None)
    run.advance(500)
    assert run.prints == [] and run.state == "running"
    assert messages == [("POSA waits: the position control is off (MOTOR OFF); MOTOR ON, ERRCLR or CONTINUE switches "
                         "it on", 2)]
    program = tmp_path / "off.m"
    program.write_text("MOTOR OFF\nCVEL 10\nCSTART\n")
    proc = subprocess.run([sys.executable, "-m", "motiontool", "run", str(program), "--seconds", "0.2"],
                          capture_output=True, text=True, timeout=120)
    assert "CSTART waits: the position control is off (MOTOR OFF)" in proc.stderr
