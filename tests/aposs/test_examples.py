"""Every example program of the two MCO seeds passes `motiontool check` (issue 3), with the OCR repairs
listed in tests/aposs/manual/README.md."""

import subprocess
import sys

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.aposs.image import ProgramImage

from .helpers import EXAMPLES

PROGRAMS = sorted(EXAMPLES.glob("*.m"))
COMPLETE = [p for p in PROGRAMS if not p.name.startswith("F_")]


def test_all_complete_programs_of_the_manual_are_here():
    """Spec §9 lists 22 complete programs (C15 holds three)."""
    assert len(COMPLETE) >= 22


@pytest.mark.parametrize("path", PROGRAMS, ids=[p.stem for p in PROGRAMS])
def test_example_compiles_without_errors(path):
    result = compile_source(path=path)
    assert result.ok, "\n".join(d.format() for d in result.diagnostics)
    again = ProgramImage.from_bytes(result.image.to_bytes())
    assert again == result.image


def test_check_command_on_all_examples_exits_0():
    proc = subprocess.run([sys.executable, "-m", "motiontool", "check", *map(str, PROGRAMS)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "error" not in proc.stdout
