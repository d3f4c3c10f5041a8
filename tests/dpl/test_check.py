"""The DPL front end: tokens, syntax, checks, and diagnostics that look exactly like the APOSS compiler's."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from motiontool.aposs.driver import compile_source
from motiontool.cli import main
from motiontool.dpl import ast
from motiontool.dpl.driver import check_source
from motiontool.dpl.lexer import PARAM, tokenize
from motiontool.language.diagnostics import Diagnostic
from tests.dpl.manual import PROGRAMS, seed_code


def diagnostics(text: str) -> list[str]:
    return [d.format() for d in check_source(text, "p.dpl").diagnostics]


def errors(text: str) -> list[str]:
    return [d.format() for d in check_source(text, "p.dpl").errors]


def test_diagnostics_are_the_aposs_compilers_objects_and_format():
    """Same class, same `path:line:col: severity: message` text as `motiontool check prog.m`."""
    dpl = check_source("Pos0{\nx% = APC_NOPE\n}\n", "prog.dpl").diagnostics[0]
    aposs = compile_source("x = \n", "prog.m").diagnostics[0]
    assert type(dpl) is type(aposs) is Diagnostic
    assert dpl.format() == "prog.dpl:2:6: error: unknown name 'APC_NOPE' (integer variables end with '%')"
    assert aposs.format().startswith("prog.m:1:")


def test_check_command_takes_dpl_and_aposs_files_in_order(tmp_path, capsys):
    good = tmp_path / "good.dpl"
    good.write_text("Pos0{\nx% = MULDIV(2, 3, 4)\n}\n")
    bad = tmp_path / "bad.dpl"
    bad.write_text("Initial {\nStatus% = APCSetRunMode(APC_DI SABLE)\n}\n")
    m = tmp_path / "ok.m"
    m.write_text("a = 1\n")
    assert main(["check", str(good), str(m)]) == 0
    assert capsys.readouterr().out == ""
    assert main(["check", str(bad), str(good)]) == 1
    assert capsys.readouterr().out == (f"{bad}:2:32: error: expected ')' closing the arguments of APCSetRunMode, "
                                       "found 'SABLE'\n")


def test_the_unrepaired_manual_text_gets_errors_at_the_damaged_places(tmp_path):
    """The OCR'd §7.1 program as printed: the first damage stops the parse at its line and column."""
    raw = tmp_path / "raw.dpl"
    raw.write_text("\n".join(text for _, text in seed_code([(5065, 5227)])) + "\n", encoding="utf-8")
    out = subprocess.run([sys.executable, "-m", "motiontool", "check", str(raw)], capture_output=True, text=True)
    assert out.returncode == 1
    assert out.stdout.startswith(f"{raw}:45:1: error: unexpected character '\\'")


@pytest.mark.parametrize("source, message", [
    ("Pos0{\nIF #01.11 = 1 THEN\nx% = 1\n}\n", "p.dpl:4:1: error: '}' inside the IF at p.dpl:2:1: ENDIF is missing"),
    ("Pos0{\nx% = 1\n", "p.dpl:3:1: error: end of file inside the Pos0 task: its closing '}' is missing"),
    ("x% = 1\n", "p.dpl:1:1: error: statements belong inside a task: Initial { … }, Background { … }, Pos0 { … } "
                 "or Pos1 { … }; found 'x%'"),
    ("Pos0{\n}\nPOS0{\n}\n", "p.dpl:3:1: error: a second Pos0 task (the first is at p.dpl:1:1)"),
    ("Pos0{\nSpeed = 3\n}\n", "p.dpl:2:1: error: 'Speed' cannot be assigned: integer variables end with '%' "
                              "(floating-point variables are not supported by this simulator)"),
    ("Pos0{\nx% = 1.5\n}\n", "p.dpl:2:6: error: '1.5': floating-point values are not supported by this "
                             "simulator (DPL integer programs only)"),
    ("Pos0{\n#18. 12 = 1\n}\n", "p.dpl:2:1: error: a drive parameter is written #MM.PP without blanks, e.g. #18.11"),
    ("Pos0{\nx % = 1\n}\n", "p.dpl:2:3: error: unexpected '%': it belongs directly after an integer variable's "
                            "name (Count%)"),
    ("Pos0{\nIF x% = 1 THEN\nELSE IF x% = 2 THEN\nENDIF\n}\n",
     "p.dpl:3:6: error: write ELSEIF as one word (ELSE IF would need its own ENDIF)"),
    ("Pos0{\nWHILE x% < 3\n}\n", "p.dpl:2:1: error: 'WHILE' is not supported by this DPL simulator (the APC "
                                 "manual's programs do not use it); write the loop with a label and GOTO"),
    ("Pos0{\nx%.32 = 1\n}\n", "p.dpl:2:4: error: a bit number 0..31 follows '.', found '32'"),
    ("Pos0{\nx% = 2147483648\n}\n", "p.dpl:2:6: error: constant '2147483648' is outside the integer range "
                                    "-2147483648 … 2147483647"),
])
def test_syntax_errors_name_the_place(source, message):
    assert errors(source) == [message]


