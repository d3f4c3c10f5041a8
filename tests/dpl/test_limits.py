"""Bad numbers in a DPL program are diagnostics with their place, never a Python exception (issue 18, items 4 and 8;
decisions L22, R5): a 5 000-digit constant ended `motiontool check` in ValueError (found by benchmarks/fuzz_files.py),
other scripts' digits were read as numbers."""

from __future__ import annotations

import pytest

from motiontool import cli

HEAD = "Initial {\n    x% = "
TAIL = "\n}\n"


@pytest.mark.parametrize(("constant", "message"), [
    ("9" * 5000, "is outside the integer range"),
    ("1" + "0" * 30, "is outside the integer range"),
    ("1e999", "is outside the floating-point range"),
    ("\u0665\u0660", "unexpected character '\u0665'"),
])
def test_a_bad_constant_is_an_error_at_its_place(tmp_path, capsys, constant, message):
    program = tmp_path / "p.dpl"
    program.write_text(HEAD + constant + TAIL, encoding="utf-8")
    assert cli.main(["check", str(program)]) == 1
    out = capsys.readouterr().out
    assert f"{program}:2:10: error: " in out and message in out
    assert len(out) < 400  # the constant is not echoed whole


def test_constants_that_fit_still_read(tmp_path, capsys):
    program = tmp_path / "p.dpl"
    program.write_text(HEAD + "000000000000002147483647\n    y% = 0x00000000000000FF" + TAIL,
                       encoding="utf-8")
    assert cli.main(["check", str(program)]) == 0, capsys.readouterr().out


def test_a_device_or_pipe_is_refused_as_a_dpl_program(tmp_path, capsys):
    """`check x.dpl` read a FIFO until a writer came (forever) and a device until memory ran out."""
    import os

    fifo = tmp_path / "pipe.dpl"
    os.mkfifo(fifo)
    assert cli.main(["check", str(fifo)]) == 1
    assert f"{fifo}:1:1: error: cannot read the file: not a regular file" in capsys.readouterr().out
