"""The manual's DPL programs (seed 004 §6.4, §7.1-§7.6) are the manual's text except for the OCR repairs each
fixture lists, and they pass the checks without a diagnostic."""

from __future__ import annotations

import pytest

from motiontool.dpl.driver import check_source
from tests.dpl.manual import SEED, fixture_paths, listed_repairs, repairs, seed_lines, source_ranges, split

FIXTURES = fixture_paths()


def test_every_program_of_the_manual_is_a_fixture():
    names = {p.stem for p in FIXTURES}
    assert names == {"s6_4_position", "s6_4_speed", "s6_4_cam", "s6_4_diglock", "s7_1_position",
                     "s7_2_flying_shear", "s7_3_cam", "s7_4_homing", "s7_5_ctsync_master", "s7_6_ctsync_slave"}


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_the_header_lists_exactly_the_repairs(path):
    """"unchanged except for OCR repairs (each listed in a header comment)" (issue 20): the diff between the
    seed's lines and the program is exactly the header's list, so no change can go unlisted."""
    header, program = split(path.read_text(encoding="utf-8"))
    assert listed_repairs(header) == repairs(source_ranges(header), program)


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_the_programs_check_without_diagnostics(path):
    result = check_source(path=path)
    assert [d.format() for d in result.diagnostics] == []
    assert result.program is not None


@pytest.mark.skipif(not SEED.exists(), reason="the seed (vendor manual) is not on this machine")
def test_the_kept_excerpt_is_the_seeds_text():
    seed = SEED.read_text(encoding="utf-8").split("\n")
    assert all(seed[n - 1] == text for n, text in seed_lines().items())
