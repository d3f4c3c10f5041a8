"""Positioning, speed mode, limits, origins on the simulated axis (kernel-spec a-e, h)."""

from motiontool.kernel.plant import PlantConfig

from .helpers import run_source, start


def test_posa_with_default_parameters_takes_three_seconds():
    """CR 3445-3467 / DG 9224-9246: VEL 100, ACC 100, DEC 100 (VELRES 100 → full VELMAX 1500 rpm, 1024 PPR
    → 102.4 qc/ms, RAMPMIN 1 s); POSA 204800 from rest: 1 s up, 1 s at speed, 1 s down. With TESTWIN 0 the
    blocking POSA returns when CPOS reaches the target (DG 10295-10318)."""
    run = run_source("VEL 100\nACC 100\nDEC 100\nt = TIME\nPOSA 204800\nPRINT TIME - t\nPRINT CPOS\n", 5000)
    assert run.prints[1] == "204800"
    assert int(run.prints[0]) in (3000, 3001)


def test_limited_jerk_takes_longer_than_trapezoid():
    """DG 8990-9006: RAMPTYPE 2 ramps the acceleration with JERKMIN (32-86, 100 ms)."""
    program = "VEL 100\nACC 100\nDEC 100\nt = TIME\nPOSA 204800\nPRINT TIME - t\n"
    linear = int(run_source(program, 5000).prints[0])
    jerk = int(run_source(program, 5000, settings={"RAMPTYPE": 2}).prints[0])
    assert jerk > linear + 50


def test_posa_beyond_active_software_limit_raises_111_without_moving():
    """DG 10200-10225 / CR 3451: the target is checked before the move; 111, the axis does not move."""
    run = run_source("POSA 600000\nPRINT \"after\"\n", 2000, settings={"SWPOSLIMACT": 1})
    assert run.errors[0].number == 111
    assert run.controller.axis.apos == 0 and run.controller.axis.cpos == 0
    assert run.prints == []


def test_tracking_error_beyond_poserr_raises_108():
    """DG 8752-8786: when |CPOS - APOS| exceeds POSERR the control is switched off and error 108 raised."""
    run = run_source("VEL 100\nACC 100\nPOSA 100000\n", 3000, plant=PlantConfig(blocked=True))
    assert [e.number for e in run.errors] == [108]
    assert run.state == "error"
    assert not run.controller.axis.control_on  # ERRCOND 0: coast


def test_error_handler_clears_and_program_continues():
    """CR 2634-2678: ON ERROR GOSUB; ERRNO holds the number; ERRCLR clears it; the program goes on."""
    src = """
ON ERROR GOSUB handler
SET SWPOSLIMACT 1
POSA 600000
PRINT "continued ", ERRNO
SUBMAINPROG
SUBPROG handler
  PRINT "error ", ERRNO
  ERRCLR
RETURN
ENDPROG
"""
    run = run_source(src, 1000)
    assert run.prints == ["error 111", "continued 0"]
    assert run.state == "ended"


def test_setorigin_example():
    """CR 235-256: after SETORIGIN 2000, POSA 2000 goes to real 4000 and APOS reads 2000."""
    src = "VEL 100\nACC 100\nDEC 100\nSETORIGIN 2000\nPOSA 2000\nDELAY 300\nPRINT APOS\nRSTORIGIN\nPRINT APOS\n"
    run = run_source(src, 3000)
    assert run.prints == ["2000", "4000"]


def test_deforigin_makes_the_actual_position_zero():
    """CR 860-886: DEFORIGIN — the current actual position becomes 0."""
    run = run_source("VEL 50\nACC 50\nDEC 50\nPOSA 5000\nDELAY 500\nDEFORIGIN\nPRINT APOS\n", 5000)
    assert run.prints == ["0"]


def test_speed_mode_reaches_the_velocity():
    """CR 624-665: CVEL v then CSTART runs in speed mode; AVEL in UU/s; CSTOP brakes to standstill."""
    src = "ACC 100\nDEC 100\nCVEL 50\nCSTART\nDELAY 1500\nPRINT AVEL\nPRINT AXEND & 4\nCSTOP\nDELAY 1500\nPRINT AVEL\n"
    run = run_source(src, 5000)
    assert abs(int(run.prints[0]) - 51200) <= 60   # 50 % of 102.4 qc/ms = 51200 qc/s
    assert run.prints[1] == "4"
    assert run.prints[2] == "0"


