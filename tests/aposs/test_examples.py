"""Every example program of the two MCO seeds passes `motiontool check` (issue 3), with the OCR repairs listed in
tests/aposs/manual/README.md — except the manual's own slips, kept as printed, which `check` reports where they stand
(issue 17); their corrected copies pass."""

import subprocess
import sys

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.aposs.image import ProgramImage

from .helpers import EXAMPLES

PROGRAMS = sorted(EXAMPLES.glob("*.m"))
# The manual's own slips that `motiontool check` reports, kept as printed (each has a *_corrected.m copy that runs as
# the manual describes; tests/aposs/manual/README.md): file → (line, the start of the message).
REPORTED_BY_CHECK = {
    "C06_hiperface.m": (11, "'ENCODEABSRES' is not a parameter name"),
    "C07_enctg_absolute_position.m": (13, "'ENCODEABSRES' is not a parameter name"),
    "F_C03_nowait_axend.m": (17, "unknown command 'WAIT'"),
}
VALID = [p for p in PROGRAMS if p.name not in REPORTED_BY_CHECK]
COMPLETE = [p for p in PROGRAMS if not p.name.startswith("F_") and "_corrected" not in p.name]


def test_all_complete_programs_of_the_manual_are_here():
    """Spec §9 lists 22 complete programs (C15 holds three)."""
    assert len(COMPLETE) >= 22


def test_every_slip_reported_by_check_has_a_corrected_copy():
    for name in REPORTED_BY_CHECK:
        assert (EXAMPLES / name.replace(".m", "_corrected.m")).exists(), name


@pytest.mark.parametrize("path", VALID, ids=[p.stem for p in VALID])
def test_example_compiles_without_errors(path):
    result = compile_source(path=path)
    assert result.ok, "\n".join(d.format() for d in result.diagnostics)
    again = ProgramImage.from_bytes(result.image.to_bytes())
    assert again == result.image


@pytest.mark.parametrize("name", sorted(REPORTED_BY_CHECK))
def test_the_manuals_slips_are_reported_by_check_where_they_stand(name):
    """Issue 17 item 9: a program the manual prints wrongly is kept as printed; `motiontool check` names the place."""
    line, message = REPORTED_BY_CHECK[name]
    errors = [d for d in compile_source(path=EXAMPLES / name).diagnostics if d.severity == "error"]
    assert errors and errors[0].loc.line == line and errors[0].message.startswith(message), \
        "\n".join(d.format() for d in errors)


def test_check_command_on_all_examples_exits_0_and_names_each_slip():
    proc = subprocess.run([sys.executable, "-m", "motiontool", "check", *map(str, VALID)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "error" not in proc.stdout
    slips = [EXAMPLES / name for name in sorted(REPORTED_BY_CHECK)]
    proc = subprocess.run([sys.executable, "-m", "motiontool", "check", *map(str, slips)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1
    for name, (line, message) in REPORTED_BY_CHECK.items():
        assert f"{name}:{line}:" in proc.stdout and message in proc.stdout, name