def test_checks_report_every_problem_with_its_place():
    source = "\n".join([
        "Initial {",
        "DIM A%[3]",
        "DIM A%[4]",                                  # 3: twice
        "CONST T%[2] = { 1, 2, 3 }",                  # 4: three values for two
        "DIM B%[0]",                                  # 5: size 0
        "}",
        "Background{",
        "GOTO TOP:",                                  # 8: label in another task
        "x% = A%",                                    # 9: array without index
        "T%[0] = 1",                                  # 10: CONST written
        "y% = C%[1] + A%[3]",                         # 11: not an array; index outside
        "(v%, s%, r%) = APCReadPar(48)",              # 12: three results for two
        "z% = APCSetRunMode()",                       # 13: argument missing
        "s% = APCCamInitialise1(A%, y%)",             # 14: not an array
        "s% = APCSetReferencePosition(1, 2, 3)",      # 15: warning: POS task
        "w% = APC_OFF_ACCEL + 1 / 0",                 # 16: duplicate alias warning; division by zero
        "#100.2 = 1",                                 # 17: parameter menu
        "_X01% = 3",                                  # 18: not a PLC register
        "}",
        "Pos0{",
        "TOP:",
        "TOP:",                                       # 22: label twice
        "q% = never%",                                # 23: never assigned (warning)
        "}",
        "Clock{",
        "}",
    ]) + "\n"
    assert diagnostics(source) == [
        "p.dpl:3:1: error: A% is DIMensioned twice (first at p.dpl:2:1)",
        "p.dpl:4:1: error: CONST T%[2] is given 3 values",
        "p.dpl:5:8: error: the size of B% must be 1 … 65535, not 0",
        "p.dpl:8:1: error: label 'TOP' is not defined in the Background task; labels belong to one task and 'TOP' "
        "is in the Pos0 task",
        "p.dpl:9:6: error: A% is an array: give an element, e.g. A%[0]",
        "p.dpl:10:1: error: T% is a CONST array (in flash): it cannot be written",
        "p.dpl:11:6: error: C% is not an array: DIM C%[size] first",
        "p.dpl:11:17: error: index 3 is outside A%[0 … 2]",
        "p.dpl:12:1: error: APCReadPar gives 2 results (Value%, Status%), not 3",
        "p.dpl:13:6: error: APCSetRunMode takes 1 argument (Mode%), not 0",
        "p.dpl:14:28: error: APCCamInitialise1: OutArray1% is the name of a DIM or CONST array",
        "p.dpl:15:6: warning: APCSetReferencePosition belongs in a POS task (Pos0/Pos1), not Background (seed 004 "
        "L3092)",
        "p.dpl:16:6: warning: APC_OFF_ACCEL is 150; the manual prints the name twice (also printed for the offset "
        "flag 164)",
        "p.dpl:16:26: error: division by zero",
        "p.dpl:17:1: error: drive parameter #100.2: menus and parameters are 0 … 99",
        "p.dpl:18:1: error: _X01%: PLC registers are _P00% … _U99% (names starting '_' are reserved)",
        "p.dpl:22:1: error: label 'TOP' is defined twice in the Pos0 task (first at p.dpl:21:1)",
        "p.dpl:23:6: warning: 'never%' is read but never assigned anywhere (it stays 0)",
        "p.dpl:25:1: error: the Clock task is not run by this simulator (it runs Initial, Background, Pos0 and Pos1)",
    ]


def test_unknown_names_suggest_the_definition_or_function_meant():
    assert errors("Pos0{\nx% = APCSelectRefernce(APC_PR0F_ST0P)\n}\n") == [
        "p.dpl:2:6: error: unknown function 'APCSelectRefernce'; did you mean APCSelectReference?",
        "p.dpl:2:24: error: unknown name 'APC_PR0F_ST0P'; did you mean APC_PROF_STOP? (integer variables end "
        "with '%')",
    ]


