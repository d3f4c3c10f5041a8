"""End to end: `motiontool drive` as its own process, everything else over `fc:socket://127.0.0.1:…` (issue "Done
when"): the samples print exactly what the embedded run prints, every parameter reads and writes, download/start/
break, the debugger, the Array Editor, a CAM download, the polling and TESTSETP scopes, two nodes on one drive."""

from __future__ import annotations

import io
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms.links import open_link
from motiontool.comms.protocol import LinkError
from motiontool.headless import RunOptions, run_program
from motiontool.paramdb import database
from tests.comms.drive_process import DrivePool, DriveProcess, drive_process
from tests.test_samples import SAMPLES, parse_header

pytestmark = pytest.mark.wire

ROOT = Path(__file__).resolve().parents[2]


def run_both(path: Path | None, options: RunOptions, url: str) -> tuple[tuple, tuple]:
    """(exit, stdout, stderr) of the embedded run and of the same run over the link."""
    results = []
    for link in (None, url):
        out, err = io.StringIO(), io.StringIO()
        options.link = link
        code = run_program(path, options, out, err)
        results.append((code, out.getvalue(), err.getvalue()))
    return results[0], results[1]


@pytest.fixture(scope="module")
def pool():
    pool = DrivePool("--clock", "virtual")
    yield pool
    pool.close()


@pytest.mark.parametrize("path", SAMPLES, ids=[p.stem for p in SAMPLES])
def test_sample_prints_over_fc_exactly_what_the_embedded_run_prints(path, pool, tmp_path):
    header = parse_header(path)
    drive = pool.take()
    try:
        options = RunOptions(seconds=header.seconds, settings=[f"{n}={v}" for n, v in header.settings],
                             inputs=[f"{n}={v}@{t}" for n, v, t in header.inputs])
        embedded, wire = run_both(path, options, drive.url + "#1")
        assert wire == embedded
        assert embedded[1], "the sample prints something"
    finally:
        code, _, err = drive.stop()
        assert code == 0, err


def test_cli_run_with_trace_record_and_exit_codes_as_embedded(pool, tmp_path):
    source = tmp_path / "rec.m"
    source.write_text("DIM rec[150]\nVEL 100\nACC 100\nDEC 100\nTESTSETP 2 4097 4098 4102 rec\nTESTSTART 50\n"
                      "POSA 1000\nWAITAX\nPRINT \"at \", APOS\nSET SWPOSLIMACT 1\nPOSA 600000\n")
    outputs = []
    for link in (None, "X"):
        drive = pool.take() if link else None
        args = [sys.executable, "-m", "motiontool", "run", str(source), "--seconds", "5",
                "--trace", str(tmp_path / f"t{bool(link)}.csv"), "--record", str(tmp_path / f"r{bool(link)}.csv")]
        if drive is not None:
            args += ["--link", drive.url]
        proc = subprocess.run(args, capture_output=True, text=True, timeout=180)
        outputs.append((proc.returncode, proc.stdout, proc.stderr))
        if drive is not None:
            drive.stop()
    assert outputs[0] == outputs[1]
    assert outputs[0][0] == 2 and "error 111" in outputs[0][2]
    for name in ("t", "r"):
        assert (tmp_path / f"{name}False.csv").read_text() == (tmp_path / f"{name}True.csv").read_text()


def test_drive_says_where_it_listens_and_stops_cleanly_on_sigint_sigterm_and_the_end_of_stdin():
    for sig in (signal.SIGINT, signal.SIGTERM):
        drive = DriveProcess("--node", "1", "--node", "2")
        assert drive.url.startswith("fc:socket://127.0.0.1:")
        link = open_link(drive.url + "#2")
        assert link.read_parameter("KPROP") == 30
        link.close()
        drive.proc.send_signal(sig)
        assert drive.proc.wait(timeout=20) == 0          # the signal alone ends it, cleanly
        code, out, err = drive.stop()
        assert out == ""        # the one line was read already; nothing else on stdout
    drive = DriveProcess()                               # --stop-with-parent: the end of stdin ends it
    assert drive.url
    drive.proc.stdin.close()
    assert drive.proc.wait(timeout=20) == 0
    drive.stop()
    with drive_process(listen="fc:pty") as drive:
        assert drive.url.startswith("fc:/dev/pts/")
        link = open_link(drive.url + "#1,baud=115200")
        assert link.read_parameter("KPROP") == 30
        link.close()


