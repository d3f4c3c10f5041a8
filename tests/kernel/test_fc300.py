"""GETVLT/GETVLTSUB/SETVLT/SETVLTSUB, VLTALARMSTAT/VLTCONTROL/VLTERRCLR and ERRCLR's bit 7 on the simulated FC 300
(issue 25; kernel/fc300.py, docs/fc300.md, K124-K126): they ended with error 110."""

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms.protocol import LinkError
from motiontool.kernel.fc300 import trip

from .helpers import run_source, start


def test_getvlt_reads_4_13_and_getvltsub_reads_5_40_as_the_pages_print_them():
    # CR 1405: "PRINT GETVLT 413 /* reads par. 4-13 motor speed high limit */" (1500 RPM, assumed default);
    # CR 1422-1423: "PRINT GETVLTSUB 540 0 // reads index 01 of the parameter 5-40 "Function Relay""; DG 7680:
    # 5-40 gets the new default "[51] MCO Controlled"
    run = run_source("PRINT GETVLT 413\nPRINT GETVLTSUB 540 0\nPRINT GETVLTSUB 540 1\n", 1000)
    assert run.prints == ["1500", "51", "51"]
    assert run.errors == []


def test_setvlt_writes_3_03_with_conversion_index_minus_3_and_it_stays_after_the_program():
    # CR 4025-4027: "/* change par. 3-03 "maximum reference" high to 60 Hz */ /* -Conversion index = -3 (Multiplied
    # with 10³ during transmission) */ SETVLT 303 60000"; CR 4019-4020: "The parameter alterations are only stored
    # in RAM" (the drive keeps them until power down, not only while the program runs)
    run = run_source("SETVLT 303 60000\nPRINT GETVLT 303\n", 1000)
    assert run.prints == ["60000"]
    again = run_source("PRINT GETVLT 303\n", 1000, link=run.link)
    assert again.prints == ["60000"]


def test_dg_reading_and_writing_examples_run():
    # DG 7626: "var = GETVLT 1610"; DG 7629: "SETVLT 303 1500"
    run = run_source("var = GETVLT 1610\nSETVLT 303 1500\nPRINT var, \" \", GETVLT 303\n", 1000)
    assert run.prints == ["0 1500"]
    assert run.errors == []


def test_16_13_reads_the_frequency_in_tenths_of_a_hertz():
    # CR 1394-1396: "an LCP value of 50.0 Hz (par. 16-13 conversion in dex = –1) is equivalent to a return value of
    # 500". CVEL 50 is half of VELMAX 1500 RPM: 750 RPM on the (assumed) 4-pole motor is 25.0 Hz, 50.0 % of 3-03
    run = run_source("CVEL 50\nCSTART\nWAITT 3000\nPRINT GETVLT 1617, \" \", GETVLT 1613, \" \", GETVLT 1602\n", 5000)
    assert run.prints == ["750 250 500"]


def test_getvlt_and_setvlt_take_time_on_the_drive():
    # DG 6190-6193: "The GETVLT commands are typically 20 ms or faster … (It may take up to 100, or 500 ms, or even
    # more.)" — the simulation takes 20 ms and 100 ms (K124)
    run = run_source("t = TIME\nx = GETVLT 413\nt1 = TIME\nSETVLT 413 1400\nPRINT t1 - t, \" \", TIME - t1\n", 1000)
    assert run.prints == ["20 100"]


def test_setvltsub_example_as_printed_is_rejected_by_its_syntax_and_025_is_parameter_0_25():
    # CR 4047-4048: "SETVLT 025 1 100 // sets index 1 of the par. 0-25 "Quick menu" to 100 "configuration"": SETVLT
    # takes two values (CR 4011 "SETVLT par v"), so the printed line does not compile, and the error names SETVLTSUB
    # (CR 4031 "SETVLTSUB par indxno v"); after the VLT commands 025 is par. 0-25, not octal 21 (decision L1 revised,
    # issue 25 item 5): SETVLTSUB 025 1 100 does what the comment says
    printed = compile_source("SETVLT 025 1 100\n", "t.m")
    assert not printed.ok
    assert [d.message for d in printed.diagnostics if d.severity == "error"] == [
        "SETVLT takes a parameter number and a value; set an element of an indexed parameter with SETVLTSUB "
        "par indxno v (CR 4031)"]
    assert not any("octal" in d.message for d in printed.diagnostics)
    run = run_source("SETVLTSUB 025 1 100\nPRINT GETVLTSUB 025 1, \" \", GETVLTSUB 25 1, \" \", GETVLTSUB 025 0\n",
                     1000)
    assert run.prints == ["100 100 0"] and not run.errors   # index 1 of 0-25 set, index 0 untouched


