"""Bad output paths and bad options on the command line: `cannot write PATH: reason` / a clear message, exit 1,
found before a long run starts; `run --trace` streams its rows to the file (issue 18, items 3, 8, 9)."""

from __future__ import annotations

import subprocess
import sys
import time

import pytest

from motiontool import cli

LOOP = "main:\nDELAY 10\nGOTO main\n"


def program(tmp_path, text: str = 'PRINT "hello"\n'):
    path = tmp_path / "p.m"
    path.write_text(text, encoding="utf-8")
    return path


def motiontool(*args, timeout: float = 60):
    return subprocess.run([sys.executable, "-m", "motiontool", *map(str, args)], capture_output=True, text=True,
                          timeout=timeout)


@pytest.mark.parametrize(("make", "reason"), [
    (lambda d: d / "missing" / "x.img", "No such file or directory"),
    (lambda d: d, "Is a directory"),
    (lambda d: d / "p.m" / "x.img", "Not a directory"),
])
def test_compile_to_a_bad_output_path(tmp_path, capsys, make, reason):
    """`compile -o /nonexistent/dir/x.img` and `compile -o somedir` ended in tracebacks."""
    source = program(tmp_path)
    target = make(tmp_path)
    assert cli.main(["compile", str(source), "-o", str(target)]) == 1
    assert capsys.readouterr().err == f"motiontool compile: cannot write {target}: {reason}\n"


def test_run_refuses_bad_trace_and_record_paths_before_it_starts(tmp_path, capsys):
    """`run --trace /nonexistent/x.csv` failed after the whole run; `run --record somedir` in a traceback."""
    source = program(tmp_path, LOOP)
    start = time.perf_counter()
    assert cli.main(["run", str(source), "--seconds", "3600", "--trace", str(tmp_path / "no" / "x.csv")]) == 1
    assert time.perf_counter() - start < 5  # an hour of virtual time was not run first
    assert capsys.readouterr().err == f"motiontool run: cannot write {tmp_path}/no/x.csv: No such file or directory\n"
    (tmp_path / "somedir").mkdir()
    assert cli.main(["run", str(source), "--seconds", "3600", "--record", str(tmp_path / "somedir")]) == 1
    assert capsys.readouterr().err == f"motiontool run: cannot write {tmp_path}/somedir: Is a directory\n"
    (tmp_path / "rec-node2.csv").mkdir()
    assert cli.main(["run", "--node", f"1:{source}", "--node", f"2:{source}", "--seconds", "3600",
                     "--record", str(tmp_path / "rec.csv")]) == 1
    assert capsys.readouterr().err == f"motiontool run: cannot write {tmp_path}/rec-node2.csv: Is a directory\n"


@pytest.mark.parametrize(("options", "message"), [
    (["--set", "KPROP=abc"], "--set KPROP=abc: give a whole number (or 0x hex) from -2147483648 to 4294967295"),
    (["--set", "FOO=5"], "--set FOO=5: error 112: Unknown param. (parameter FOO)"),
    (["--set", "KPROP=99999999"], "--set KPROP=99999999: error 183: Invalid argument (32-60 KPROP: 99999999 is "
                                  "outside 0..100000)"),
    (["--set", "KPROP=\u0665"], "--set KPROP=\u0665: give a whole number (or 0x hex) from -2147483648 to 4294967295"),
    (["--set", "1:KPROP=5"], "--set 1:KPROP=5: 'ID:' picks a controller, which needs --node (several controllers); "
                             "for the one controller write --set KPROP=5"),
    (["--input", "999=1"], "--input 999=1: no digital input 999 (MCO 305: 1-12, FC 300: 18-33; analog: 53, 54)"),
    (["--input", "0=1"], "--input 0=1: no digital input 0 (MCO 305: 1-12, FC 300: 18-33; analog: 53, 54)"),
    (["--input", "1=5"], "--input 1=5: a digital input is 0 or 1, not 5"),
    (["--input", "1=1@99999999"], "--input 1=1@99999999: 99999999 ms is after the end of the run (--seconds 60)"),
    (["--input", "2:1=1"], "--input 2:1=1: 'ID:' picks a controller, which needs --node (several controllers); for "
                           "the one controller write --input 3=1@100"),
    (["--seconds", "inf"], "--seconds inf: give a number above 0 and at most 864000"),
    (["--seconds", "nan"], "--seconds nan: give a number above 0 and at most 864000"),
    (["--seconds", "0"], "--seconds 0: give a number above 0 and at most 864000"),
    (["--interval", "0", "--trace", "t.csv"], "--interval 0: give a whole number from 1 to 3600000"),
])
def test_bad_run_options_are_refused_with_exit_1(tmp_path, capsys, options, message):
    """`--input 999=1`, `0=1`, `1=5` and absurd times were accepted silently; an unknown --set exited 2 (as if the
    controller had failed) and `--set 1:KPROP=5` without --node said "Unknown param"."""
    assert cli.main(["run", str(program(tmp_path)), *options]) == 1
    out = capsys.readouterr()
    assert out.err == f"motiontool run: {message}\n"
    assert out.out == ""  # nothing ran


