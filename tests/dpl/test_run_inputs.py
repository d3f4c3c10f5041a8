"""`motiontool run FILE.dpl --input …`: the freeze input DIGIN0 and marker pulses at given times, so freeze capture,
the lock and the CAM selected by a freeze and the CAM re-arm (seed 004 §4.3.8, §4.7.9-4.7.10, §4.8.6) are checked
headless from a program's trace; the CTSync line's node limits and POS rate (L2077-2078) and the encoder's lines
per revolution (#3.34, L463-469) from the command line (issue 29 item 8)."""

from __future__ import annotations

import pytest

from motiontool.cli import main
from tests.dpl.test_run_cli import read_trace

# A virtual master of 1000 counts per 1 ms sample (§6.4's user-program reference) and the reference freeze enabled
# with its flag reset; #18.11 = 1 resets the flag again (Background). EXTRA goes into Initial before run mode 2.
PROGRAM = """Initial {
s% = APCSetReferenceSource(4)
s% = APCEnableReferenceFreeze()
s% = APCResetRefSourceFreezeFlag()
EXTRA
s% = APCSetRunMode(2)
}
Background {
top:
IF #18.11 = 1 THEN
    #18.11 = 0
    s% = APCResetRefSourceFreezeFlag()
ENDIF
goto top:
}
Pos0 {
M% = M% + 1000
T% = UnsignedTopWord(M%)
P% = UnsignedBottomWord(M%)
s% = APCSetReferencePosition(T%, P%, 0)
}
"""
CAM = """DIM InA%[1]
DIM OutA%[1]
InA%[0] = 20000
OutA%[0] = 5000
s% = APCCamInitialise1(InA%, OutA%)
s% = APCSetCAMSize(1)
"""


def run(tmp_path, extra: str, options: list[str], signals: str, seconds: str = "0.1"):
    """The trace {time ms: {signal: value}} of PROGRAM with `extra` in Initial."""
    program, trace = tmp_path / "p.dpl", tmp_path / "t.csv"
    program.write_text(PROGRAM.replace("EXTRA", extra), encoding="utf-8")
    assert main(["run", str(program), "--seconds", seconds, *options, "--trace", str(trace),
                 "--signals", signals]) == 0
    header, rows = read_trace(trace)
    return {row[0]: dict(zip(header[1:], row[1:], strict=True)) for row in rows}


def pulses(*times: int) -> list[str]:
    """A 1 ms high pulse on DIGIN0 at each time."""
    return [f for t in times for f in ("--input", f"DIGIN0=1@{t}", "--input", f"DIGIN0=0@{t + 1}")]


def test_freeze_input_captures_the_positions_and_latches_until_reset(tmp_path, capsys):
    """L1026-1047 "one pair by the Freeze input … captured within a micro second", L1076 the freeze signal "on
    Digital Input 0 (Pin 10) … 81.43 sets the detection type, 0 = rising edge, 1 = falling edge. Parameter 81.42
    … must be set to 1 to enable the freeze hardware", L1079 the flags "remain latched on, so that further
    Freeze signals will not be detected until the user resets them": DIGIN0 rising at 20 ms captures [28] of that
    instant in [29] and [21]; the edge at 40 ms is not seen; after the reset at 55 ms the edge at 70 ms is."""
    t = run(tmp_path, "", ["--set", "81.42=1", *pulses(20, 40, 70), "--set", "18.11=1@55"], "20,21,22,28,29")
    assert (t[20]["22"], t[21]["22"]) == (0, 1)
    assert t[21]["29"] == t[20]["28"] > t[19]["28"] and t[21]["21"] == t[20]["20"]
    assert t[50]["29"] == t[20]["28"] and t[50]["22"] == 1            # 40 ms: latched, not captured
    assert t[60]["22"] == 0 and t[71]["22"] == 1 and t[71]["29"] == t[70]["28"] > t[69]["28"]
    # falling edge with #81.43 = 1: captured when DIGIN0 goes low at 21 ms
    t = run(tmp_path, "", ["--set", "81.42=1", "--set", "81.43=1", *pulses(20)], "22,28,29")
    assert t[21]["22"] == 0 and t[22]["22"] == 1 and t[22]["29"] == t[21]["28"]
    # without #81.42 the freeze hardware passes nothing to the counters (its default 0, L8212)
    t = run(tmp_path, "", pulses(20, 40), "22")
    assert {row["22"] for row in t.values()} == {0}
    assert capsys.readouterr().err == ""


