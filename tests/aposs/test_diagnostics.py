"""Broken programs give one precise diagnostic at the right line:col, never a traceback (issue 3)."""

import pytest

from .helpers import compile_text, messages

CASES = [
    # (source, "line:col", message fragment)
    ("x = 1\nGOTO nowhere\n", "2:1", "label 'nowhere' is not defined"),
    ("a:\nx = 1\na:\n", "3:1", "label 'a' is defined twice"),
    ("GOSUB missing\n", "1:1", "GOSUB target 'missing' is not a SUBPROG"),
    ("ON ERROR GOSUB handler\n", "1:1", "GOSUB target 'handler' is not a SUBPROG"),
    ("x = 1\nDIM a[10]\n", "2:1", "DIM must come before all other statements"),
    ("DIM a[2]\n#pragma NOIMPLICIT\ny = 1\n", "3:1", "'y' is not declared"),
    ("x = 1\n#pragma NOIMPLICIT\n", "2:1", "#pragma must stand directly after the DIM statement"),
    ("POSA\n", "1:1", "POSA needs more arguments (syntax: POSA p)"),
    ("POSA a + 5\n", "1:8", "must be in parentheses"),
    ("POSA 1 2\n", "1:8", "unexpected '2' after POSA"),
    ("x = f(1)\nlong f(long a)\n{\nreturn(a)\n}\n", "1:5", "called before it is declared"),
    ("BREAK\n", "1:1", "BREAK outside SWITCH, WHILE or REPEAT"),
    ("main:\nSUBMAINPROG\nSUBPROG s\nGOTO main\nRETURN\nENDPROG\n", "4:1", "jumps must stay inside"),
    ("SUBMAINPROG\nlong f(long a)\n", "2:1", "functions cannot be defined inside SUBMAINPROG"),
    ("SUBMAINPROG\nSUBPROG s\nx = 1\nENDPROG\n", "4:1", "ENDPROG does not belong here"),
    ("SUBPROG s\nRETURN\n", "1:1", "SUBPROG must stand inside the SUBMAINPROG"),
    ("IF x THEN\ny = 1\n", "1:1", "IF at prog.m:1:1 is not closed: missing ENDIF"),
    ("IF x\ny = 1\nENDIF\n", "1:5", "IF condition must end with THEN"),
    ("WHILE x\nENDWHILE\n", "1:8", "WHILE condition must end with DO"),
    ("IF x THEN\nELSE IF y THEN\nENDIF\nENDIF\n", "2:6", "write ELSEIF as one word"),
    ("x = 1\nENDWHILE\n", "2:1", "ENDWHILE without WHILE"),
    # L14: a command that can stand as a statement and takes arguments stays a command before '='; keywords never
    # name a variable (STAT = …, DIM index[5] compile with a warning: tests/aposs/test_command_names.py)
    ("VEL = 5\n", "1:1", "'VEL' is a command name and cannot be used as a variable"),
    ("DIM then[5]\n", "1:5", "'then' is a command name"),
    ("FOO 1 2\n", "1:1", "unknown command 'FOO'"),
    ("x = POSA 5\n", "1:5", "'POSA' does not return a value"),
    ("DIM a[10]\nx = a\n", "2:5", "'a' is an array; give an element"),
    ("DIM a[10]\nx = a[1][2]\n", "2:5", "'a' has one dimension"),
    ("x = b[1]\n", "1:5", "array 'b' is not declared"),
    ("double d\nx = d mod 2\n", "2:7", "operator 'mod' needs LONG operands"),
    ("x = 1 % 0\n", "1:7", "division by zero"),
    ("SWITCH x\nCASE 1:\nCASE 1:\nENDSWITCH\n", "3:6", "CASE 1 appears twice"),
    ("SWITCH x\nCASE y:\nENDSWITCH\n", "2:6", "CASE needs a constant"),
    ("long f(long a);\nx = 1\n", "1:1", "declared but never defined"),
    ("long f(long a)\n{\nreturn(a)\n}\nx = f(1, 2)\n", "5:5", "takes 1 argument(s), 2 given"),
    ("long a\nlong a\n", "2:6", "'a' is already declared"),
    ("a = 1\nlong a\n", "2:6", "'a' is used before its declaration"),
    ("long a = 5\n", "1:8", "declarations cannot give a value"),
    ("NOWAIT MAYBE\n", "1:8", "NOWAIT expects ON or OFF here"),
    ('LINKGPAR 1900 name 0 100 0\n', "1:15", "expects a text in quotes"),
    ("SETCURVE 5\n", "1:10", "expected the name of an array"),
    ("ON FOO GOSUB x\n", "1:4", "unknown interrupt"),
    ("x = (1 + 2\n", "1:11", "expected ')' to close '('"),
    ("PRINT \"a\" \"b\"\n", "1:11", "unexpected text"),
    ("x = 7.b9\n", "1:6", ".b number 9 is outside 1..4"),
    ("#include \"nothere.m\"\n", "1:1", "cannot find include file 'nothere.m'"),
    ("SUBMAINPROG\nSUBPROG a\nRETURN\nSUBPROG a\nRETURN\nENDPROG\n", "4:1", "SUBPROG 'a' is defined twice"),
    ("x = CHR(65)\n", "1:5", "CHR(n) is only allowed as a PRINT item"),
    ("LOOP 3 nolabel\n", "1:1", "label 'nolabel' is not defined"),
    ("MOTOR\n", "1:1", "unknown command 'MOTOR'"),
    ("x = 1 +\n", "1:8", "expected a value, found end of line"),
    ("a[] = b[]\n", "1:1", "array 'a' is not declared"),
]