@pytest.mark.slow
def test_every_parameter_reads_and_writes_over_the_wire():
    """`motiontool params --link` reads all 262 as the simulator holds them; every writable one is written (a
    value different from the default, inside its range) and read back."""
    db = database()
    with drive_process() as drive:
        proc = subprocess.run([sys.executable, "-m", "motiontool", "params", "--link", drive.url + "#1"],
                              capture_output=True, text=True, timeout=120)
        assert proc.returncode == 0, proc.stderr
        lines = proc.stdout.splitlines()
        assert len(lines) == len(db) == 262
        sim = open_link("sim")
        # CANNR (33-90) is a controller's CAN node id: node 1 of a drive has 1, a lone simulator 127 (decision K101)
        assert lines == [f"{p.label} {1 if p.number == '33-90' else sim.read_parameter(p.number)}" for p in db]
        link = open_link(drive.url + "#1")
        written = {}
        for p in db:
            if p.read_only:
                continue
            low, high = p.to_raw(p.minimum), p.to_raw(p.maximum)
            value = high if link.read_parameter(p.number) != high else low
            if p.options:
                value = max(p.options) if link.read_parameter(p.number) != max(p.options) else min(p.options)
            link.write_parameter(p.number, value)
            written[p.number] = value
        assert {n: link.read_parameter(n) for n in written} == written
        proc = subprocess.run([sys.executable, "-m", "motiontool", "params", "--link", drive.url + "#1",
                               "--set", "32-60=50", "--get", "KPROP"], capture_output=True, text=True, timeout=120)
        assert proc.stdout == "32-60 KPROP 50\n32-60 KPROP 50\n"
        proc = subprocess.run([sys.executable, "-m", "motiontool", "params", "--link", drive.url + "#1",
                               "--set", "KPROP=999999"], capture_output=True, text=True, timeout=120)
        assert proc.returncode == 1 and "32-60 KPROP: 999999 is outside 0..100000" in proc.stderr
        link.close()


def compiled(source: str, debug: bool = False):
    result = compile_source(source, "p.m", debug=debug)
    assert result.ok, [d.format() for d in result.diagnostics]
    return result.image


def test_download_start_break_continue_and_the_debugger_over_the_wire():
    with drive_process("--clock", "virtual") as drive:
        link = open_link(drive.url + "#1")
        prints = []
        link.subscribe(lambda e: prints.append(e.text) if e.kind == "print" else None)
        link.download(compiled("i = 0\nmain:\ni = i + 1\nDELAY 10\nGOTO main\n").to_bytes(), name="loop")
        link.start()
        link.advance(100)
        assert link.status().program_state == "running"
        link.break_program()
        assert link.status().program_state == "break"
        link.continue_program()
        assert link.status().program_state == "running"
        link.break_program()
        source = "a = 1\nb = 2\nPRINT \"sum \", a + b\nc = a + b\nPRINT \"c \", c\n"
        image = compiled(source, debug=True)
        link.download(image.to_bytes(), name="dbg")
        link.call("set_breakpoints", lines=[4])
        link.start(step=True)                                  # Prepare Singlestep
        link.advance(5)
        assert link.status().line == 1
        link.call("step")
        link.advance(5)
        assert link.status().line == 2
        link.continue_program()                                # Go: to the breakpoint on line 4
        link.advance(5)
        status = link.status()
        assert (status.program_state, status.line) == ("break", 4)
        assert link.call("read_variables", names=["a", "b"]) == [1, 2]
        link.call("write_variable", name="a", value=40)        # watch and change
        link.continue_program()
        link.advance(20)
        link.flush_events()
        assert prints == ["sum 3", "c 42"]
        link.close()