def test_unknown_number_and_read_only_are_112_and_index_and_range_are_183():
    # DG 11522-11524: 112 "An attempt has been made to change a parameter (SET or SETVLT command), which does not
    # exist"; DG 7594: "Parameter groups 16-** and 34-** are read only" (112 as SET of a 34-**); 4-13 ranges
    # "par. 4-11 - 60000 RPM" (FC 301 programming manual); a parameter without index has only index 0 (K124)
    assert [e.number for e in run_source("x = GETVLT 4242\n", 1000).errors] == [112]
    assert [e.number for e in run_source("SETVLT 1613 500\n", 1000).errors] == [112]
    assert [e.number for e in run_source("SETVLT 413 60001\n", 1000).errors] == [183]
    assert [e.number for e in run_source("x = GETVLTSUB 540 2\n", 1000).errors] == [183]
    assert [e.number for e in run_source("x = GETVLTSUB 413 1\n", 1000).errors] == [183]
    assert run_source("PRINT GETVLTSUB 413 0\n", 1000).prints == ["1500"]


def test_vltcontrol_sets_the_control_word_in_motor_off_state_only():
    # DG 7052: "VLTCONTROL sets the VLT control word in MOTOR OFF state"; 16-00 Control Word, 16-03 Status Word
    # (FC profile: bit 11 "in operation" needs bit 3 "no coasting" and bit 6 "start" of the control word)
    run = run_source("PRINT GETVLT 1600, \" \", GETVLT 1603\nVLTCONTROL 0\nPRINT GETVLT 1600\nMOTOR OFF\n"
                     "PRINT GETVLT 1600, \" \", GETVLT 1603\nVLTCONTROL 0x047C\n"
                     "PRINT GETVLT 1600, \" \", GETVLT 1603\n", 2000)
    assert run.prints == ["1148 3847", "1148", "1140 1795", "1148 3847"]


def test_an_fc_alarm_is_error_113_and_errclr_resets_it_with_bit_7():
    # DG 11530: "FC 300 is not enabled but the PID controller MCO 305 is active … when: it has an alarm"; DG 7051
    # "VLTALARMSTAT returns if an alarm is active or not"; CR 1315: "ERRCLR also resets FC 300 alarms by means of
    # Bit 7 of the control word"
    run = start("ON ERROR GOSUB err\nWHILE 1 DO\nENDWHILE\nSUBMAINPROG\nSUBPROG err\n"
                "PRINT ERRNO, \" \", VLTALARMSTAT, \" \", GETVLT 1603\nERRCLR\nPRINT VLTALARMSTAT\nRETURN\nENDPROG\n")
    run.advance(50)
    trip(run.controller, 14)
    run.advance(100)
    assert run.prints == ["113 1 1800", "0"]


def test_vlterrclr_clears_only_the_drive_alarm():
    # DG 7053: "VLTERRCLR clears a VLT-alarm"; the MCO's own error stays pending (ERRCLR clears that)
    run = start("MOTOR OFF\nWAITT 100\nPRINT VLTALARMSTAT\nVLTERRCLR\nPRINT VLTALARMSTAT, \" \", ERRNO\n"
                "VLTCONTROL 0x0474\nVLTCONTROL 0x04FC\nPRINT GETVLT 1603\n")
    run.advance(50)
    trip(run.controller, 14)   # in MOTOR OFF state no error 113: the PID controller is not active
    run.advance(300)
    assert run.prints == ["1", "0 0", "3847"]
    assert run.errors == []


def test_a_link_reads_and_writes_the_drives_parameters_by_their_lcp_number():
    # the IDE/command line name a drive parameter as the LCP does ("4-13"); the MCO's own groups 19/32/33/34 stay
    # the controller's (K124)
    link = run_source("SETVLT 413 1400\n", 1000).link
    assert link.read_parameter("4-13") == 1400
    link.write_parameter("3-03", 60000)
    assert run_source("PRINT GETVLT 303\n", 1000, link=link).prints == ["60000"]
    assert link.read_parameter("32-60") == link.read_parameter("KPROP")
    with pytest.raises(LinkError, match="112"):
        link.write_parameter("16-13", 500)   # DG 7594: read only