def test_motor_stop_and_continue():
    """CR 2367-2396, 564-578: MOTOR STOP brakes with DEC; AXEND bits 0, 1, 3, 6 set; CONTINUE finishes."""
    src = """
VEL 100
ACC 100
DEC 100
NOWAIT ON
POSA 204800
DELAY 1500
NOWAIT OFF
MOTOR STOP
PRINT AXEND
CONTINUE
PRINT CPOS
"""
    run = run_source(src, 8000)
    assert int(run.prints[0]) & 0b1001011 == 0b1001011
    assert run.prints[1] == "204800"


def test_nowait_retargeting_and_axend():
    """CR 334-348, 2433-2470: with NOWAIT ON the program goes on; AXEND bit 1 while positioning."""
    src = "VEL 100\nACC 100\nDEC 100\nNOWAIT ON\nPOSA 100000\nPRINT AXEND & 2\nPOSA 50000\nWAITAX\nPRINT CPOS\n"
    run = run_source(src, 8000)
    assert run.prints == ["2", "50000"]


def test_user_units():
    """DG 286-304: 1 UU = POSFACT_Z / POSFACT_N qc; UU→qc truncates, qc→UU rounds."""
    run = run_source("VEL 20\nACC 100\nDEC 100\nPOSA 1000\nPRINT CPOS\n", 8000,
                     settings={"POSFACT_Z": 50375, "POSFACT_N": 1000})
    assert run.prints == ["1000"]
    assert round(run.controller.axis.cpos) == 50375


def test_homing_types():
    """DG 9278-9298: HOME_TYPE 0-3 find the switch; afterwards APOS is about 0 at the reference point."""
    for home_type in range(4):
        run = run_source("HOME\nPRINT \"homed\"\nDELAY 200\nPRINT APOS\n", 20000,
                         settings={"I_FUNCTION_1": 1, "HOME_TYPE": home_type})
        assert run.prints[0] == "homed", (home_type, run.errors)
        assert abs(int(run.prints[1])) <= 5
        raw_zero = run.controller.axis.origin
        period = 4096
        if home_type in (0, 2):
            assert raw_zero % period == 0   # at an index pulse
        assert raw_zero != 0


def test_home_with_zero_velocity_is_error_107():
    run = run_source("HOME\n", 1000, settings={"I_FUNCTION_1": 1, "HOME_VEL": 0})
    assert run.errors[0].number == 107


def test_motion_while_error_pending_is_105():
    """DG 11444-11450."""
    src = "ON ERROR GOSUB h\nPOSA 600000\nSUBMAINPROG\nSUBPROG h\nIF ERRNO == 111 THEN\nPOSA 10\nENDIF\n" \
          "PRINT ERRNO\nERRCLR\nRETURN\nENDPROG\n"
    run = run_source(src, 1000, settings={"SWPOSLIMACT": 1})
    assert [e.number for e in run.errors][:2] == [111, 105]


def test_program_end_restores_set_parameters():
    """CR 3896-3899: SET of 32/33-xx holds only while the program runs."""
    run = run_source("SET KPROP 77\nPRINT GET KPROP\n", 100)
    assert run.prints == ["77"]
    assert run.link.read_parameter("KPROP") == 30


def test_hardware_limit_switch_raises_125():
    """DG 11618-11628: an active limit switch input is error 125."""
    plant = PlantConfig(pos_limit_switch_qc=30000)
    run = run_source("VEL 50\nACC 100\nPOSA 100000\n", 5000, settings={"I_FUNCTION_2": 5}, plant=plant)
    assert run.errors[0].number == 125


def test_continuous_program_keeps_running():
    run = start("VEL 100\nACC 100\nDEC 100\nmain:\nPOSA 20000\nPOSA 0\nGOTO main\n")
    run.advance(3000)
    assert run.state == "running"


def test_break_and_error_clear_inputs():
    """DG 10336-10418: I_FUNCTION 9 = break program, 7 = error clear (rising edge)."""
    run = run_source("main:\nDELAY 10\nGOTO main\n", 1000, settings={"I_FUNCTION_4": 9}, inputs=[(4, 1, 300)])
    assert run.state == "break"
    assert 300 <= run.controller.time_ms <= 400


