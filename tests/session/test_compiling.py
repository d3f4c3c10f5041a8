"""Compiling a window's program without Qt (issue 27 item 5): the compiler for its language and Settings →
Compiler's checks (DG 3057-3085)."""

from __future__ import annotations

from motiontool.session.compiling import CompilerSettings, compile_program


def test_an_aposs_program_compiles_with_its_stem_as_the_image_name():
    outcome = compile_program("i = 1\n", "/work/axis.m", "axis.m", dpl=False)
    assert outcome.result.ok and outcome.first_error is None
    assert outcome.result.image.name == "axis"


def test_the_first_error_gives_line_and_column():
    outcome = compile_program("i = 1\nj = = 2\n", None, "Untitled.m", dpl=False)
    assert not outcome.result.ok
    assert outcome.first_error[0] == 2
    assert outcome.result.errors[0].format().startswith("Untitled.m:2:")


def test_settings_limits_are_errors_at_the_first_line():
    """DG 3057-3085: Max number of variables (an array counts as one), Enable Preprocessor."""
    source = "#define N 1\nDIM c[3]\na = N\nb = 2\n"
    assert compile_program(source, None, "p.m", dpl=False).result.ok
    tight = CompilerSettings(max_variables=2, preprocessor=False)
    outcome = compile_program(source, None, "p.m", dpl=False, settings=tight)
    messages = [d.format() for d in outcome.result.errors]
    assert any("#define: the preprocessor is switched off" in m and m.startswith("p.m:1:") for m in messages)
    assert any("the program has 3 variables (arrays count as one); Settings → Compiler allows 2" in m
               for m in messages)


def test_a_dpl_program_is_checked_not_compiled():
    outcome = compile_program("Initial{\n  a% = 1\n}\n", None, "Untitled.dpl", dpl=True)
    assert outcome.result.ok and not hasattr(outcome.result, "image")
