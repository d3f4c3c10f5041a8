"""No small file can stall or exhaust the compiler: every limit is a diagnostic at file:line:col (issue 18, item 4).

Run through `motiontool check`, the command a user types; the IDE's live check compiles the same way.
"""

from __future__ import annotations

import time

from motiontool import cli
from motiontool.aposs import preprocess


def check(tmp_path, capsys, text: str, name: str = "p.m") -> tuple[int, str, float]:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    start = time.perf_counter()
    code = cli.main(["check", str(path)])
    return code, capsys.readouterr().out.replace(str(tmp_path) + "/", ""), time.perf_counter() - start


def doubling(levels: int, use: str) -> str:
    lines = ["#define A0 x x"] + [f"#define A{i} A{i - 1} A{i - 1}" for i in range(1, levels)]
    return "\n".join(lines) + "\n" + use + "\n"


def test_doubling_macros_stop_at_the_use_with_a_diagnostic(tmp_path, capsys):
    """20 levels of doubling #define (393 bytes) took 32 s and 2 GB; 30 ended in MemoryError."""
    for levels in (20, 30, 64):
        code, out, seconds = check(tmp_path, capsys, doubling(levels, f"a = 1 + A{levels - 1}"))
        assert code == 1
        first = out.splitlines()[0]
        assert first == (f"p.m:{levels + 1}:9: error: macro 'A{levels - 1}' expands to more than "
                         f"{preprocess.MAX_LINE_TOKENS} tokens on one line (doubling or recursive macros?)")
        assert f"p.m:{levels + 1}:9: note: in expansion of macro 'A{levels - 1}' (defined at p.m:{levels}:1)" in out
        assert seconds < 5


def test_many_large_expansions_stop_at_the_program_limit(tmp_path, capsys):
    text = doubling(12, "a = A11\n" * 300)
    code, out, seconds = check(tmp_path, capsys, text)
    assert code == 1
    assert f"error: macro 'A11' expands to more than {preprocess.MAX_EXPANDED_TOKENS} tokens in the program" in out
    line = int(out.split(":")[1])
    assert 13 < line < 13 + 300  # at the use where the budget ran out
    assert seconds < 10


def test_nested_function_macros_and_deep_definitions(tmp_path, capsys):
    code, out, _ = check(tmp_path, capsys, "#define D(x) x x\na = " + "D(" * 25 + "1" + ")" * 25 + "\n")
    assert code == 1 and out.startswith("p.m:2:27: error: macro 'D' expands to more than")  # arguments first
    chain = "\n".join(f"#define M{i} M{i + 1}" for i in range(150)) + "\n#define M150 1\na = M0\n"
    code, out, _ = check(tmp_path, capsys, chain)
    assert code == 1
    assert out.startswith(f"p.m:152:5: error: macro 'M{preprocess.MAX_MACRO_DEPTH}' is expanded inside more than "
                          f"{preprocess.MAX_MACRO_DEPTH} other macros")


def test_macro_calls_nested_in_arguments_stop_at_the_limit(tmp_path, capsys):
    """F(F(F(…))) 1 500 deep took 13 s (each level scans its arguments again)."""
    code, out, seconds = check(tmp_path, capsys, "#define F(x) (x)\na = " + "F(" * 1500 + "1" + ")" * 1500 + "\n")
    assert code == 1
    assert out.startswith(f"p.m:2:{5 + 2 * preprocess.MAX_MACRO_DEPTH}: error: macro 'F' is called inside the "
                          f"arguments of more than {preprocess.MAX_MACRO_DEPTH} other macro calls")
    code, out, _ = check(tmp_path, capsys, "#define F(x) (x)\na = " + "F(" * 90 + "1" + ")" * 90 + "\n")
    assert code == 0, out


def test_a_program_using_macros_heavily_is_not_limited(tmp_path, capsys):
    """2 047 tokens on each of 50 lines: far more than real programs, inside the limits."""
    lines = ["#define A0 1 + 1"] + [f"#define A{i} A{i - 1} + A{i - 1}" for i in range(1, 9)]
    code, out, _ = check(tmp_path, capsys, "\n".join(lines + [f"a{i} = A8" for i in range(50)]) + "\n")
    assert code == 0, out


def test_deeply_nested_if_condition_is_a_diagnostic(tmp_path, capsys):
    """#if with 197 nested parentheses raised RecursionError."""
    code, out, _ = check(tmp_path, capsys, "a = 1\n#if " + "(" * 1000 + "1" + ")" * 1000 + "\nb = 2\n#endif\n")
    assert (code, out) == (1, "p.m:2:1: error: #if condition nested too deeply\n")


def test_giant_integer_literal_is_a_diagnostic(tmp_path, capsys):
    """An integer literal of more than 4 300 digits raised ValueError."""
    code, out, _ = check(tmp_path, capsys, "a = 1\nb = " + "7" * 5000 + "\n")
    assert code == 1
    assert out.startswith("p.m:2:5: error: constant '77777777777777777777...' is outside the LONG range")
    code, out, _ = check(tmp_path, capsys, "#if " + "7" * 5000 + "\n#endif\n")
    assert code == 1 and out.startswith("p.m:1:5: error: constant '7777")


def test_overlong_include_name_is_a_diagnostic(tmp_path, capsys):
    """An #include name longer than the OS allows raised OSError."""
    code, out, _ = check(tmp_path, capsys, 'a = 1\n  #include "' + "n" * 300 + '.m"\n')
    assert code == 1
    assert out == f"p.m:2:3: error: cannot use include file name '{'n' * 57}...': File name too long\n"


def test_digits_of_other_scripts_are_not_apos_numbers(tmp_path, capsys):
    """Python's \\d matched '٥' (ARABIC-INDIC DIGIT FIVE), so `a = ٥` compiled as 5."""
    code, out, _ = check(tmp_path, capsys, "a = \u0665\n")
    assert (code, out) == (1, "p.m:1:5: error: unexpected character '\u0665'\n")


def test_variable_arrays_must_fit_the_controller(tmp_path, capsys):
    """`long a[2000000000]` compiled and then allocated gigabytes at the start (decisions L23)."""
    code, out, _ = check(tmp_path, capsys, "long a[600000], b[600000]\n")
    assert (code, out) == (1, "p.m:1:17: error: array 'b' makes the variable arrays 1200000 elements; the "
                              "controller holds at most 1000000 (DIM arrays are separate)\n")
    (tmp_path / "f.m").write_text("long f()\n{\nlong big[2000000000]\nreturn(1)\n}\nPRINT f()\n", encoding="utf-8")
    assert cli.main(["run", str(tmp_path / "f.m"), "--seconds", "1"]) == 2
    assert capsys.readouterr().err == "error 193: Stack overflow (line 6)\n"  # before anything is allocated