@pytest.mark.parametrize("source, where, fragment", CASES, ids=[c[2][:40] for c in CASES])
def test_broken_program_gives_precise_error(source, where, fragment):
    errors = messages(source)
    assert errors, f"no error for {source!r}"
    first = errors[0]
    assert first.startswith(where + ":"), errors
    assert fragment in first, errors


def test_error_inside_include_file_points_into_it(tmp_path):
    (tmp_path / "inc.m").write_text("// header\n\n   POSA\n")
    main = tmp_path / "main.m"
    main.write_text('DIM a[1]\n#include "inc.m"\n')
    result = compile_text(main.read_text(), str(main))
    d = result.errors[0]
    assert (d.loc.file.endswith("inc.m"), d.loc.line, d.loc.col) == (True, 3, 4)


def test_error_from_macro_points_at_use_and_names_macro():
    result = compile_text("#define MOVE POSA\nx = 1\n   MOVE\n")
    d = result.errors[0]
    assert (d.loc.line, d.loc.col) == (3, 4)
    assert "MOVE" in d.format()


def test_several_independent_errors_are_all_reported():
    result = compile_text("GOTO a\nGOTO b\nGOSUB c\n")
    assert [d.loc.line for d in result.errors] == [1, 2, 3]


def test_never_assigned_variable_warns():
    assert messages("PRINT speed\n", "warning") == ["1:7: 'speed' is never assigned; it always reads 0"]


REVIEW_CASES = [
    ("double d\nd = 1e999\n", "2:5", "is too large"),
    ("double d\nd = 1e300 * 1e300\n", "2:11", "overflows the DOUBLE range"),
    ("SET KPRO 150\n", "1:5", "'KPRO' is not a parameter name"),
    ("x = 4000000000\n", "1:5", "outside the LONG range"),
    ("x = 1\nIF 1 THEN\nDIM a[5]\nENDIF\n", "3:1", "DIM must come before all other statements"),
    ("x = then\n", "1:5", "'then' is a keyword"),
    ("long f(long then)\n{\nreturn(1)\n}\n", "1:13", "'then' is a command name"),
    ("long f()\n{\nreturn(g())\n}\nlong g()\n{\nreturn(1)\n}\n", "3:8", "called before it is declared"),
    ("ON INT GOSUB h\n", "1:8", "ON INT needs an input number"),
    ("double b[3]\nlong f(long[] a)\n{\nreturn(a[1])\n}\nx = f(b)\n", "6:7", "is a DOUBLE array"),
    ("ON COMBIT 40 GOSUB h\nSUBMAINPROG\nSUBPROG h\nRETURN\nENDPROG\n", "1:11", "ON COMBIT needs a bit number"),
    ("a = 1\nx = a.33\n", "2:7", "bit number 33 is outside 1..32"),
    ("l:\nLOOP -1 l\n", "2:6", "LOOP needs a count of 0 or more"),
    ("x = 4 / 2\n", "1:7", "APOSS divides with '%'"),
    ("x = 1\nLOOP 2 later\nlater:\n", "2:1", "label 'later' must come before the LOOP"),
]


@pytest.mark.parametrize("source, where, fragment", REVIEW_CASES, ids=[c[2][:40] for c in REVIEW_CASES])
def test_review_findings_give_precise_errors(source, where, fragment):
    errors = messages(source)
    assert errors and errors[0].startswith(where + ":") and fragment in errors[0], errors


@pytest.mark.parametrize("source", [
    "ON DELETE +APOS SETOUT 1\n",                                       # C:2603
    "n = 3\nv = 7\nx = v.n\nv.n = 0\n",                                 # DG 6734: expr1.expr2
    "OUT X59/3 1\n",                                                    # CR 3152-3155
    "DIM t[10]\nTESTSETDEST DYNMEM\n",                                  # DG 7120
    "#define A 3\n#if A > 2 AND A < 5\nx = 1\n#endif\n",
    "x = -2147483648\n",
    "x = 3\ns = 1\nOUT x (s)\n",
    "ON INT 2*256+1 GOSUB h\nSUBMAINPROG\nSUBPROG h\nRETURN\nENDPROG\n",  # CAN input module*256 + io
    "x = 1\nIF x THEN ENDIF\n",
    "#define X 1\n#undef X /* c */\n#pragma NOIMPLICIT /* c */\n",
    "DEFCORIGIN X(1)\n",                                                # CR 826
    "o = 0\nd = CPOSDIFF x(1) o\n",                                     # CR 620
])
def test_manual_forms_compile(source):
    result = compile_text(source)
    assert result.ok, [d.format() for d in result.diagnostics]


def test_double_to_long_store_warns():
    assert messages("x = 2.5\n", "warning") == [
        "1:1: the DOUBLE value is truncated to store it in LONG 'x'; write (long) to say so"]


def test_element_address_is_computed_once_for_read_modify_write():
    from motiontool.aposs.image import Op
    image = compile_text("DIM a[10]\ni = 1\na[i++]++\n").image
    ops = [Op(image.code[2 * k]) for k in range(len(image))]
    # i++ happens once: exactly one store into i after its initial assignment
    stores_to_i = [k for k, op in enumerate(ops) if op == Op.STOREG and image.code[2 * k + 1] == 0]
    assert len(stores_to_i) == 2
