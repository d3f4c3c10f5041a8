"""search.py: the manual's Find/Replace pattern syntax, plain and regex modes, Find in Files (Qt-free)."""

from __future__ import annotations

import contextlib
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.ui.editor import search
from motiontool.ui.editor.search import Hit, PatternError, SearchOptions

PATTERN = SearchOptions(mode="pattern", match_case=True)


def matches(pattern: str, text: str, options: SearchOptions = PATTERN) -> list[str]:
    return [text[h.start:h.end] for h in search.find_all(text, pattern, options)]


# --- the manual's examples [DG L2316-2324] = ide-spec 1.34 --------------------------------------------------

def test_literal_10():
    """DG L2318: '10  Search for the string "10".'"""
    assert matches("10", "x = 10 + 210") == ["10", "10"]


def test_plus_one_or_more():
    """DG L2319: '10+  Search for "1" followed by at least one "0" (e.g. 10, 100, 1000, etc.).'"""
    assert matches("10+", "1 10 100 1000 2") == ["10", "100", "1000"]


def test_star_zero_or_more():
    """DG L2320: '10*  Search for "1" followed by zero or more "0" characters (e.g. 1, 10, 100, 1000, etc.).'"""
    assert matches("10*", "1 10 100 1000 2") == ["1", "10", "100", "1000"]


def test_character_set():
    """DG L2321: 'vel[xyz]  Search for "velx", "vely", or "velz".'"""
    assert matches("vel[xyz]", "velx vely velz vela") == ["velx", "vely", "velz"]


def test_character_range():
    """DG L2322: 'vel[1-3]  Search for "vel1", "vel2", or "vel3".'"""
    assert matches("vel[1-3]", "vel0 vel1 vel2 vel3 vel4") == ["vel1", "vel2", "vel3"]


def test_or_of_groups():
    """DG L2323: '(vel) (acc)  Search for "vel" or "acc".' — the OCR lost the pipe: (vel)|(acc) (ide-spec 1.34)."""
    assert matches("(vel)|(acc)", "vel = acc + dec") == ["vel", "acc"]


def test_assignment_with_blanks_and_tabs():
    """DG L2324: 'vel[ \\t]*=  Search for "vel", followed by any number of spaces or tabs, followed by "="'."""
    text = "vel=1\nvel \t = 2\nvel == 3\nvelocity = 4\nIF vel > 2"
    assert matches(r"vel[ \t]*=", text) == ["vel=", "vel \t =", "vel ="]


def test_question_mark_is_any_single_character():
    """DG L2310: '? for any single character'."""
    assert matches("P?SA", "POSA PSA P-SA") == ["POSA", "P-SA"]
    assert matches("a?b", "a\nb") == []  # not across a line break


def test_escapes():
    """DG L2314: 'Sequences such as \\t, etc. will be substituted for an equivalent single character. \\\\ represents
    the backslash.'"""
    assert matches(r"a\tb", "a\tb ab") == ["a\tb"]
    assert matches(r"c:\\x", r"c:\x") == ["c:\\x"]
    assert matches(r"\?\+\*\[\(", "?+*[(") == ["?+*[("]


def test_translation_table():
    assert search.translate_pattern("10+") == "10+"
    assert search.translate_pattern("a?c") == "a.c"
    assert search.translate_pattern("x.y") == r"x\.y"  # '.' is an ordinary character
    assert search.translate_pattern("+a") == r"\+a"  # nothing to repeat: literal
    assert search.translate_pattern("[^0-9]") == "[^0-9]"
    assert search.translate_pattern("[a-]") == r"[a\-]"


@pytest.mark.parametrize("bad", ["(vel", "vel)", "[abc", "a|(b"])
def test_malformed_patterns_raise(bad):
    with pytest.raises(PatternError):
        search.compile_search(bad, PATTERN)


# --- options -------------------------------------------------------------------------------------------------

def test_match_case_and_whole_word():
    text = "POSA posa POSA_X xposa"
    assert matches("posa", text, SearchOptions()) == ["POSA", "posa", "POSA", "posa"]
    assert matches("posa", text, SearchOptions(match_case=True)) == ["posa", "posa"]
    assert matches("posa", text, SearchOptions(whole_word=True)) == ["POSA", "posa"]


def test_plain_mode_is_literal_and_regex_mode_is_python():
    assert matches("a+b", "a+b aab", SearchOptions()) == ["a+b"]
    assert matches(r"a+b", "a+b aab", SearchOptions(mode="regex")) == ["aab"]
    with pytest.raises(PatternError):
        search.compile_search("(", SearchOptions(mode="regex"))


