"""Issue 26 item 5: DPL programs take the nesting the checker allows and the encodings APOSS programs take (a BOM,
CRLF, Latin-1), as the APOSS compiler does (decisions R17)."""

from __future__ import annotations

import pytest

from motiontool import cli
from motiontool.dpl.parser import MAX_NESTING


def _program(expression: str) -> str:
    return "Initial {\n    x% = " + expression + "\n}\n"


@pytest.mark.parametrize("depth", [90, MAX_NESTING])
def test_parentheses_up_to_the_limit_check_without_recursion_error(tmp_path, capsys, depth):
    program = tmp_path / "p.dpl"
    program.write_text(_program("(" * depth + "1" + ")" * depth))
    assert cli.main(["check", str(program)]) == 0
    assert capsys.readouterr().out == ""


def test_parentheses_beyond_the_limit_are_an_error_at_their_place(tmp_path, capsys):
    depth = MAX_NESTING + 1
    program = tmp_path / "p.dpl"
    program.write_text(_program("(" * depth + "1" + ")" * depth))
    assert cli.main(["check", str(program)]) == 1
    assert f"nested deeper than {MAX_NESTING} levels" in capsys.readouterr().out


@pytest.mark.parametrize("data", [
    b"\xef\xbb\xbfInitial {\r\n    x% = 1\r\n}\r\n",        # Windows editors: BOM and CRLF
    b"Initial {\r    x% = 1\r}\r",                         # old Mac line ends
    b"// M\xfcller\nInitial {\n    x% = 1\n}\n",           # Latin-1 comment of an old file
])
def test_files_in_the_encodings_aposs_programs_take_are_read(tmp_path, capsys, data):
    program = tmp_path / "p.dpl"
    program.write_bytes(data)
    assert cli.main(["check", str(program)]) == 0
    assert capsys.readouterr().out == ""
    assert program.read_bytes() == data
