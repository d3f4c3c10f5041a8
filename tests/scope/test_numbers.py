"""Scope numbers without Qt (issue 23 item 8): grouped values, times in s or ms, colours that are not reused,
Tune runs on the time base of a TESTSETP set already shown (decisions S15, S32)."""

from motiontool.controller.embedded import EmbeddedLink
from motiontool.scope.acquisition import list_testsetp, load_testsetp
from motiontool.scope.curves import Curve, Scope
from motiontool.scope.numbers import GROUP, time_text, time_ticks, value_text
from motiontool.scope.tune import Tune
from tests.scope.test_acquisition import TESTSETP, start


def test_values_are_grouped_never_scientific():
    assert value_text(1_324_400.0) == f"1{GROUP}324{GROUP}400"
    assert value_text(-12.3456789) == "-12.3457"
    assert value_text(0.000123456) == "0.000123456"
    assert value_text(2.5) == "2.5" and value_text(-0.0) == "0"
    assert all("e" not in value_text(v) for v in (1e9 + 0.5, 3e-7, 12345.678))


def test_times_are_seconds_from_2_s_on_else_milliseconds():
    assert time_ticks([0.0, 2000.0, 4000.0], 2000.0, "s") == ["0", "2", "4"]
    assert time_ticks([0.0, 250.0, 500.0], 250.0, "ms") == ["0", "250", "500"]
    assert time_ticks([19_234_500.0, 19_235_000.0], 500.0, "s") == [f"19{GROUP}234.5", f"19{GROUP}235.0"]
    assert time_text(1250.0) == f"1{GROUP}250.0 ms" and time_text(4321.0) == "4.321 s"


def test_a_removed_curves_colour_is_given_again_before_one_in_use():
    scope = Scope("free_run")
    for name in "abc":
        scope.add_curve(Curve(name))
    scope.remove_curve("a")
    scope.add_curve(Curve("d"))
    scope.add_curve(Curve("e"))
    assert len({c.colour for c in scope.curves}) == 4


def test_a_tune_run_lands_on_the_time_base_of_a_testsetp_set_shown_before():
    """DG 4737: recorded times are the controller's clock; a Tune run and a TESTSETP set in one window must be
    read against one time axis, not 5 hours apart."""
    link = EmbeddedLink()
    link.service.controller.time_ms = 5 * 3_600_000
    start(link, TESTSETP)
    link.advance(3000)
    scope = Scope("testsetp")
    first = load_testsetp(scope, link, list_testsetp(link)[-1].index)[0]
    result = Tune(scope, link).run_synchronously()
    run = scope.curve(result.curves[0])
    assert run.raw()[0][0] == first.raw()[0][0]
    assert run.source.info["recorded_at_ms"] > 5 * 3_600_000   # the controller time stays in the Source info
