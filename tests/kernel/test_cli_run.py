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


def _run_into_closed_pipe(tmp_path, source, *args, lines=1):
    """Start `motiontool run`, read `lines` lines of its stdout and close the pipe (like `| head -1`)."""
    program = tmp_path / "p.m"
    program.write_text(source)
    proc = subprocess.Popen([sys.executable, "-m", "motiontool", "run", str(program), *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    got = [proc.stdout.readline() for _ in range(lines)]
    proc.stdout.close()
    err = proc.stderr.read()
    proc.stderr.close()
    return got, proc.wait(timeout=120), err


LOOP = 'i = 0\nWHILE 1 DO\n  PRINT "line ", i\n  i = i + 1\n  DELAY 1\nENDWHILE\n'


def test_a_closed_stdout_ends_the_run_quietly(tmp_path):
    """Issue 17 item 6: `motiontool run … | head -1` — the reader goes away, the run ends without a traceback
    (with one controller and with several, --node)."""
    (tmp_path / "s.m").write_text("DELAY 20000\n")
    for extra in ([], ["--node", f"2:{tmp_path / 's.m'}"]):
        got, code, err = _run_into_closed_pipe(tmp_path, LOOP, "--seconds", "20", *extra)
        assert got[0].endswith("line 0\n")
        assert err == "" and code == 0


def test_a_pipe_closed_before_the_last_lines_are_flushed_ends_quietly(tmp_path):
    """The few lines of a short program sit in the output buffer until the end: the reader that left before
    then must not get a BrokenPipeError at exit either."""
    got, code, err = _run_into_closed_pipe(tmp_path, 'DELAY 200\nPRINT "a"\nPRINT "b"\n', lines=0)
    assert err == "" and code == 0
