"""The manuals' language examples run on the simulated controller: what they print and compute is what the manuals
say (HELLO, the error handler, PRINT, control flow, arrays, DOUBLE arithmetic, functions, ++, the preprocessor)."""

from __future__ import annotations

import re

import pytest

from .helpers import run_manual, source, variables


def test_d12_hello_prints_five_greetings_half_a_second_apart_and_good_bye():
    """DG 3377-3380 (HELLO.M): `while (i <= 5) do print "Hello: ",i delay 500 i = i + 1 endwhile print "Good bye."`."""
    run = run_manual("D12_hello.m", 5000)
    assert run.prints == [f"Hello: {i}" for i in range(1, 6)] + ["Good bye."]
    assert [t - run.print_times[0] for t in run.print_times] == [0, 500, 1000, 1500, 2000, 2500]
    assert run.state == "ended" and not run.errors


LIMIT_SWITCH = {"settings": {"I_FUNCTION_1": 5}, "inputs": [(1, 1, 500), (1, 0, 3000)]}  # input 1: + limit switch


@pytest.mark.parametrize("name, branch", [
    ("D15_error_handler.m", "It's o.k., although it wasn't a limit switch"),   # as printed: ERRNO == 25
    ("D15_error_handler_corrected.m", "HW end limit activated"),
])
def test_d15_error_handler_reports_the_error_waits_ten_seconds_clears_and_ends(name, branch):
    """DG 6232-6257: the program asks for a limit switch to be pushed; the error handler prints ERRNO, waits 10 s,
    clears the error and ends with EXIT. The limit switch is error 125 (DG 11612-11628), so the printed test
    `ERRNO == 25` takes the ELSE branch; the corrected copy tests 125. `PRINT …;` keeps the line open: the next PRINT
    continues it (K48)."""
    run = run_manual(name, 15000, **LIMIT_SWITCH)
    assert run.prints == ["Please create a temporary error status", " by pushing a limit switch.",
                          "Current error number: 125", branch,
                          "You can re-set the cause of the errorwithin the next 10 seconds",
                          "Re-set error status ....", "... and program terminated."]
    assert [e.number for e in run.errors] == [125]
    assert 10500 <= run.print_times[-1] <= 10510 and run.state == "ended"
    assert run.controller.error == 0


def test_c01_apos_after_posa_without_and_with_a_temporary_zero():
    """CR 228-240: `POSA 2000` / `PRINT "Actual Position Reached", APOS` → "Actual Position Reached 2000 (depending on
    PID settings a small deviation may occur)"; after `SETORIGIN 2000`, `POSA 2000` → "Actual Position 2000" — the
    axis then stands at the real 4000. A target window of 5 qc (33-47 TESTWIN) makes POSA wait for the actual
    position."""
    run = run_manual("C01_apos_setorigin.m", 10000, settings={"TESTWIN": 5, "TESTVAL": 5, "TESTTIM": 5})
    assert [re.sub(r"\d+$", "N", p) for p in run.prints] == ["Actual Position Reached N", "Actual Position N"]
    assert all(abs(int(p.split()[-1]) - 2000) <= 5 for p in run.prints)
    assert run.controller.axis.cpos == 4000 and not run.errors


def test_c05_deforigin_makes_the_actual_position_zero():
    """CR 873-880: "Position before new origin 2000", "Position after defining new origin 0"."""
    run = run_manual("C05_deforigin.m", 10000, settings={"TESTWIN": 5, "TESTVAL": 5, "TESTTIM": 5})
    assert run.prints[1] == "Position after defining new origin 0"
    before = re.fullmatch(r"Position before new origin (\d+)", run.prints[0])
    assert before and abs(int(before[1]) - 2000) <= 5 and not run.errors


def test_c22_print_forms():
    """CR 3516-3533: text, text with ';' (no line feed), a variable, APOS, mixed information separated by commas."""
    run = run_manual("F_C22_print.m", 1000)
    assert run.prints == ["Information is important !", "Information is important !10", "0", "Variable 10 Pos.: 0"]


def test_c08_control_flow():
    """CR 1443-1451 GOSUB, 1467-1470 GOTO, 1553-1567 IF/ELSEIF/ELSE, 1590-1595 IN, 2133-2136 "LOOP 9 … repeat loop
    contents 10 times", 3629-3632 REPEAT … UNTIL; DG 6524-6528 BREAK; names are case-insensitive (a / A)."""
    run = run_manual("F_C08_control_flow.m", 1000, inputs=[(2, 1, 0), (4, 1, 0)])
    assert run.state == "ended" and not run.errors
    assert variables(run, "calls", "cnt", "branch", "in4", "loops", "reps", "w") == [1, 3, 2, 1, 10, 2, 3]
    assert run.controller.io.outputs[1] == 1                          # IF (IN 2): output 1 set


