"""The DPL runtime on the APC kernel: statements, integer semantics, the task model, run-time errors."""

from __future__ import annotations

import pytest

from motiontool.apc import ApcDrive
from motiontool.dpl.driver import check_source
from motiontool.dpl.runtime import MAX_POS_STATEMENTS, SLICE_STATEMENTS, DplRuntime


def run(source: str, samples: int = 1, drive: ApcDrive | None = None) -> DplRuntime:
    checked = check_source(source, "t.dpl")
    assert checked.ok, [d.format() for d in checked.diagnostics]
    runtime = DplRuntime(drive or ApcDrive(), checked)
    runtime.start()
    runtime.advance(samples)
    return runtime


def var(runtime: DplRuntime, name: str) -> int:
    return runtime.read_variable(name)


def test_integer_semantics_wrap_truncate_and_compare():
    """All values are signed 32-bit (positions wrap, L1193-1209); / truncates toward zero (A51)."""
    r = run("\n".join([
        "Initial {",
        "a% = 2147483647 + 1",
        "b% = -7 / 2",
        "c% = 7 / -2",
        "d% = 65536 * 65536",
        "e% = (3 > 2) + (2 <> 2) + (NOT 0) * 10 + (1 AND 0) * 100 + (0 OR 5) * 1000",
        "f% = 0x0F & 0x3C | 0x100",
        "g% = MULDIV(2147483647, 2, 3)",
        "(q%, rm%) = MULDIVRM(100, 65536, 60000)",
        "h% = UnsignedTopWord(-1) + UnsignedBottomWord(0x12345678)",
        "i% = IWINDOW(-2147483646, 2147483646, 20, 20)",
        "j% = IWINDOW(100, 79, 20, 20)",
        "}",
    ]) + "\n")
    assert [var(r, n + "%") for n in "abcdefghij"] == [-2147483648, -3, -3, 0, 1011, 0x10C, 1431655764,
                                                 65535 + 0x5678, 1, 0]
    assert (var(r, "q%"), var(r, "rm%")) == (109, 13600)  # §8.4: 100 rpm is 109 counts/ms + 13600/60000


def test_bits_arrays_registers_and_parameters():
    drive = ApcDrive()
    r = run("\n".join([
        "Initial {",
        "DIM A%[3]",
        "CONST T%[] = { 10, APC_FB_POS, -3 }",
        "Ctl%.0 = 1",
        "Ctl%.4 = 1",
        "Ctl%.0 = 0",
        "A%[2] = T%[1] + T%[2]",
        "_P01% = 7",
        "#18.12 = _P01% * 2",
        "#18.13.1 = 1",
        "bit% = A%[2].5 + #18.13.1 * 10",
        "}",
    ]) + "\n", drive=drive)
    assert var(r, "Ctl%") == 16 and var(r, "A%[2]") == 45 and var(r, "bit%") == 11
    assert drive.params.read((70, 1)) == 7 and drive.params.read((18, 12)) == 14 and drive.params.read((18, 13)) == 2


def test_if_elseif_else_and_one_line_if():
    source = "Initial {\nIF x% = 1 THEN\ny% = 10\nELSEIF x% = 2 THEN\ny% = 20\nELSE\ny% = 30\nENDIF\n" \
             "IF y% = 30 THEN z% = 1\n}\n"
    assert (var(run(source), "y%"), var(run(source), "z%")) == (30, 1)
    assert var(run(source.replace("IF x% = 1", "x% = 2\nIF x% = 1")), "y%") == 20


def test_initial_runs_first_then_pos_tasks_every_sample_background_once_per_sample():
    """Initial before the POS tasks; POS0/POS1 each sample; a Background loop one pass per POS period (A60)."""
    source = "\n".join([
        "Initial {", "wait:", "w% = w% + 1", "IF w% < 5 THEN GOTO wait", "}",
        "Background{", "top:", "b% = b% + 1", "goto top: // main background loop", "}",
        "Pos0{", "p0% = p0% + 1", "}",
        "Pos1{", "p1% = p1% + 1", "en% = APCReadPar(APC_ENABLE_STATUS)", "}",
    ]) + "\n"
    r = run(source, samples=4)
    assert (var(r, "w%"), var(r, "p0%"), r.state) == (4, 0, "initial")  # one pass of the wait loop per slice
    r.advance(10)
    assert (var(r, "w%"), var(r, "p0%"), var(r, "p1%"), var(r, "b%")) == (5, 10, 10, 9)
    once = run("Background{\nb% = b% + 1\n}\n", samples=20)
    assert var(once, "b%") == 1 and once.state == "running"


def test_a_long_background_slice_ends_after_its_statement_budget():
    r = run("Background{\nb% = b% + 1\nIF b% < 1000000 THEN b% = b% + 0\nc% = c% + 1\n" +
            "n% = 1\n" * (SLICE_STATEMENTS + 10) + "}\n", samples=1)
    assert var(r, "c%") == 1 and r.state == "running"


def test_run_time_errors_stop_the_program_at_their_place():
    """Bad indices and division by zero stop every task (the module would trip) and name file:line:col."""
    r = run("Initial {\nDIM A%[2]\ni% = 2\n}\nPos0{\nA%[i%] = 1\n}\n", samples=3)
    assert r.state == "error" and str(r.error) == "t.dpl:6:1: error: index 2 is outside A%[0 … 1]"
    assert r.drive.pos0 is None
    r = run("Background{\nx% = 3 / y%\n}\n", samples=2)
    assert str(r.error) == "t.dpl:2:8: error: division by zero"
    r = run("Initial {\ns% = CTSyncEnableOutputChannel(1)\n}\n", samples=2)
    assert str(r.error) == ("t.dpl:2:6: error: CTSyncEnableOutputChannel is not simulated (an SM-Applications "
                            "call the APC manual does not document)")
    r = run("Pos0{\nloop:\nGOTO loop\n}\n", samples=2)
    assert str(r.error) == (f"t.dpl:3:1: error: the Pos0 task did not end within its POS period (task overrun "
                            f"after {MAX_POS_STATEMENTS} statements)")


def test_apc_calls_reach_the_kernel_with_their_results():
    drive = ApcDrive()
    r = run("\n".join([
        "Initial {",
        "s1% = APCSetRunMode(APC_DISABLE)",
        "s2% = APCSetProfileMaxSpeedClamp(MULDIV(1073741824, 900, 60000))",
        "(v%, s3%) = APCReadPar(APC_PRF_MAX_SPD)",
        "w% = APCReadPar(113)",
        "}",
    ]) + "\n", drive=drive)
    assert (var(r, "s1%"), var(r, "s2%"), var(r, "s3%")) == (1, 1, 1)
    assert var(r, "v%") == var(r, "w%") == 16106127 == drive.read(113)


def test_stop_removes_the_pos_tasks_and_start_restarts_from_initial():
    r = run("Initial {\ni% = i% + 1\n}\nPos0{\np% = p% + 1\n}\n", samples=5)
    assert var(r, "p%") == 5  # Initial ends in the slice before the first sample
    r.stop()
    r.advance(5)
    assert (r.state, var(r, "p%"), r.drive.pos0) == ("stopped", 5, None)
    r.start()
    assert var(r, "i%") == 0
    r.advance(2)
    assert (var(r, "i%"), var(r, "p%")) == (1, 2)


@pytest.mark.parametrize("source", ["Pos0{\nx% = APCSetReferencePosition(1, 2, 3)\n}\n"])
def test_pos_only_calls_run_in_pos_tasks(source):
    r = run(source, samples=3)
    assert r.state == "running" and var(r, "x%") == 1
