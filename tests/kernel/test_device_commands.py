"""INKEY (the LCP keys), ENCPOSOFFS/MENCPOSOFFS (a Hiperface encoder the simulation does not have) and
COMOPTGET/COMOPTSEND (the fieldbus option's words): issue 25, they ended with error 110."""

from motiontool.kernel.lcp import press_key

from .helpers import run_source, start


def test_inkey_minus_one_does_not_wait_and_returns_minus_one_without_a_key():
    # CR 1704-1707: "p < 0 no wait for key code … Return Value key code for the received character or –1 in case
    # no character available"; CR 1705: "p > 0 wait of max. p milliseconds"
    run = run_source("t = TIME\nPRINT INKEY(-1), \" \", TIME - t\nt = TIME\nk = INKEY 50\nPRINT k, \" \", TIME - t\n",
                     1000)
    assert run.prints == ["-1 0", "-1 50"]


def test_inkey_reads_one_pressed_key_per_command_and_on_keypressed_fires():
    # CR 1703: "p = 0 wait for key code"; CR 1731-1732: "One key signal is read in per successful INKEY command";
    # CR 1709: "[OK] and [Cancel] 48" (a combination sends the sum); CR 2764-2773 (C14) reads the key in the
    # ON KEYPRESSED handler with INKEY(-1)
    run = start("ON KEYPRESSED GOSUB k\nk1 = INKEY 0\nPRINT \"got \", k1\nWHILE 1 DO\nENDWHILE\n"
                "SUBMAINPROG\nSUBPROG k\nPRINT \"key\"\nRETURN\nENDPROG\n")
    run.advance(100)
    assert run.prints == []
    press_key(run.controller, 48)
    run.advance(10)
    assert run.prints == ["key", "got 48"]


def test_encposoffs_times_out_without_a_hiperface_encoder():
    # CR 1183: "TIMEOUT -1 No answer has been received within 300ms"; the simulated machine has no absolute encoder
    # on the RS485 line, so offset is not written (K123)
    run = run_source("ofs = 7\nt = TIME\nr = ENCPOSOFFS ofs\nPRINT r, \" \", ofs, \" \", TIME - t\n"
                     "r = MENCPOSOFFS ofs\nPRINT r\n", 3000)
    assert run.prints == ["-1 7 300", "-1"]
    assert run.errors == []


def test_comoptget_and_comoptsend_copy_16_bit_words_of_the_option_buffer():
    # CR 518-519: "COMOPTGET reads from the Communication option buffer the no words and writes them in the array
    # 'array', starting with the first element"; CR 548-549: "COMOPTSEND … the first 'no' values are sent from the
    # 'array'"; CR 3278-3281: PCD[] is the same data area, "written or read word by word (16-Bit)" (K122)
    run = run_source("DIM a[4]\nPCD[1] = 0x12345\nPCD[2] = 7\nCOMOPTGET 3 a\nPRINT a[1], \" \", a[2], \" \", a[3]\n"
                     "a[1] = -1\nCOMOPTSEND 2 a\nPRINT PCD[1], \" \", PCD[2]\n", 3000)
    assert run.prints == ["9029 7 0", "65535 7"]


def test_comoptget_into_an_array_smaller_than_the_count_is_error_171():
    # CR 516: "array = the name of an array which must be at least the size of no"; DG 11383: 171 "Array too small"
    run = run_source("DIM a[2]\nCOMOPTGET 3 a\n", 1000)
    assert [(e.number, e.line) for e in run.errors] == [(171, 2)]
