"""TESTSETP recording (DG 7112-7135, 5336) and `motiontool run --record`."""

import subprocess
import sys

from .helpers import run_source

PROGRAM = """
DIM test[3000]
VEL 100
ACC 100
DEC 100
TESTSETP 1 4097 4098 4102 test
TESTSTART 500
POSA 20000
DELAY 100
PRINT test[1], " ", test[2]
"""


def test_testsetp_records_into_the_array_every_ms():
    """DG 5336: TESTSETP 1 4097 4098 … test records REG_ACTPOS, REG_COMPOS … every 1 ms into 'test'."""
    run = run_source(PROGRAM, 3000)
    rec = run.link.call("upload_recording", index=0)
    assert rec["names"] == ["REG_ACTPOS", "REG_COMPOS", "REG_TRACKERR"]
    assert len(rec["samples"]) == 500
    data = run.controller.arrays.arrays[0].data
    assert data[:3] == rec["samples"][0] and data[3:6] == rec["samples"][1]  # interleaved (decision K4)
    compos = [s[1] for s in rec["samples"]]
    assert compos == sorted(compos) and compos[-1] > 0


def test_array_too_small_for_the_recording_is_171():
    run = run_source("DIM t[10]\nTESTSETP 1 4097 4098 4102 t\nTESTSTART 5\n", 100)
    assert run.errors[0].number == 171


def test_more_than_20_indices_is_195():
    indices = ", ".join(str(4097 + i) for i in range(21))
    run = run_source(f"TESTSETINDEX {indices}\n", 100)
    assert run.errors[0].number == 195


def test_cli_record_writes_csv(tmp_path):
    program = tmp_path / "rec.m"
    program.write_text(PROGRAM)
    out = tmp_path / "rec.csv"
    proc = subprocess.run([sys.executable, "-m", "motiontool", "run", str(program), "--seconds", "2",
                           "--record", str(out)], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    lines = out.read_text().splitlines()
    assert lines[0] == "time_ms,REG_ACTPOS [4097],REG_COMPOS [4098],REG_TRACKERR [4102]"
    assert len(lines) == 501