def test_d16_arrays_as_printed_fill_only_the_first_row():
    """DG 6443-6510: DIM, reading and writing elements, `%`; DG 6465-6474 fills `test[10][100]` with
    `test[lin][col++] = value++` but never resets `col`, so only row 1 is filled (a slip of the manual); the corrected
    copy resets it and fills all 1000 elements."""
    run = run_manual("F_D16_arrays.m", 10000, settings={"TESTWIN": 5, "TESTVAL": 5, "TESTTIM": 5})
    assert run.prints == ["offs[1] = 1000 test[1][100] = 100"]   # `%` divides (DG 6677-6680): 20000 % 20
    # test[2][1] is element 101 in row-major order (L20)
    assert variables(run, "ypos[19]", "test[101]", "lin", "col") == [19000, 0, 11, 101]
    assert abs(run.controller.uu(run.controller.axis.apos) - 10000) <= 5   # POSA xpos[1]
    fixed = run_manual("F_D16_arrays_corrected.m", 10000)
    assert variables(fixed, "test[101]", "test[1000]") == [101, 1000]


def test_d18_copying_an_array_copies_as_many_elements_as_the_smaller_holds():
    """DG 6482-6486: `test[] = field[]` with test[100] and field[200]."""
    run = run_manual("F_D18_array_copy.m", 1000)
    assert run.prints == ["test[1] = 1 test[100] = 100"]


@pytest.mark.parametrize("name, fabs", [("F_D19_doubles.m", "0.0"), ("F_D19_doubles_corrected.m", "6.666667")])
def test_d19_double_arithmetic(name, fabs):
    """DG 6573-6607: `dy = -100.00 % 15.0 // this will be -6.6666..`, `dx = round(dy) // this will be -7.0000`,
    `b = a rnd 15 // now correctly delivers -7`, casts. The manual writes `dx = fabs(dx) // this gives back
    6.6666..` where dx is still 0.0; the corrected copy takes fabs(dy)."""
    run = run_manual(name, 1000)
    # `y = a % 2` divides in LONG arithmetic before the DOUBLE store (DG 6605-6607): 6 % 2 = 3
    assert run.prints == [f"dy = -6.666667 fabs = {fabs}", "round = -7.0", "b = -7", "a = 6 y = 3.0"]
    assert not run.errors


def test_d20_functions_return_a_value_and_change_an_array_by_reference():
    """DG 6621-6646: test_func(1, 2, 2.0) returns 1 + 2 + 2; modi(test, 2) multiplies element 2 by 10 (as printed: a
    parameter named `index`, DG 6639, decision L14)."""
    run = run_manual("F_D20_functions.m", 1000)
    assert run.prints == ["wert = 5 test[2] = 70"] and not run.errors


def test_d21_post_increment_yields_the_old_value():
    """DG 6690-6702 and the operator rows DG 6673-6675: `var = testarray[5]++` gives 7 and leaves 8."""
    run = run_manual("F_D21_postincrement.m", 1000)
    assert run.prints == ["var = 7 testarray[5] = 8"]
    assert variables(run, "value", "testarray[10]", "index") == [-1, 1, 100]


def test_d22_preprocessor_macros_and_conditional_compilation():
    """DG 6892-6994: the object-like and function-like macros expand where used (`PRINT "VALUE = ",10` then 20),
    SUM_SQUARE(3,4) = 25, `#ifdef`/`#else`, `#if 0/1`, `#if OPTION > 2`, `#elif`."""
    run = run_manual("F_D22_preprocessor.m", 1000)
    line = next(n for n, text in enumerate(source("F_D22_preprocessor.m").splitlines(), 1)
                if text.startswith('PRINT "This is line ",__LINE__'))
    assert run.prints[0] == " apos = 0 avel = 0" and run.prints[2] == " apos = 0 avel = 0"
    assert run.prints[1] == f"This is line {line}"
    assert run.prints[3:] == ["VALUE = 10", "VALUE = 20", "This will always be compiled.",
                              "Compile this for customer B."]
    assert variables(run, "i", "start") == [5, 1]


def test_c21_software_pid_filter():
    """CR 3409-3444: u(n) = (KP·e(n) + KD·(e(n) − e(n−1)) + KI·Σe) / timer; with KP 1, KD 1 the first output is 2·e.
    INAD 53 reads the analog input (−1000 … 1000 = −10 … +10 V, CR 1601-1612)."""
    run = run_manual("F_C21_pid.m", 1000, inputs=[(53, 250, 0)])
    assert run.prints == ["input = 250 output = 500"]