def test_every_command_line_error_exits_1(tmp_path):
    """argparse's own errors exited 2 - the code `run` gives a controller error - and ours 1."""
    source = program(tmp_path)
    for args in (["run", source, "--seconds", "x"], ["run", source, "--bogus"], ["compile", source],
                 ["cam", "build", "-o", tmp_path / "c.zbc"], ["run", source, "--set", "FOO=5"]):
        proc = motiontool(*args)
        assert proc.returncode == 1, (args, proc.stderr)
        assert "Traceback" not in proc.stderr
    proc = motiontool("run", program(tmp_path, "SET SWPOSLIMACT 1\nPOSA 600000\n"))
    assert proc.returncode == 2  # a controller error keeps its own code


@pytest.mark.slow  # several seconds on an idle machine: make test runs it, make test-fast does not
def test_trace_rows_go_to_the_file_while_the_program_runs(tmp_path):
    """`run --trace` kept every row in memory (~1.8 GB per hour of 1 ms rows) and wrote them at the end. Now the
    rows stream into a temporary file beside the target, which becomes the trace when the run is complete."""
    source, trace = program(tmp_path, LOOP), tmp_path / "trace.csv"
    proc = subprocess.Popen([sys.executable, "-m", "motiontool", "run", str(source), "--seconds", "4", "--realtime",
                             "--trace", str(trace)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    sizes = []
    try:
        deadline = time.monotonic() + 60
        while proc.poll() is None and time.monotonic() < deadline:
            partial = list(tmp_path.glob(".trace.csv.*.tmp"))
            if partial:
                assert not trace.exists()  # the trace appears only complete
                sizes.append(partial[0].stat().st_size)
            time.sleep(0.2)
    finally:
        proc.wait(timeout=60)
    assert proc.returncode == 0, proc.stderr
    growing = [s for s in sizes if s > 0]
    assert len(set(growing)) >= 3, sizes  # rows arrived in the file during the run
    rows = trace.read_text().splitlines()
    assert rows[0] == "time_ms,APOS,CPOS,TRACKERR" and len(rows) > 4000  # --realtime stops after about 4 s
    times = [int(r.split(",")[0]) for r in rows[1:]]
    assert times == list(range(times[0], times[0] + len(times)))  # every ms, none lost (the clock ran before)
    assert not list(tmp_path.glob(".trace.csv.*.tmp"))


def test_multi_node_trace_is_merged_by_time(tmp_path, capsys):
    source, trace = program(tmp_path, LOOP), tmp_path / "trace.csv"
    assert cli.main(["run", "--node", f"1:{source}", "--node", f"3:{source}", "--seconds", "0.5", "--trace",
                     str(trace), "--signals", "APOS"]) == 0
    rows = trace.read_text().splitlines()
    assert rows[0] == "time_ms,1:APOS,3:APOS" and len(rows) == 501
    assert rows[1] == "1,0,0" and rows[-1] == "500,0,0"