def test_the_language_as_the_manual_writes_it():
    """Names ignore case, tuple results, one-line IF, bit access, parameters with one-digit menus (L1969),
    calls as statements (§8.2), labels with and without the colon in GOTO, Notes prose with any text."""
    source = "\n".join([
        "Notes{ anything: IF ( #1.1 = \"\" and more",
        "lines } //Notes",
        "Initial {",
        "CONST Tab%[] = { 1, -2,",
        "   APC_FB_POS }",
        "DIM a%[Tab%SIZE]" if False else "DIM a%[3]",
        "}",
        "Pos1{",
        "top:",
        "(v%, s%) = apcreadpar(apc_fb_pos)",
        "IF V% > 3 AND NOT s% = 0 OR #1.06 <> 2 THEN a%[1] = Tab%[2]",
        "Bits%.3 = 1",
        "#18.12.0 = Bits%.3",
        "APCSetPGain(#18.12)",
        "x% = -(3 + 4) * 2 / 3 & 0x0F | 16",
        "goto top",
        "GOTO TOP:",
        "} // Pos1",
    ]) + "\n"
    result = check_source(source, "p.dpl")
    assert result.diagnostics == []
    program = result.program
    assert program.notes.startswith(" anything: IF")
    assert [c.name for c in program.consts] == ["TAB%"]
    assert result.symbols.consts["TAB%"] == [1, -2, 48]
    assert result.symbols.arrays == {"A%": 3}
    pos1 = program.tasks["Pos1"].body
    assert isinstance(pos1[1], ast.TupleAssign) and [t.name for t in pos1[1].targets] == ["V%", "S%"]
    assert isinstance(pos1[2], ast.If) and pos1[2].orelse is None
    assert isinstance(pos1[4].target, ast.Bit) and isinstance(pos1[4].target.base, ast.Param)
    assert isinstance(pos1[5], ast.CallStmt)
    assert [t.value for t in tokenize("#1.06 #18.11", "x") if t.kind == PARAM] == [(1, 6), (18, 11)]


def test_notes_without_closing_brace_and_unreadable_files_are_errors(tmp_path):
    assert errors("Notes{\nno end\n") == ["p.dpl:1:1: error: Notes task without its closing '}'"]
    missing = tmp_path / "missing.dpl"
    assert [d.format() for d in check_source(path=missing).diagnostics] == [
        f"{missing}:1:1: error: cannot read the file: No such file or directory"]
    latin = tmp_path / "latin.dpl"
    latin.write_bytes(b"Pos0{\n// \xe9\n}\n")
    assert check_source(path=latin).diagnostics == []  # Latin-1, as APOSS programs (decisions R17)


_WORDS = ["Initial", "Background", "Pos0", "Pos1", "Notes", "{", "}", "\n", "IF", "THEN", "ELSEIF", "ELSE", "ENDIF",
          "GOTO", "top:", "top", "DIM", "CONST", "x%", "A%", "[", "]", "(", ")", ",", "=", "<>", "+", "-", "*", "/",
          ".", "3", "0", "65536", "#18.11", "APCReadPar", "MULDIV", "APC_FB_POS", "AND", "NOT", "REINIT", "&", "\"s\"",
          "1.5", "%", "#", "_P01%", "CTSyncGetSlaveReferences"]


@settings(max_examples=400, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.sampled_from(_WORDS), max_size=60), st.text(max_size=20))
def test_any_input_gives_diagnostics_never_an_exception(words, noise):
    """Fuzzing: token soup and arbitrary text always end in diagnostics inside the file (or a clean program)."""
    for text in (" ".join(words), " ".join(words) + noise):
        result = check_source(text, "f.dpl")
        lines = text.count("\n") + 1
        for d in result.diagnostics:
            assert d.severity in ("error", "warning") and d.format()
            assert 1 <= d.loc.line <= lines + 1 and d.loc.col >= 1
        assert (result.program is None) == bool(result.errors)


def test_fuzzing_the_manual_programs_by_deleting_lines():
    """Every single-line deletion of every manual program gives diagnostics or a clean program, never a crash."""
    for path in sorted(PROGRAMS.glob("*.dpl")):
        lines = path.read_text(encoding="utf-8").split("\n")
        for n in range(0, len(lines), 3):
            check_source("\n".join(lines[:n] + lines[n + 1:]), str(path))


def test_a_very_deep_program_is_an_error_not_a_crash():
    depth = 3000
    source = "Pos0{\n" + "IF 1 THEN\n" * depth + "ENDIF\n" * depth + "}\n"
    result = check_source(source, "deep.dpl")
    assert result.errors
    assert Path("deep.dpl").name in result.errors[0].format()
