"""Names equal to command names where the manuals' own examples use them (decision L14, issue 25 item 5).

DG 6425 says a variable name "may not be identical to a command name", but CR 429, CR 1645, CR 2488 and DG 6639
print programs that do it. Where only a name can stand (a declaration, a subprogram's name, the target of `=` of
a command that only gives a value or takes no argument) the name is the program's, with a warning; the command of
that name is then not available in the program."""

from __future__ import annotations

from tests.aposs.helpers import compile_text, messages
from tests.kernel.helpers import run_source

# CR 426-429, the CANIN syntax example as printed (with a PRINT added)
CANIN_EXAMPLE = """MSG = 0
temp = 0 /* Define variables */
rx1 = DEFCANIN 42 8 /* a RX object is created */
STAT = CANIN rx1 1000 0 MSG temp /* wait 1s for data */
PRINT STAT
"""


def _warnings(text: str) -> list[str]:
    return messages(text, "warning")


def test_cr_429_stat_as_a_variable_compiles_with_a_warning_and_holds_what_canin_returns():
    """CR 429: `STAT = CANIN rx1 1000 0 MSG temp /* wait 1s for data */`."""
    assert messages(CANIN_EXAMPLE) == []
    assert _warnings(CANIN_EXAMPLE) == [
        "4:1: 'STAT' is the name of the command STAT; this program uses it as a variable, so STAT cannot be used "
        "as the command here (DG 6425)"]
    renamed = run_source(CANIN_EXAMPLE.replace("STAT", "status"), 3000)
    run = run_source(CANIN_EXAMPLE, 3000)
    assert run.prints == renamed.prints and len(run.prints) == 1 and not run.errors


def test_cr_1645_in_as_a_variable_reads_inb():
    """CR 1645-1648: `in = INB 0 /* store the condition of the first 8 inputs */`; "IN1 = low, IN2 = high,
    IN3 = high, all other inputs are low  res = 2^1 + 2^2 = 6"."""
    text = "in = INB 0 /* store the condition of the first 8 inputs */\nPRINT in\n"
    assert messages(text) == [] and len(_warnings(text)) == 1
    run = run_source(text, 100, inputs=[(2, 1, 0), (3, 1, 0)])
    assert run.prints == ["6"]


def test_cr_2488_a_subprogram_named_break():
    """CR 2488: `ON CANINPUT 0 GOSUB break /* interrupt procedure is defined */` (DG 6037 does the same with
    ON TIME): BREAK is a keyword, but after GOSUB and SUBPROG only a subprogram's name can stand."""
    text = ("ON CANINPUT 0 GOSUB break /* interrupt procedure is defined */\nDELAY 10\n"
            "SUBMAINPROG\nSUBPROG break\nRETURN\nENDPROG\n")
    assert messages(text) == []
    assert _warnings(text) == ["4:9: 'break' is a keyword (DG 6425); it names a subprogram here, which GOSUB and "
                               "SUBPROG keep apart from the command"]
    assert compile_text(text).ok


def test_dg_6639_a_parameter_named_index():
    """DG 6639: `long modi(long[] myarray, long index)`; DG 6691 `while(index < 100) do` (the whole programs run
    as printed in tests/aposs/manual/test_language.py: F_D20, F_D21)."""
    text = ("DIM test[100]\nlong modi(long[] myarray, long index)\n{\n    myarray[index] = myarray[index] * 10\n"
            "    return(index)\n}\ntest[2] = 7\nmodi(test,2)\nPRINT test[2]\n")
    assert messages(text) == [] and len(_warnings(text)) == 1
    assert run_source(text, 100).prints == ["70"]


def test_the_command_of_a_shadowed_name_is_not_available_and_the_error_names_the_place():
    """The price of the name: once `in` is a variable, `IN 3` reads the variable and then a stray 3."""
    errors = messages("in = INB 0\nx = IN 3\n")
    assert errors and errors[0].startswith("2:")


def test_a_statement_command_with_arguments_before_equals_stays_an_error():
    """`VEL = 5` is far more likely a mistaken `VEL 5` than a variable; no example of the manuals does it."""
    assert messages("VEL = 5\n") == ["1:1: 'VEL' is a command name and cannot be used as a variable"]
