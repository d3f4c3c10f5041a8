"""The VM executes every language construct as the manual describes (run on the real controller)."""

import tomllib
from pathlib import Path

import pytest

from .helpers import run_source

EXAMPLES = tomllib.loads((Path(__file__).parents[1] / "aposs" / "operator_examples.toml").read_text())["example"]


@pytest.mark.parametrize("example", [e for e in EXAMPLES if "program" in e],
                         ids=[e["src"] + " " + e.get("var", "") for e in EXAMPLES if "program" in e])
def test_manual_program_examples_compute_the_stated_value(example):
    """The manual's statement examples (DG 6684-6787): ++, bit assignments, DOUBLE arithmetic."""
    source = example["program"].rstrip() + f"\nPRINT {example['var']}\n"
    if "SUBMAINPROG" in source.upper():
        pytest.skip("program with subprograms: value printed elsewhere")
    run = run_source(source, 1000)
    assert run.state == "ended", run.errors
    value = run.prints[-1]
    if isinstance(example["value"], float):
        assert float(value) == pytest.approx(example["value"], abs=example.get("tolerance", 1e-6))
    else:
        assert int(value) == example["value"]


def variables_program(expr: str) -> str:
    """Evaluate a binary example at run time: operands come from variables so nothing is folded."""
    return expr


@pytest.mark.parametrize("a, op, b, expected", [
    (19, "%", 3, 6), (250, "mod", 16, 10), (250, "rnd", 16, 16), (-100, "rnd", 15, -7), (127, "^", 255, 128),
    (7, "&", 6, 6), (2, "|", 4, 6), (3, "<<", 1, 6), (12, ">>", 1, 6), (-19, "%", 3, -6), (-250, "mod", 16, -10),
])
def test_long_operators_at_run_time(a, op, b, expected):
    """DG 6669-6762: % divides (19 % 3 = 6), mod, rnd, ^ is XOR, & | << >>."""
    run = run_source(f"a = {a}\nb = {b}\nx = a {op} b\nPRINT x\n", 100)
    assert run.prints == [str(expected)]


def test_double_arithmetic_and_casts_at_run_time():
    """DG 6575-6607: -100.00 % 15.0 = -6.666…, round(-6.666) = -7.0, fabs, (long)."""
    run = run_source("double y, z\nlong a\ny = -100.00\nz = 15.0\nPRINT y % z\nPRINT round(y % z)\n"
                     "PRINT fabs(y)\na = (long) (y % z)\nPRINT a\nPRINT 7 % 2\n", 100)
    assert run.prints == ["-6.666667", "-7.0", "100.0", "-6", "3"]


def test_bit_selectors_at_run_time():
    """DG 6730-6787: 7.1 = 1, 7.4 = 0, 0x027F.b1 = 127, .b2 = 2, 0x1FFFE.sb1 = -2; Value.3 = 1 → 4."""
    run = run_source("v = 7\nPRINT v.1, v.4\nw = 0x027F\nPRINT w.b1, w.b2\nq = 0x1FFFE\nPRINT q.sb1, q.ub1\n"
                     "value = 0\nvalue.3 = 1\nPRINT value\nvalue.b1 = 72\nvalue.b2 = 128\nPRINT value\n", 100)
    assert run.prints == ["1 0", "127 2", "-2 254", "4", str(0x8048)]


def test_loop_runs_n_plus_one_times():
    """CR 2116-2130: LOOP n jumps back n times, so the block runs n+1 times; LOOP 9 runs 10 times."""
    run = run_source("i = 0\nagain:\ni++\nLOOP 9 again\nPRINT i\nj = 0\nonce:\nj++\nLOOP 0 once\nPRINT j\n", 100)
    assert run.prints == ["10", "1"]


def test_loop_counter_restarts_when_the_loop_is_entered_again():
    run = run_source("n = 0\nk = 0\nouter:\ninner:\nn++\nLOOP 2 inner\nk++\nIF k < 3 THEN\nGOTO outer\nENDIF\n"
                     "PRINT n\n", 100)
    assert run.prints == ["9"]


def test_control_structures():
    """C:1523-1568 IF/ELSEIF/ELSE, WHILE, REPEAT (runs at least once), SWITCH with fall-through."""
    src = """
x = 2
IF x == 1 THEN
  PRINT "one"
ELSEIF x == 2 THEN
  PRINT "two"
ELSE
  PRINT "other"
ENDIF
i = 0
WHILE i < 3 DO
  i++
ENDWHILE
PRINT i
REPEAT
  i = i + 10
UNTIL i > 0
PRINT i
SWITCH (x)
CASE 1:
  PRINT "c1"
  BREAK
CASE 2:
  PRINT "c2"
CASE 3:
  PRINT "c3"
  BREAK
DEFAULT:
  PRINT "d"
ENDSWITCH
SWITCH 9
CASE 1:
  PRINT "no"
DEFAULT:
  PRINT "default"
ENDSWITCH
k = 0
WHILE 1 DO
  k++
  IF k == 5 THEN
    BREAK
  ENDIF
ENDWHILE
PRINT k
"""
    run = run_source(src, 100)
    assert run.prints == ["two", "3", "13", "c2", "c3", "default", "5"]


