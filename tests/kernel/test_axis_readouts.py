"""_GETVEL, JERKFINVEL, JERKSTOPDIST and WAITNDX (issue 25: they ended with error 110)."""

from motiontool.kernel.master import MasterConfig

from .helpers import run_source

SAMPLE = "i = 0\nWHILE i < 5 DO\nPRINT AVEL, \" \", MAVEL\nDELAY 7\ni = i + 1\nENDWHILE\n"


def test_getvel_sets_the_measuring_time_of_avel_and_mavel():
    # CR 295-301: "The standard setting is 20 ms, but this can be changed by the user with the _GETVEL command …
    # var = _GETVEL 100 sets the duration of the measurement to 100 ms, so that you have a considerably better
    # resolution of the speed with AVEL and MAVEL". CVEL 7 = 7175 qc/s: counts over 20 ms resolve 50 qc/s, over
    # 100 ms 10 qc/s. The value returned is the measuring time replaced (K121).
    run = run_source("CVEL 7\nCSTART\nDELAY 1000\n" + SAMPLE + "v = _GETVEL 100\nDELAY 200\n" + SAMPLE + "PRINT v\n",
                     5000, master=MasterConfig(velocity=7.175))
    values = [[int(x) for x in p.split()] for p in run.prints[:10]]
    assert run.prints[10] == "20"
    assert all(abs(v - 7175) <= 50 for row in values for v in row)
    assert all(v % 50 == 0 for row in values[:5] for v in row)
    assert all(v % 10 == 0 for row in values[5:] for v in row)
    assert any(v % 50 for row in values[5:] for v in row)   # finer than 20 ms can measure


def test_jerkstopdist_is_the_distance_the_ramptype_2_stop_then_travels():
    # CR 1862-1870: "calculates the distance that axis n will need to stop if it allows a maximum deceleration of
    # DEC and uses the RAMPTYPE 2 with JERKMIN2 and JERKMIN4 (or JERKMIN) … the result is given in User-Units"
    run = run_source("SET RAMPTYPE 2\nSET JERKMIN 200\nSET JERKMIN4 400\nACC 20\nCVEL 50\nCSTART\nDELAY 3000\n"
                     "x = CPOS\nd = JERKSTOPDIST 20\nDEC 20\nMOTOR STOP\nPRINT d, \" \", CPOS - x\n"
                     "CVEL -30\nCSTART\nDELAY 3000\nx = CPOS\nd = JERKSTOPDIST 40\nDEC 40\nMOTOR STOP\n"
                     "PRINT d, \" \", CPOS - x\n", 20_000)
    (d1, moved1), (d2, moved2) = ([int(x) for x in p.split()] for p in run.prints)
    assert d1 > 20_000 and abs(d1 - moved1) <= 1
    assert d2 < -5000 and abs(d2 - moved2) <= 1     # backwards: a negative distance


def test_jerkstopdist_works_without_ramptype_2_and_needs_a_deceleration():
    # CR 1868-1870: "This command also works if you are not in a RAMPTYPE 2 movement"
    run = run_source("CVEL 50\nCSTART\nDELAY 2000\nPRINT JERKSTOPDIST 20 > JERKSTOPDIST 40\nd = JERKSTOPDIST 0\n",
                     5000)
    assert run.prints == ["1"]
    assert [(e.number, e.line) for e in run.errors] == [(183, 5)]


def test_jerkfinvel_is_the_velocity_after_the_acceleration_is_ramped_away():
    # CR 1846-1853: "the final velocity which would be reached if the actual acceleration (or deceleration) stops
    # under consideration of the given JERKMIN values … The result is in percent (or VELRES units) … could also be
    # negative (e.g. driving backwards …)"
    run = run_source("PRINT JERKFINVEL\nSET RAMPTYPE 2\nSET JERKMIN 2000\nACC 50\nCVEL 80\nCSTART\nDELAY 1100\n"
                     "f = JERKFINVEL\nv = AVEL * 100 % 102500\nPRINT f > v + 10, \" \", f < 80\nDELAY 5000\n"
                     "PRINT JERKFINVEL\nCVEL -30\nDELAY 8000\nPRINT JERKFINVEL\n", 30_000)
    assert run.prints == ["0", "1 1", "80", "-30"]


def test_waitndx_waits_for_the_next_index_pulse_and_times_out_with_179():
    # DG 7056: "WAITNDX waits until the next index position is reached … t = timeout in ms"; DG 11750-11752:
    # "Timeout while waiting for index: The command WAITNDX was executed and the timeout listed was exceeded."
    # One index pulse per revolution: 4 × 32-01 ENCODER (1024) = 4096 qc
    run = run_source("CVEL 1\nCSTART\nWAITNDX 5000\nPRINT APOS\nWAITNDX 5000\nPRINT APOS\nMOTOR STOP\n"
                     "PRINT TIME\nWAITNDX 300\n", 20_000)
    assert run.prints[:2] == ["4096", "8192"]
    assert [(e.number, e.line) for e in run.errors] == [(179, 9)]
    assert run.errors[0].time_ms - int(run.prints[2]) in (300, 301)
