"""Issue 26 item 6: a long DPL run with --trace streams its rows to the file (an hour of rows was 656 MB in memory)
and PRINT with stdout closed ends the run quietly (decisions R18)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from motiontool import cli, headless_dpl
from motiontool.headless import TraceWriter

PROGRAM = Path(__file__).parent / "programs" / "s7_1_position.dpl"


def test_a_dpl_trace_goes_to_the_file_while_the_program_runs(tmp_path, monkeypatch):
    seen: list[tuple[int, int]] = []  # (rows held in memory, bytes in the temporary file) at every batch

    class Watched(TraceWriter):
        def add(self, node, data):
            super().add(node, data)
            self.file.file.flush()
            seen.append((sum(len(p) for p in self.pending.values()), Path(self.file.tmp).stat().st_size))

    monkeypatch.setattr(headless_dpl, "TraceWriter", Watched)
    trace = tmp_path / "t.csv"
    assert cli.main(["run", str(PROGRAM), "--seconds", "20", "--trace", str(trace)]) == 0
    assert max(held for held, _ in seen) <= 100  # a batch at most, not the run
    sizes = [size for _, size in seen]
    assert sizes == sorted(sizes) and len(set(sizes)) > 100  # the file grew during the run
    rows = trace.read_text().splitlines()
    assert len(rows) > 19_000 and rows[0].startswith("time_ms,")
    times = [int(r.split(",")[0]) for r in rows[1:]]
    assert times == sorted(times)
    assert not list(tmp_path.glob(".t.csv.*.tmp"))


def test_print_with_stdout_closed_ends_quietly(tmp_path):
    program = tmp_path / "p.m"
    program.write_text('PRINT "hello"\n')
    result = subprocess.run(f'"{sys.executable}" -m motiontool run "{program}" --seconds 0.1 >&-', shell=True,
                            capture_output=False, stderr=subprocess.PIPE, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