def test_array_editor_and_cam_download_over_the_wire(tmp_path):
    from motiontool.arrayeditor.rows import ArrayList
    from motiontool.cameditor.transfer import download_config, upload_config
    from motiontool.formats.zbc import read_config

    conf = tmp_path / "c.zbc"
    proc = subprocess.run([sys.executable, "-m", "motiontool", "cam", "build", "--name", "c", "--master-length",
                           "4000", "--point", "0,0,C", "--point", "1500,1200,T", "--point", "2500,2400,T",
                           "--point", "4000,3600,C", "-o", str(conf)], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    config = read_config(conf)
    with drive_process() as drive:
        link = open_link(drive.url + "#1")
        download_config(link, config)                          # the CAM editor's Write to controller
        back = upload_config(link)
        assert [a.values for a in back.arrays] == [a.values for a in config.arrays]
        assert back.curves and back.curves[0].name == "c"
        editor = ArrayList()                                   # the Array Editor's Read / Write
        editor.read_controller(link)
        rows = [i for i, r in enumerate(editor.rows) if r.record.kind == "Array"]
        editor.set_value(rows[5], 12345)
        kprop = next(i for i, r in enumerate(editor.rows) if r.record.name == "KPROP")
        editor.set_value(kprop, 66)
        assert editor.write_controller(link) == []
        assert link.read_array(0)[5] == 12345 and link.read_parameter("KPROP") == 66
        link.close()


def test_polling_and_testsetp_scopes_over_the_wire():
    from motiontool.scope.acquisition import Polling, list_testsetp, load_testsetp, new_curve
    from motiontool.scope.curves import Scope

    with drive_process("--clock", "virtual") as drive:
        link = open_link(drive.url + "#1")
        link.download(compiled("DIM rec[600]\nTESTSETP 1 4097 4098 4102 rec\nTESTSTART 200\nVEL 100\nACC 100\n"
                               "DEC 100\nPOSA 500\nWAITAX\nDELAY 300\n").to_bytes())
        link.start()
        scope = Scope()
        new_curve(scope, "APOS", "poll", "polled")
        new_curve(scope, "CPOS", "poll", "polled")
        polling = Polling(scope, link)
        polling.start()
        for _ in range(40):
            link.advance(25)
            polling.poll()
        assert polling.polls == 40
        apos = scope.curves[0].buffer
        assert len(apos) == 40 and apos.arrays()[1][-1] > 0
        recordings = list_testsetp(link)
        assert recordings and recordings[0].samples == 200
        curves = load_testsetp(Scope(), link, 0)
        assert [c.name for c in curves][0].startswith("1: ") and len(curves[0].buffer) == 200
        link.close()


def test_two_nodes_behind_one_drive_print_what_the_embedded_bus_prints(tmp_path):
    master, slave = tmp_path / "m.m", tmp_path / "s.m"
    master.write_text("PULSVEL 2500\nDELAY 1000\nPRINT \"master \", MAPOS\n")
    slave.write_text("DELAY 1000\nPRINT \"slave \", MAPOS, \" \", GET SYNCFACTS\n")
    with drive_process("--clock", "virtual", "--node", "1", "--node", "2", "--master-node", "1") as drive:
        options = RunOptions(seconds=3, settings=["2:SYNCFACTS=7"], nodes=[f"2:{slave}"])
        embedded, wire = run_both(master, options, drive.url)
        assert wire == embedded
        assert sorted(wire[1].splitlines()) == ["1: master 10000", "2: slave 10000 7"]
        options.master_node = 1
        options.link = drive.url
        err = io.StringIO()
        assert run_program(master, options, io.StringIO(), err) == 1
        assert "motiontool drive --master-node" in err.getvalue()


def test_two_nodes_printing_in_the_same_milliseconds_come_out_in_time_then_node_order(tmp_path):
    """Each node's link polls its own events (here every millisecond, racing the run's flushes), so node 2's line
    of a millisecond can arrive before node 1's; the run prints them in (time, node) order as the embedded bus
    does. This failed intermittently before the run ordered them (issue 28 item 3)."""
    program = "i = 0\nWHILE i < 100 DO\n  DELAY 3\n  i = i + 1\n  PRINT \"{} \", i\nENDWHILE\n"
    first, second = tmp_path / "a.m", tmp_path / "b.m"
    first.write_text(program.format("a"))
    second.write_text(program.format("b"))
    options = RunOptions(seconds=1, nodes=[f"2:{second}"])
    for _ in range(3):
        with drive_process("--clock", "virtual", "--node", "1", "--node", "2") as drive:
            embedded, wire = run_both(first, options, drive.url + ",poll=0.001")
        assert wire == embedded
    assert embedded[1].splitlines()[:4] == ["1: a 1", "2: b 1", "1: a 2", "2: b 2"]


def test_a_missing_drive_is_a_clear_error():
    err = io.StringIO()
    code = run_program(ROOT / "resources" / "samples" / "01_positioning.m",
                       RunOptions(link="fc:socket://127.0.0.1:1#1"), io.StringIO(), err)
    assert code == 2 and "cannot open socket://127.0.0.1:1" in err.getvalue()
    with pytest.raises(LinkError):
        open_link("fc:socket://127.0.0.1:1")
