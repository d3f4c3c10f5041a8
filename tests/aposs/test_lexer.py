"""Lexical rules of APOSS (spec §1; DG 6202-6208, 6405-6419)."""

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.aposs.lexer import DIRECTIVE, FLOAT, IDENT, INT, NEWLINE, STRING, tokenize
from motiontool.language.diagnostics import CompileError, Diagnostic
from tests.kernel.helpers import run_source


def kinds(text):
    return [(t.kind, t.value) for t in tokenize(text, "t.m") if t.kind not in (NEWLINE, "EOF")]


def test_keywords_are_case_insensitive_and_keep_their_spelling():
    """DG 6425: names 'can be written in small or capital letters (no difference!)'."""
    toks = tokenize("While wHILE", "t.m")
    assert [t.value for t in toks[:2]] == ["WHILE", "WHILE"]
    assert [t.text for t in toks[:2]] == ["While", "wHILE"]


def test_number_forms():
    """DG 6413: decimal 5000, hexadecimal 0x7F = 127, octal 0100 = 64, 'A' = 65."""
    assert kinds("5000 0x7F 0X2000 'A' 15.0") == [(INT, 5000), (INT, 127), (INT, 0x2000), (INT, 65),
                                                   (FLOAT, 15.0)]


def test_octal_constant_warns_and_bad_octal_digit_is_an_error():
    warnings: list[Diagnostic] = []
    assert tokenize("x = 0100", "t.m", warnings=warnings)[2].value == 64
    assert "octal" in warnings[0].message and warnings[0].loc.col == 5
    with pytest.raises(CompileError, match="invalid digit '8' in octal constant '018'"):
        tokenize("x = 018", "t.m")


def test_an_fc_parameter_number_with_a_leading_zero_is_decimal():
    """CR 4047 writes FC 300 par. 0-25 as `025` after SETVLT (the LCP number without its dash, as CR 1405 `GETVLT
    413` for 4-13); DG 6413's octal rule would make it 21. Right after GETVLT, GETVLTSUB, SETVLT and SETVLTSUB the
    number is decimal, with no octal warning; elsewhere 025 stays octal (decision L1)."""
    warnings: list[Diagnostic] = []
    toks = tokenize("SETVLTSUB 025 1 0100\nx = getvlt 0413 + 025", "t.m", warnings=warnings)
    assert [t.value for t in toks if t.kind == INT] == [25, 1, 64, 413, 21]
    assert [w.loc.col for w in warnings] == [17, 19]
    assert [w.loc.line for w in warnings] == [1, 2]
    with pytest.raises(CompileError, match="invalid digit '8'"):
        tokenize("x = GETVLT + 018", "t.m")


def test_hex_wraps_to_a_signed_32_bit_value():
    assert kinds("0xFFFFFFFF") == [(INT, -1)]
    with pytest.raises(CompileError, match="does not fit in 32 bits"):
        tokenize("0x100000000", "t.m")


def test_bit_suffix_after_a_name_is_not_a_double():
    """DG 6784: Value.3 = 1 sets bit 3."""
    assert kinds("Value.3 arr[1].b1 0x027F.b2") == [
        (IDENT, "VALUE"), ("OP", "."), (INT, 3), (IDENT, "ARR"), ("OP", "["), (INT, 1), ("OP", "]"),
        ("OP", "."), (IDENT, "B1"), (INT, 0x027F), ("OP", "."), (IDENT, "B2")]


def test_the_bit_table_example_7_1_is_a_double_and_the_warning_shows_the_bit_form():
    """DG 6734-6738 prints "expr1.expr2 7.1 = 1 7.3 = 1 7.4 = 0  Returns the Bit expr2 from expr1", but DG 6565-6577
    prints 0.5, 15.0, -100.00 as DOUBLE constants: no lexical rule tells 7.1 from 1.5, so `7.1` stays a DOUBLE and a
    LONG that receives it is told how to write the bit, when the number has that bit (decision L2; `x = 2.5` keeps
    the plain warning, test_diagnostics.py). The table's values hold in that form."""
    assert kinds("7.1 0.5") == [(FLOAT, 7.1), (FLOAT, 0.5)]
    result = compile_source("x = 7.1\nd = 2.75\n", "t.m")
    assert [d.message for d in result.diagnostics] == [
        "the DOUBLE value is truncated to store it in LONG 'x'; write (long) to say so; 7.1 is a DOUBLE constant: "
        "bit 1 of 7 is written (7).1",
        "the DOUBLE value is truncated to store it in LONG 'd'; write (long) to say so"]
    run = run_source("PRINT (7).1, \" \", (7).3, \" \", (7).4\n", 100)
    assert run.prints == ["1 1 0"]


def test_comments_and_locations():
    """DG 6202-6208: /* block */ and // line comments."""
    toks = tokenize("ACC 10 /* Acceleration 10 */ // more\n  VEL 5", "t.m")
    vel = [t for t in toks if t.value == "VEL"][0]
    assert (vel.loc.line, vel.loc.col) == (2, 3)


def test_nested_and_unterminated_comments_are_errors():
    """DG 6208: nested comments are not allowed."""
    with pytest.raises(CompileError, match="nested comments") as e:
        tokenize("/* a /* b */ c */", "t.m")
    assert e.value.diagnostic.loc.col == 6
    with pytest.raises(CompileError, match="unterminated comment") as e:
        tokenize("x = 1\n  /* open", "t.m")
    assert (e.value.diagnostic.loc.line, e.value.diagnostic.loc.col) == (2, 3)


def test_multiline_comment_keeps_following_line_numbers():
    toks = tokenize("a = 1 /* x\ny\nz */\nb = 2", "t.m")
    b = [t for t in toks if t.value == "B"][0]
    assert b.loc.line == 4


def test_directive_is_one_token_and_continuation_lines_are_joined():
    """DG 6827-6837: a line ending in a backslash continues on the next line."""
    toks = tokenize("#define X 1 \\\n + 2\nY", "t.m")
    assert toks[0].kind == DIRECTIVE and "+ 2" in toks[0].value
    y = [t for t in toks if t.value == "Y"][0]
    assert y.loc.line == 3


def test_strings_and_unexpected_characters():
    assert kinds('PRINT "a b"') == [(IDENT, "PRINT"), (STRING, "a b")]
    with pytest.raises(CompileError, match="missing closing"):
        tokenize('PRINT "abc', "t.m")
    with pytest.raises(CompileError, match=r"U\+2013 EN DASH\); write '-'") as e:
        tokenize("CANDEL \u20131", "t.m")
    assert e.value.diagnostic.loc.col == 8
    with pytest.raises(CompileError, match="invalid number '12ab'"):
        tokenize("x = 12ab", "t.m")
