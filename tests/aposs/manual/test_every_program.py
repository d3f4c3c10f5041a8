"""Every program of the manuals kept in this folder has a test of its behaviour (issue 17 item 9): a test module under
tests/ names its file. The programs that need what the simulation does not have yet are listed with the reason."""

from __future__ import annotations

from pathlib import Path

from .helpers import MANUAL

TESTS = MANUAL.parents[1]
# program → why its described behaviour is not asserted yet
AWAITING = {
    "C14_on_keypressed.m": "the LCP keypad (ON KEYPRESSED, INKEY) is not simulated",
}


def _test_sources() -> str:
    here = Path(__file__).resolve()
    return "\n".join(p.read_text(encoding="utf-8") for p in TESTS.rglob("*.py") if p.resolve() != here)


def test_every_manual_program_has_a_behaviour_test():
    sources = _test_sources()
    programs = sorted(p.name for p in MANUAL.glob("*.m"))
    missing = [name for name in programs if name not in AWAITING and f'"{name}"' not in sources]
    assert missing == [], "manual programs without a test that runs them"
    assert set(AWAITING) <= set(programs)


def test_the_awaiting_list_is_current():
    """A program that got its test leaves the list."""
    sources = _test_sources()
    assert [name for name in AWAITING if f'"{name}"' in sources] == []
