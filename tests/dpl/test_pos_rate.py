"""A POS rate set with #81.12 + REINIT (Table 6-3 L4685, Figure 6-3 L4708-4719) acts from the next sample on, in
`motiontool run`, on the Link the IDE uses and on a CTSync line: the tasks run at the rate [13] reports
("13 Pos Task Sample Time", L7711). Before issue 29 item 2 the CLI took it up to 50 ms late, running a 2 ms
program every 1 ms."""

from __future__ import annotations

import csv

from motiontool.apc import ApcDrive
from motiontool.cli import main
from motiontool.controller.dpl_program import dpl_link
from motiontool.dpl.image import DplImage

# Pos0 counts its runs into #18.11, Background its passes into #18.12; Background takes #81.12 = 5 (4 ms) when
# #18.30 = 1
PROGRAM = """Initial {
#81.12 = 4
REINIT
}
Background {
top:
b% = b% + 1
#18.12 = b%
IF #18.30 = 1 THEN
    #18.30 = 0
    #81.12 = 5
    REINIT
ENDIF
goto top:
}
Pos0 {
n% = n% + 1
#18.11 = n%
}
"""


def changes(path, column: str) -> tuple[list[int], list[list[int]]]:
    """The times (ms) at which `column` of a trace changed, and the rows."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    index = rows[0].index(column)
    data = [[int(v) for v in row] for row in rows[1:]]
    return [b[0] for a, b in zip(data, data[1:], strict=False) if b[index] != a[index]], data


def spacing(times: list[int]) -> set[int]:
    return {b - a for a, b in zip(times, times[1:], strict=False)}


def test_run_takes_the_initial_tasks_pos_rate_from_the_first_sample(tmp_path):
    """Figure 6-3's `#81.12 = …` + REINIT in Initial (here 4 = 2 ms): Pos0 runs every 2 ms from its first run,
    and [13] says 3 (2 ms) throughout; the Background loop makes one pass between two samples (decision A60)."""
    program, trace = tmp_path / "rate.dpl", tmp_path / "t.csv"
    program.write_text(PROGRAM, encoding="utf-8")
    assert main(["run", str(program), "--seconds", "0.2", "--trace", str(trace), "--signals", "13,18.11,18.12"]) == 0
    times, rows = changes(trace, "18.11")
    assert spacing(times) == {2} and rows[-1][2] == 100 and rows[-1][3] == 99
    assert {row[1] for row in rows} == {3}


def test_a_rate_changed_while_running_acts_at_the_next_sample_on_one_drive_and_a_ctsync_line(tmp_path, capsys):
    """REINIT in Background with #81.12 = 5 (4 ms) at 50 ms: the next Pos0 run is 4 ms after the last one, and
    every one after; on a CTSync line of two nodes the same, in lockstep (L2071 "All CTSync Master and Slave POS
    tasks must be set to the same update time")."""
    program, trace = tmp_path / "rate.dpl", tmp_path / "t.csv"
    program.write_text(PROGRAM, encoding="utf-8")
    assert main(["run", str(program), "--seconds", "0.2", "--set", "18.30=1@50", "--trace", str(trace),
                 "--signals", "13,18.11"]) == 0
    times, rows = changes(trace, "18.11")
    before, after = [t for t in times if t <= 50], [t for t in times if t >= 50]
    assert spacing(before) == {2} and spacing(after) == {4} and after[0] == 50
    assert rows[60][1] == 4 and rows[40][1] == 3
    assert main(["run", str(program), "--node", f"2:{program}", "--seconds", "0.2", "--set", "1:18.30=1@50",
                 "--set", "2:18.30=1@50", "--trace", str(trace), "--signals", "18.11"]) == 0
    times, rows = changes(trace, "1:18.11")
    assert [t for t in times if t >= 50][:3] == [50, 54, 58] and all(row[1] == row[2] for row in rows)
    capsys.readouterr()


def test_the_ides_link_runs_the_new_rate_from_the_next_sample():
    """The IDE's embedded APC link (apcsim): the same program, advanced a millisecond at a time."""
    link = dpl_link()
    drive = link.service.drive
    link.download(DplImage("rate.dpl", PROGRAM).to_bytes(), name="rate.dpl")
    link.start()
    seen = []
    for ms in range(1, 101):
        link.advance(1)
        seen.append((ms, link.read_parameter("18.11")))
        if ms == 50:
            link.write_parameter("18.30", 1)
    times = [t for (_, a), (t, b) in zip(seen, seen[1:], strict=False) if a != b]
    assert spacing([t for t in times if t <= 50]) == {2} and spacing([t for t in times if t >= 50]) == {4}
    assert 0 <= link.service.time_ms * 1_000_000 - drive.time_ns < 4_000_000    # the drive's clock is the link's


def test_run_ms_and_13_follow_reinit_not_the_written_parameter():
    """#81.12 alone changes nothing until REINIT (L4678-4723 Figure 6-3 writes it, then REINIT); ApcDrive.run_ms
    runs the samples that fall in the time, the period read before each."""
    d = ApcDrive()
    d.params.write((81, 12), 5)
    d.run_ms(10)
    assert (d.samples, d.read(13)) == (10, 2)
    d.pos0 = lambda: d.reinit() if d.samples == 12 else None
    d.run_ms(30)                                   # samples 11, 12 at 1 ms, then every 4 ms: 16, 20, … 40 ms
    assert (d.samples, d.time_ns, d.read(13)) == (19, 40_000_000, 4)
