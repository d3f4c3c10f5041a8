"""What LONG and DOUBLE arithmetic do beyond their range, at run time and in constants alike (issue 18, item 10;
decisions K80). Run as a user does: `motiontool run`."""

from __future__ import annotations

from motiontool import cli


def run(tmp_path, capsys, source: str) -> tuple[int, str, str]:
    path = tmp_path / "p.m"
    path.write_text(source, encoding="utf-8")
    code = cli.main(["run", str(path), "--seconds", "1"])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_long_arithmetic_wraps_like_the_32_bit_registers(tmp_path, capsys):
    """DG 6397: "Long word (32 bit): -2147483648 to +2147483647"; CR 266-288: APOSDIFF exists because positions
    wrap ("handling an overflow if necessary"). A constant and a run-time value wrap the same way."""
    code, out, err = run(tmp_path, capsys, "a = 2147483647\na = a + 1\nPRINT a\nPRINT 2147483647 + 1\n"
                                           "b = 65536\nPRINT b * b + 5\nPRINT 65536 * 65536 + 5\n")
    assert (code, err) == (0, "")
    assert out.splitlines() == ["-2147483648", "-2147483648", "5", "5"]


def test_double_overflow_is_error_156_at_run_time_as_in_a_constant(tmp_path, capsys):
    """The run-time product printed 'inf' while the same constant was a compile error. DG 11674-11680: error 156
    "Illegal double argument ... Mathematical error"; a DOUBLE result beyond the range is one (decisions K80), as
    is division by zero (L6) and exp beyond the range."""
    code, out, err = run(tmp_path, capsys, 'double d\nd = 1e300\nd = d * d\nPRINT "never ", d\n')
    assert (code, out, err) == (2, "", "error 156: Illegal double arg. (line 3)\n")
    code, out, err = run(tmp_path, capsys, "double d\nd = 1e300 * 1e300\n")
    assert code == 1 and "p.m:2:11: error: 1e+300 * 1e+300 overflows the DOUBLE range" in err
    code, out, err = run(tmp_path, capsys, "double d\nd = 1e308\nPRINT grad(d)\n")
    assert (code, err) == (2, "error 156: Illegal double arg. (line 3)\n")
