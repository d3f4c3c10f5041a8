"""The measure language: parsed without eval, one number per run, errors with their position."""

import contextlib
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from motiontool.sweep.measures import EvaluationError, MeasureError, evaluate, format_value, parse

T = np.arange(6, dtype=float)
SIGNALS = {"APOS": np.array([0.0, 50, 95, 105, 99, 100]), "TRACKERR": np.array([0.0, -7, 3, 2, -1, 0]),
           "32-60": np.full(6, 40.0)}


def value(text: str) -> float:
    return evaluate(parse(text), T, SIGNALS)


@pytest.mark.parametrize("text, expected", [
    ("max(abs(TRACKERR))", 7), ("min(TRACKERR)", -7), ("first(APOS)", 0), ("last(APOS)", 100),
    ("final(APOS)", 100), ("mean(APOS)", 449 / 6), ("rms(TRACKERR)", math.sqrt(63 / 6)),
    ("max(APOS) - min(APOS)", 105), ("-2 * -3 + 4 / 2", 8), ("max([32-60]) / 8", 5),
    ("MAX(abs(TRACKERR - 1))", 8), ("settle_time(APOS, 100, 5)", 2), ("settle_time(APOS, 100, 4)", 4),
    ("settle_time(APOS, 100, 0)", 5),
    ("settle_time(APOS, 0, 1e9)", 0), ("settle_time(APOS, 200, 5)", math.nan), ("max(APOS - 2 * APOS)", 0),
])
def test_values(text, expected):
    got = value(text)
    assert (math.isnan(got) and math.isnan(expected)) or got == pytest.approx(expected)


def test_signals_are_listed_once_in_order():
    assert parse("max(TRACKERR) + settle_time(APOS, 1, 2) - min(TRACKERR) + last([4097])").signals == \
        ("TRACKERR", "APOS", "4097")


@pytest.mark.parametrize("text, position, words", [
    ("APOS", 1, "a measure is one number"), ("max(APOS", 9, "expected ')'"), ("max(APOS))", 10, "unexpected ')'"),
    ("foo(APOS)", 1, "unknown function foo()"), ("max(APOS, 2)", 1, "takes 1 argument"),
    ("settle_time(APOS, 1)", 1, "takes 3 arguments"), ("settle_time(3, 1, 2)", 13, "needs a signal first"),
    ("settle_time(APOS, APOS, 2)", 19, "are numbers, not signals"), ("max(APOS) $", 11, "unexpected character"),
    ("1e999", 1, "too large"), ("", 1, "empty"), ("max + 1", 1, "max is a function"),
    ("(" * 60 + "1" + ")" * 60, 51, "nested deeper"), ("max(abs)", 5, "abs is a function"),
])
def test_errors_name_the_position(text, position, words):
    with pytest.raises(MeasureError) as caught:
        parse(text)
    assert caught.value.position == position
    assert words in str(caught.value)


def test_a_measure_without_a_value_for_a_run_is_an_evaluation_error():
    with pytest.raises(EvaluationError, match="division by zero"):
        value("max(APOS) / first(APOS)")
    with pytest.raises(EvaluationError, match="TOLERANCE -1 is below 0"):
        value("settle_time(APOS, 1, -1)")
    with pytest.raises(EvaluationError, match="no samples"):
        evaluate(parse("max(APOS)"), T[:0], {"APOS": T[:0]})


def test_format_is_the_same_everywhere():
    assert [format_value(v) for v in (7.0, -0.0, 0.1 + 0.2, math.nan, -math.inf, 2.0 ** 60)] == \
        ["7", "0", "0.30000000000000004", "nan", "-inf", "1.152921504606847e+18"]


TOKENS = st.sampled_from(["max", "min", "abs", "settle_time", "rms", "(", ")", ",", "-", "+", "*", "/", "APOS",
                          "[32-60]", "[", "]", "1", "2.5", "1e400", ".", " ", "e", "٥", "\x00", "last"])


@given(st.one_of(st.text(max_size=200), st.lists(TOKENS, max_size=80).map("".join)))
def test_the_parser_raises_nothing_but_its_own_error(text):
    try:
        measure = parse(text)
    except MeasureError as exc:
        assert 1 <= exc.position <= len(text) + 1 and "\n" not in str(exc)
        return
    with contextlib.suppress(EvaluationError):  # what parses evaluates to one number or its own error
        evaluate(measure, T, {name: SIGNALS["APOS"] for name in measure.signals})