def test_find_down_up_and_wrap():
    text = "ab ab ab"
    assert search.find(text, "ab", 1) == Hit(3, 5)
    assert search.find(text, "ab", 7) == Hit(0, 2, wrapped=True)
    assert search.find(text, "ab", 7, SearchOptions(wrap=False)) is None
    up = SearchOptions(backward=True)
    assert search.find(text, "ab", 6, up) == Hit(3, 5)
    assert search.find(text, "ab", 0, up) == Hit(6, 8, wrapped=True)
    assert search.find(text, "ab", 0, SearchOptions(backward=True, wrap=False)) is None


def test_empty_matches_are_skipped():
    assert matches("x*", "ab xx c") == ["xx"]
    assert search.find("abc", "x*", 0, PATTERN) is None


def test_replace_all_modes():
    assert search.replace_all("vel1 vel2", "vel[0-9]", "speed", PATTERN) == ("speed speed", 2)
    assert search.replace_all("a b", " ", r"\t", PATTERN) == ("a\tb", 1)
    assert search.replace_all("a b", " ", r"\t", SearchOptions()) == ("a\\tb", 1)
    assert search.replace_all("vel1", r"vel(\d)", r"acc\1", SearchOptions(mode="regex")) == ("acc1", 1)


# --- property: plain search (and escaped pattern search) finds what str.find finds ----------------------------

_TEXT = st.text(alphabet=st.sampled_from(list("ab?+*[]|()\\\t .10-^$\n")), max_size=40)


@settings(max_examples=300, deadline=None)
@given(text=_TEXT, needle=_TEXT.filter(bool), pos=st.integers(0, 45))
def test_plain_search_finds_what_str_find_finds(text, needle, pos):
    opts = SearchOptions(match_case=True, wrap=False)
    hit = search.find(text, needle, pos, opts)
    expected = text.find(needle, min(pos, len(text)))
    assert (hit.start if hit else -1) == expected
    escaped = search.find(text, search.escape_pattern(needle), pos, SearchOptions("pattern", True, wrap=False))
    assert (escaped.start if escaped else -1) == expected
    if hit:
        assert text[hit.start:hit.end] == needle


@settings(max_examples=200, deadline=None)
@given(text=_TEXT, needle=_TEXT.filter(bool))
def test_plain_replace_all_equals_str_replace(text, needle):
    new, count = search.replace_all(text, needle, "<>", SearchOptions(match_case=True))
    assert new == text.replace(needle, "<>")
    assert count == text.count(needle)


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=12).filter(bool))
def test_pattern_translation_never_crashes_with_re_error(pattern):
    with contextlib.suppress(PatternError):  # a clean error for the dialog, never re.error
        search.compile_search(pattern, PATTERN)


# --- Find in Files (ide-spec 1.36) -----------------------------------------------------------------------------

def test_find_in_files(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "a.m").write_text("POSA 10\n// posa in a comment\n", encoding="utf-8")
    (tmp_path / "sub" / "b.m").write_bytes("x = 1\n\tPOSA 20 // M\xfcller\n".encode("cp1252"))
    (tmp_path / "c.txt").write_text("POSA 30\n", encoding="utf-8")
    hits = search.find_in_files(tmp_path, "posa")
    assert [(h.path.name, h.line, h.col) for h in hits] == [("a.m", 1, 1), ("a.m", 2, 4), ("b.m", 2, 2)]
    assert hits[2].text == "\tPOSA 20 // M\xfcller"
    assert search.find_in_files(tmp_path, "POSA", "*.txt")[0].path.name == "c.txt"
    assert len(search.find_in_files(tmp_path, "POSA", options=SearchOptions(match_case=True))) == 2
    pattern_hits = search.find_in_files(tmp_path, "POSA [0-9]+", options=PATTERN)
    assert [h.text.strip()[:7] for h in pattern_hits] == ["POSA 10", "POSA 20"]
    assert all(isinstance(h, tuple) and len(h) == 4 for h in hits)


def test_find_in_files_escapes_regex_characters_in_plain_mode(tmp_path):
    (tmp_path / "a.m").write_text("x = (a+b)\n", encoding="utf-8")
    assert [h.col for h in search.find_in_files(tmp_path, "(a+b)")] == [5]
    assert re.escape("(a+b)") != "(a+b)"
