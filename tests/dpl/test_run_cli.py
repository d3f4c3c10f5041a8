"""`motiontool run FILE.dpl`: the program checked, downloaded over the APC Link and run in virtual time; timed
drive-parameter writes; traces by read-parameter alias, number or drive parameter; exit codes."""

from __future__ import annotations

import csv

from motiontool.cli import main
from tests.dpl.manual import PROGRAMS


def read_trace(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], [[int(v) for v in row] for row in rows[1:]]


def test_run_the_position_program_with_a_timed_set_point_and_a_trace(tmp_path, capsys):
    """§7.1 moved by `--set 18.11=50@100` (5 revolutions at 100 ms): the trace has one row per ms, the
    columns as named, and the axis ends exactly on the set point; stdout stays empty (DPL prints nothing)."""
    trace = tmp_path / "t.csv"
    code = main(["run", str(PROGRAMS / "s7_1_position.dpl"), "--seconds", "3", "--set", "18.11=50@100",
                 "--trace", str(trace), "--signals", "APC_FB_POS,92,18.12"])
    out = capsys.readouterr()
    assert (code, out.out, out.err) == (0, "", "")
    header, rows = read_trace(trace)
    assert header == ["time_ms", "APC_FB_POS", "92", "18.12"]
    assert [r[0] for r in rows] == list(range(1, 3001))
    assert rows[99][2] == 0 and rows[101][2] == 5 * 65536              # the set point arrives at 100 ms
    assert rows[-1][1:] == [5 * 65536, 5 * 65536, 50]


def test_the_run_command_of_the_drive_stops_and_restarts_the_apc(tmp_path):
    """#1.11 = 0 at 300 ms: the §6.4.2 interlock disables the APC ([4] APC_ENABLE_STATUS 0), 1 at 600 ms again."""
    trace = tmp_path / "t.csv"
    assert main(["run", str(PROGRAMS / "s6_4_speed.dpl"), "--seconds", "1", "--set", "18.13=1000",
                 "--set", "18.32=1", "--set", "1.11=0@300", "--set", "1.11=1@600", "--trace", str(trace),
                 "--signals", "APC_ENABLE_STATUS"]) == 0
    _, rows = read_trace(trace)
    enabled = {t: v for t, v in rows}
    assert (enabled[250], enabled[450], enabled[900]) == (1, 0, 1)


def test_check_errors_exit_1_and_run_time_errors_exit_2(tmp_path, capsys):
    bad = tmp_path / "bad.dpl"
    bad.write_text("Pos0{\nx% = Nope\n}\n", encoding="utf-8")
    assert main(["run", str(bad), "--seconds", "1"]) == 1
    assert capsys.readouterr().err == f"{bad}:2:6: error: unknown name 'Nope' (integer variables end with '%')\n"
    crash = tmp_path / "crash.dpl"
    crash.write_text("Initial {\nDIM A%[2]\n}\nPos0{\nn% = n% + 1\nA%[n%] = 1\n}\n", encoding="utf-8")
    assert main(["run", str(crash), "--seconds", "1"]) == 2
    assert capsys.readouterr().err == f"{crash}:6:1: error: index 2 is outside A%[0 … 1]\n"
    assert main(["run", str(crash), "--set", "18.11"]) == 1
    assert "--set needs MM.PP=VALUE or MM.PP=VALUE@MS" in capsys.readouterr().err


def test_a_ctsync_master_and_slave_run_on_one_line(tmp_path, capsys):
    """§7.5 on node 1 and §7.6 on node 2 (`--node 2:…`): #18.32 = 1 on the master sets control bit 0 and both
    drives lock to the master's broadcast and move alike; the columns are 'ID:SIGNAL'."""
    trace = tmp_path / "t.csv"
    code = main(["run", str(PROGRAMS / "s7_5_ctsync_master.dpl"), "--node", f"2:{PROGRAMS / 's7_6_ctsync_slave.dpl'}",
                 "--seconds", "6", "--set", "1:18.32=1@100", "--trace", str(trace),
                 "--signals", "APC_DIGLCK_MODE,APC_PROF_OUT_SPD,APC_RF_POS"])
    assert (code, capsys.readouterr().err) == (0, "")
    header, rows = read_trace(trace)
    assert header == ["time_ms", "1:APC_DIGLCK_MODE", "1:APC_PROF_OUT_SPD", "1:APC_RF_POS", "2:APC_DIGLCK_MODE",
                      "2:APC_PROF_OUT_SPD", "2:APC_RF_POS"]
    last = rows[-1]
    assert last[1] == last[4] == 1 and last[2] == last[5] > 0 and last[3] == last[6]
    assert main(["run", str(PROGRAMS / "s7_5_ctsync_master.dpl"), "--node", "2:slave.m"]) == 1
    assert "all of them .dpl" in capsys.readouterr().err