def test_subprograms_functions_arrays():
    """DG 6609-6650: functions with locals, long[] by reference, return(); GOSUB/RETURN; array copy."""
    src = """
DIM test[100], other[5]
long modi(long[] myarray, long idx)
{
    myarray[idx] = myarray[idx] * 10
    return(idx)
}
long fact(long n)
{
    IF n <= 1 THEN
        return(1)
    ENDIF
    return(n * fact(n - 1))
}
long noreturn(long a)
{
    a = a + 1
}
test[2] = 7
r = modi(test, 2)
PRINT test[2], " ", r
PRINT fact(10)
PRINT noreturn(5)
GOSUB sub
PRINT g
other[] = test[]
PRINT other[2]
long m[2][3]
m[2][3] = 23
PRINT m[2][3], " ", m[6]
SUBMAINPROG
SUBPROG sub
  g = 42
RETURN
ENDPROG
"""
    run = run_source(src, 100)
    assert run.prints == ["70 2", "3628800", "0", "42", "70", "23 23"]


def test_print_formats_and_semicolon():
    """C:3516-3533: items separated by commas, CHR(n) prints a character, ';' keeps the line open."""
    run = run_source('PRINT "a=", 5, " b=", 2.5;\nPRINT " c", CHR(65)\nPRINT\n', 100)
    assert run.prints == ["a=5 b=2.5 cA", ""]


def test_print_puts_a_blank_between_items_that_have_none():
    """CR 229-240: `PRINT "Actual Position Reached", APOS` → "Actual Position Reached 2000"; CR 873-880: `PRINT
    "Position after defining new origin", APOS` → "… origin 0". The manuals' programs bring their own blank
    (DG 3380 `print "Hello: ",i`, CR 3805 `"Parameter ",para," has the length ",res`): no second one is added; no
    blank before closing punctuation or around '=' and CHR(n); nothing between PRINTs joined by ';' (CR 3740 prints a
    string character by character). Decision K48."""
    run = run_source('POSA 2000\nDELAY 200\nPRINT "Actual Position Reached", APOS\ni = 1\nPRINT "Hello: ",i\n'
                     'PRINT "Parameter ",1549," has the length ",7\nPRINT "Variable", 10,"Pos.:",2000\n'
                     'PRINT "peak ", 5, ": done", 1.5, ", more (", 3, ")"\nPRINT "x", "=", 2, CHR(176), "C"\n'
                     'PRINT "a";\nPRINT 1, 2;\nPRINT "b"\n', 1000)
    assert run.prints == ["Actual Position Reached 2000", "Hello: 1", "Parameter 1549 has the length 7",
                          "Variable 10 Pos.: 2000", "peak 5: done 1.5, more (3)", "x=2\xb0C", "a1 2b"]


@pytest.mark.parametrize("source, number", [
    ("DIM a[3]\nx = a[4]\n", 171),
    ("DIM a[3]\na[0] = 1\n", 171),
    ("x = 0\ny = 5 % x\n", 156),
    ("double d\nd = -1.0\nd = sqrt(d)\n", 156),
    ("GOSUB s\nSUBMAINPROG\nSUBPROG s\nGOSUB s\nRETURN\nENDPROG\n", 151),
])
def test_runtime_errors_have_the_manual_numbers(source, number):
    """DG 11650-11724: 171 array index outside, 151 recursive GOSUB, 156 illegal argument (decisions L6)."""
    run = run_source(source, 100)
    assert run.state == "error"
    assert run.errors[0].number == number
    assert run.controller.error == number


def test_gosub_nesting_deeper_than_ten_is_error_151():
    subs = "\n".join(f"SUBPROG s{i}\nGOSUB s{i + 1}\nRETURN" for i in range(11)) + "\nSUBPROG s11\nRETURN"
    run = run_source(f"GOSUB s0\nSUBMAINPROG\n{subs}\nENDPROG\n", 100)
    assert run.errors[0].number == 151


def test_dim_arrays_persist_between_programs_and_sizes_are_checked():
    """C:1024-1041: identity by position; a different size is error 176."""
    from motiontool.controller.embedded import EmbeddedLink

    link = EmbeddedLink()
    first = run_source("DIM a[5]\na[3] = 33\n", 100, link=link)
    assert first.state == "ended"
    second = run_source("DIM b[5]\nPRINT b[3]\n", 100, link=link)
    assert second.prints == ["33"]
    third = run_source("DIM c[6]\n", 100, link=link)
    assert third.errors[0].number == 176


def test_timing_delay_and_time():
    """C:976-993: DELAY t pauses t ms; TIME reads the controller time in ms."""
    run = run_source("t = TIME\nDELAY 250\nPRINT TIME - t\n", 1000)
    assert run.prints == ["250"]


def test_instruction_budget_lets_a_busy_loop_share_time():
    """Decision K1: 500 instructions per ms; a busy loop still lets time advance."""
    run = run_source("t = TIME\ni = 0\nWHILE i < 100000 DO\ni++\nENDWHILE\nPRINT TIME - t\n", 5000)
    elapsed = int(run.prints[0])
    assert 1000 < elapsed < 3000


def test_out_on_a_connector_pin():
    """CR 3152-3155: OUT X59/3 1 sets output 3; an unknown connector is error 171 (CR 3127-3128)."""
    run = run_source("OUT X59/3 1\nPRINT IN 1\nOUT X34/9 1\n", 100)
    assert run.controller.io.outputs[3] == 1
    assert run.errors[0].number == 171


def test_printdev_minus_one_stops_the_output():
    """CR 3535-3550: "PRINTDEV can be used to disable all prints in a program without commenting them out one by one
    … -1 = no output after that line"; `PRINTDEV 0` (DG 7116: "0 = standard") brings it back. Switching the device
    prints no empty line."""
    run = run_source('PRINT "one"\nPRINTDEV -1\nPRINT "two"\nPRINTDEV 0\nPRINT "three"\nPRINTDEV -1 "four"\n', 100)
    assert run.prints == ["one", "three"]