def test_digital_lock_selected_by_freeze_synchronises_at_the_freeze_point(tmp_path):
    """L1137-1151 APCSelectActionOnFreeze(1) "Digital Lock Select on Freeze", "no lost position, from when the
    freeze was triggered to when the reference is engaged"; L1842-1853 rigid lock "will synchronise the Slave axis
    to the Master axis, at the exact point the freeze occurred": Stop until the freeze at 30 ms, then digital lock,
    locked, and the slave reference has moved exactly the master's travel since the freeze."""
    t = run(tmp_path, "s% = APCEnableRigidLock()\ns% = APCSelectActionOnFreeze(1)",
            ["--set", "81.42=1", *pulses(30)], "100,61,117,28,29", seconds="1")
    assert t[30]["100"] == 0 and t[31]["100"] == 4 and t[200]["61"] == 0   # locking within the profile limits
    assert t[1000]["61"] == 1 and t[1000]["29"] == t[30]["28"]
    assert t[1000]["117"] - t[30]["117"] == t[1000]["28"] - t[1000]["29"]


def test_cam_selected_by_freeze_and_re_armed_runs_one_cycle_per_mark(tmp_path):
    """L1589-1600 "The CAM reference may be selected by a freeze input", L1605-1622 re-arm: "when a single shot
    completes, the stop reference will automatically be selected, the reference freeze will be reset … ready for a
    freeze signal to trigger the CAM again"; "If … the cut length is shorter than the total master distance, then
    cuts will be missed". A 20 000-count CAM moving the slave 5000 (instant stop, so that a cycle moves exactly
    that): marks 30 ms apart give a cycle each, marks 15 ms apart miss every second one."""
    setup = CAM + ("s% = APCSetStopMode(1)\ns% = APCEnableCAMSingleShot()\ns% = APCEnableCAMFreezeRearm()\n"
                   "s% = APCSelectActionOnFreeze(2)")
    t = run(tmp_path, setup, ["--set", "81.42=1", *pulses(10, 40, 70)], "100,22,117", seconds="0.1")
    assert [t[ms]["100"] for ms in (10, 11, 29, 31, 40, 41, 71)] == [0, 3, 3, 0, 0, 3, 3]
    assert t[35]["22"] == 0                                         # the freeze flag reset by the re-arm
    assert (t[35]["117"], t[65]["117"], t[100]["117"]) == (5000, 10000, 15000)
    t = run(tmp_path, setup, ["--set", "81.42=1", *pulses(10, 25, 40, 55, 70)], "117", seconds="0.1")
    assert (t[35]["117"], t[65]["117"], t[100]["117"]) == (5000, 10000, 15000)   # 25 and 55 ms are missed


def test_a_reference_marker_pulse_captures_like_a_second_freeze_input(tmp_path):
    """L633 "the marker pulse can be utilised as an additional high speed Freeze/registration input"; L1090-1106
    marker capture needs APCEnableReferenceMarker, the flag reset and APCDisableRefSourceMarker (capture, not
    reset): REF_MARKER=1@25 latches [23]/[30] of that instant and sets [24]."""
    setup = "s% = APCEnableReferenceMarker()\ns% = APCDisableRefSourceMarker()\ns% = APCResetRefSourceMarkerFlag()"
    t = run(tmp_path, setup, ["--input", "REF_MARKER=1@25"], "20,23,24,28,30")
    assert (t[25]["24"], t[26]["24"]) == (0, 1)
    assert t[26]["30"] == t[25]["28"] > t[24]["28"] and t[26]["23"] == t[25]["20"]


@pytest.mark.parametrize("option, message", [
    ("DIGIN1=1", "--input DIGIN1=1: input DIGIN1: the simulated SM-Applications takes DIGIN0 (0, the freeze input "
                 "T10) and the encoders' marker pulses REF_MARKER and FB_MARKER"),
    ("FB_MARKER=0@5", "--input FB_MARKER=0@5: FB_MARKER=0: a marker is a pulse, give FB_MARKER=1"),
    ("DIGIN0=2", "--input DIGIN0=2: value 2: give a whole number from 0 to 1"),
    ("DIGIN0=1@500", "--input DIGIN0=1@500: 500 ms is after the end of the run (--seconds 0.1)"),
    ("DIGIN0", "--input needs NAME=V or NAME=V@MS for a DPL program (DIGIN0, REF_MARKER, FB_MARKER), got 'DIGIN0'"),
])
def test_a_refused_input_is_one_line_and_exit_1(tmp_path, capsys, option, message):
    program = tmp_path / "p.dpl"
    program.write_text(PROGRAM.replace("EXTRA", ""), encoding="utf-8")
    assert main(["run", str(program), "--seconds", "0.1", "--input", option]) == 1
    assert capsys.readouterr().err == f"motiontool run: {message}\n"


