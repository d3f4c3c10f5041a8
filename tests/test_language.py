"""The toolkit both compilers share (motiontool.language, decisions A78): the same mistake gets the same message
from APOSS and DPL, in the same GCC format, at the same place."""

from __future__ import annotations

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.dpl.driver import check_source
from motiontool.dpl.lexer import tokenize as dpl_tokenize
from motiontool.language.tokens import Token

LOOKALIKES = {"\u2013": "EN DASH", "\u2014": "EM DASH", "\u201c": "LEFT DOUBLE QUOTATION MARK",
              "\u201d": "RIGHT DOUBLE QUOTATION MARK", "\u2018": "LEFT SINGLE QUOTATION MARK",
              "\u2019": "RIGHT SINGLE QUOTATION MARK", "\u00a0": "NO-BREAK SPACE"}


@pytest.mark.parametrize("ch", LOOKALIKES)
def test_a_typographic_character_gets_one_message_from_both_compilers(ch):
    aposs = compile_source(f"x = 1\ny = 2 {ch} 1\n", "p.m")
    dpl = check_source(f"x% = 1\ny% = 2 {ch} 1\n", "p.dpl")
    assert [d.format() for d in aposs.errors] == [f"p.m:2:7: error: {aposs.errors[0].message}"]
    assert [d.format() for d in dpl.errors] == [f"p.dpl:2:8: error: {dpl.errors[0].message}"]
    assert aposs.errors[0].message == dpl.errors[0].message
    assert aposs.errors[0].message.startswith(f"unexpected character '{ch}' (U+{ord(ch):04X} {LOOKALIKES[ch]}); write")


def test_the_en_dash_message_names_the_ascii_minus():
    result = check_source("x% = 2 \u2013 1\n", "p.dpl")
    assert [d.format() for d in result.errors] == \
        ["p.dpl:1:8: error: unexpected character '\u2013' (U+2013 EN DASH); write '-'"]


def test_dpl_tokens_are_the_shared_token_without_the_aposs_macro_fields():
    tokens = dpl_tokenize("x% = 1\n", "p.dpl")
    assert {type(t) for t in tokens} == {Token}
    assert not hasattr(tokens[0], "hide")
