"""`motiontool params` reads and writes FC 300 drive parameters by their LCP number (decision K124, docs/fc300.md):
the MCO parameter database does not hold them, the controller behind the link does."""

from __future__ import annotations

import pytest

from motiontool import cli


@pytest.mark.parametrize("link", [[], ["--link", "sim"]])
def test_params_gets_and_sets_fc300_parameters_by_lcp_number(capsys, link):
    assert cli.main(["params", *link, "--set", "3-03=60000", "--get", "4-13", "--get", "3-03", "--get", "32-60"]) == 0
    captured = capsys.readouterr()
    assert captured.err == ""
    assert captured.out.splitlines() == ["3-03 60000", "4-13 1500", "3-03 60000", "32-60 KPROP 30"]


@pytest.mark.parametrize(("args", "start"), [
    (["--get", "4-99"], "motiontool params: --get 4-99: error 112"),
    (["--set", "4-99=1"], "motiontool params: --set 4-99: error 112"),
    (["--set", "4-13=99999999"], "motiontool params: --set 4-13: error 183"),
    (["--set", "16-00=1"], "motiontool params: --set 16-00: error 112"),   # read only (DG 7594)
    (["--get", "4-13x"], "motiontool params: --get 4-13x: unknown parameter"),
])
def test_params_refuses_an_unknown_or_bad_fc300_parameter_in_one_line(capsys, args, start):
    assert cli.main(["params", "--link", "sim", *args]) == 1
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.startswith(start) and captured.err.count("\n") == 1, captured.err
    assert "Traceback" not in captured.err