def test_ctsync_node_limits_of_2_and_4_wire_lines(tmp_path, capsys):
    """L2078 "8 nodes maximum for 2-wire and 16 nodes maximum for 4-wire before line repeaters are required":
    9 nodes on the default 2-wire line are one line of error (was a Python traceback), 16 run with
    --ctsync-wires 4, 17 do not."""
    program = tmp_path / "p.dpl"
    program.write_text(PROGRAM.replace("EXTRA", ""), encoding="utf-8")

    def nodes(count: int) -> list[str]:
        return [str(program), *(f for n in range(2, count + 1) for f in ("--node", f"{n}:{program}"))]
    assert main(["run", *nodes(9), "--seconds", "0.01"]) == 1
    assert capsys.readouterr().err == ("motiontool run: 9 nodes: a 2-wire CTSync line takes at most 8 without "
                                       "repeaters (--ctsync-wires 4 allows 16)\n")
    trace = tmp_path / "t.csv"
    assert main(["run", *nodes(16), "--ctsync-wires", "4", "--seconds", "0.01", "--trace", str(trace),
                 "--signals", "28"]) == 0
    header, rows = read_trace(trace)
    assert header[-1] == "16:28" and len(set(rows[-1][1:])) == 1 and rows[-1][1] > 0
    assert main(["run", *nodes(17), "--ctsync-wires", "4", "--seconds", "0.01"]) == 1
    assert capsys.readouterr().err == "motiontool run: 17 nodes: a 4-wire CTSync line takes at most 16 without " \
                                      "repeaters\n"


def test_a_slave_on_another_pos_rate_is_a_run_time_error_with_words(tmp_path, capsys):
    """L2077 "All CTSync Master and Slave POS tasks must be set to the same update time (parameter #81.12)": the
    master on node 1 at 1 ms, the slave on node 3 taking 2 ms with REINIT at 20 ms: the run stops there, exit 2."""
    master, slave, trace = tmp_path / "master.dpl", tmp_path / "slave.dpl", tmp_path / "t.csv"
    master.write_text(PROGRAM.replace("EXTRA", "#81.06 = 25"), encoding="utf-8")
    slave.write_text(PROGRAM.replace("EXTRA", "#81.06 = 26").replace(
        "goto top:", "IF #18.30 = 1 THEN\n#18.30 = 0\n#81.12 = 4\nREINIT\nENDIF\ngoto top:"), encoding="utf-8")
    code = main(["run", str(master), "--node", f"3:{slave}", "--seconds", "0.1", "--set", "3:18.30=1@20",
                 "--trace", str(trace), "--signals", "28"])
    assert (code, capsys.readouterr().err.splitlines()[-1]) == (2, (
        "motiontool run: CTSync: node 3 (slave.dpl) runs its POS task every 2 ms (#81.12 = 4), the line every 1 ms "
        "(#81.12 = 3 on node 1 (master.dpl), the master): all CTSync master and slave POS tasks must be set to the "
        "same update time"))
    _, rows = read_trace(trace)
    assert 20 <= rows[-1][0] <= 22


def test_encoder_lines_per_revolution_from_the_command_line(tmp_path, capsys):
    """L463-467 "for 1024ppr encoder the counts per rev will be 4096. For one count the counter will go up in steps
    of 16": `--set 3.34=1024` (the drive encoder's lines per revolution) and the feedback position [40] of a motor
    turning at 5 rpm moves in steps of 16; an impossible line count is refused before anything runs."""
    program, trace = tmp_path / "p.dpl", tmp_path / "t.csv"
    program.write_text("Initial {\ns% = APCSetupOutputChannel(2, 0, 0)\ns% = APCEnableOutputChannel()\n"
                       "s% = APCSetSpeedSetPoint(MULDIV(5, 1073741824, 15000))\ns% = APCSelectReference(2)\n"
                       "s% = APCSetRunMode(2)\n}\n", encoding="utf-8")
    assert main(["run", str(program), "--seconds", "0.5", "--set", "3.34=1024", "--trace", str(trace),
                 "--signals", "40,3.34"]) == 0
    _, rows = read_trace(trace)
    positions = [row[1] for row in rows]
    assert positions[-1] > 1000 and {p % 16 for p in positions} == {0} and rows[-1][2] == 1024
    assert main(["run", str(program), "--seconds", "0.5", "--set", "3.34=0", "--trace", str(trace)]) == 1
    assert capsys.readouterr().err == ("motiontool run: --set 3.34=0: #3.34 = 0: drive encoder lines per "
                                       "revolution, 1 to 50000\n")