def test_software_limit_in_speed_mode_and_198_after_clearing():
    """DG 10213, 11498-11518, 11872-11876: in speed mode 111 comes when the actual position reaches the
    limit; after ERRCLR a move further in the forbidden direction is error 198, the other way is free."""
    src = """
ON ERROR GOSUB h
SET NEGLIMIT -30000
SET SWNEGLIMACT 1
ACC 100
DEC 100
CVEL -30
CSTART
DELAY 3000
CVEL -10
CSTART
DELAY 100
CVEL 10
CSTART
DELAY 500
PRINT "moving back ", AVEL > 0
SUBMAINPROG
SUBPROG h
  PRINT "error ", ERRNO, " at ", APOS < -30000
  ERRCLR
RETURN
ENDPROG
"""
    run = run_source(src, 6000)
    assert [e.number for e in run.errors] == [111, 198]
    assert run.prints == ["error 111 at 1", "error 198 at 1", "moving back 1"]


def test_interrupt_abandons_home():
    """CR 1498-1500: HOME interrupted by an interrupt is not resumed; the axis stops homing."""
    src = "ON INT 3 GOSUB s\nSET I_FUNCTION_1 1\nSET HOME_VEL 5\nHOME\nDELAY 2000\nPRINT AXEND & 1\n" \
          "SUBMAINPROG\nSUBPROG s\nRETURN\nENDPROG\n"
    run = run_source(src, 5000, inputs=[(3, 1, 1000)])
    assert run.prints == ["1"]
    assert run.controller.axis.homing is None and not run.controller.homed


def test_home_force_demands_home_first_and_again_after_an_axis_parameter_change():
    """DG 9199-9204 (33-00 HOME_FORCE 1): "after turning on … and after changing axis parameters a forced tracking of
    the home position must be made before a motion command is executed"; "For a motion command that is not executed
    with a terminated home run the error 106 is triggered". HOME itself is that home run (it was refused with 106,
    so no program could ever move). A global parameter (33-5x I/O configuration) does not count (K47)."""
    handler = "SUBMAINPROG\nSUBPROG h\nPRINT \"error \", ERRNO\nERRCLR\nRETURN\nENDPROG\n"
    settings = {"I_FUNCTION_1": 1, "HOME_FORCE": 1}
    run = run_source("ON ERROR GOSUB h\nPOSA 1000\nINDEX\nHOME\nPOSA 1000\nDELAY 300\nPRINT \"at \", APOS\n"
                     "SET I_FUNCTION_2 7\nPOSR 1000\nDELAY 300\nPRINT \"at \", APOS\n"
                     "SET KPROP 40\nPOSA 0\nHOME\nPOSA 0\nDELAY 300\nPRINT \"at \", APOS\n" + handler, 40000,
                     settings=settings)
    assert [e.number for e in run.errors] == [106, 106, 106]
    assert run.prints[:2] == ["error 106", "error 106"]
    assert abs(int(run.prints[2].split()[1]) - 1000) <= 2
    assert abs(int(run.prints[3].split()[1]) - 2000) <= 2      # a global parameter: no new home run needed
    assert run.prints[4] == "error 106"                        # KPROP (32-60) is an axis parameter
    assert abs(int(run.prints[5].split()[1])) <= 2
    assert run.state == "ended"


def test_save_axpars_and_glbpars_keep_their_own_groups():
    """CR 3654-3660: "SAVE GLBPARS saves the range of global parameters (group 30-5* and group 33-8*), and application
    parameters (group 19-**) … SAVE AXPARS saves all other axes parameters"; DG 10849 saves CANBAUD (33-91) with
    SAVE GLBPARS. Unsaved SET values go back at the program's end (CR 3896-3899). Decision K50."""
    program = "SET KPROP 77\nSET SYNCPOSOFFS 9\nSET ERRCOND 2\nSET CANBAUD 22\nSET I_FUNCTION_2 7\nSAVE {}\n"
    names = ("KPROP", "SYNCPOSOFFS", "ERRCOND", "CANBAUD", "I_FUNCTION_2")
    kept = {}
    for part in ("GLBPARS", "AXPARS"):
        run = run_source(program.format(part), 100)
        assert run.state == "ended" and not run.errors
        kept[part] = [run.controller.params[name] for name in names]
    assert kept["GLBPARS"] == [30, 0, 2, 22, 7]
    assert kept["AXPARS"] == [77, 9, 0, 20, 0]
