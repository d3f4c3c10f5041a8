"""`motiontool run`: stdout is exactly the PRINT output, stderr the controller errors; exit 0/1/2."""

import subprocess
import sys


def run_cli(tmp_path, source, *args):
    program = tmp_path / "p.m"
    program.write_text(source)
    return subprocess.run([sys.executable, "-m", "motiontool", "run", str(program), *args],
                          capture_output=True, text=True, timeout=120)


def test_stdout_is_exactly_the_print_output(tmp_path):
    proc = run_cli(tmp_path, 'PRINT "hello"\nPRINT 1, " ", 2\n')
    assert proc.returncode == 0
    assert proc.stdout == "hello\n1 2\n"
    assert proc.stderr == ""


def test_compile_error_exits_1(tmp_path):
    proc = run_cli(tmp_path, "POSA\n")
    assert proc.returncode == 1
    assert "p.m:1:1: error: POSA needs more arguments" in proc.stderr
    assert proc.stdout == ""


def test_unhandled_controller_error_exits_2_with_line(tmp_path):
    proc = run_cli(tmp_path, 'PRINT "start"\nSET SWPOSLIMACT 1\nPOSA 600000\nPRINT "never"\n')
    assert proc.returncode == 2
    assert proc.stdout == "start\n"
    assert proc.stderr.strip() == "error 111: SW end limit (line 3)"


def test_set_input_and_trace(tmp_path):
    trace = tmp_path / "trace.csv"
    proc = run_cli(tmp_path, "WAITI 2 ON\nPRINT TIME\nVEL 100\nACC 100\nDEC 100\nPOSA 1000\n", "--input", "2=1@250",
                   "--set", "KPROP=60", "--set", "32-61=0", "--trace", str(trace), "--signals", "APOS,CPOS,TRACKERR",
                   "--seconds", "1")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() in ("250", "251")
    rows = trace.read_text().splitlines()
    assert rows[0] == "time_ms,APOS,CPOS,TRACKERR"
    assert len(rows) > 300 and rows[1].startswith("1,")


def test_time_limit_ends_a_running_program(tmp_path):
    proc = run_cli(tmp_path, "main:\nDELAY 10\nGOTO main\n", "--seconds", "0.5")
    assert proc.returncode == 0
