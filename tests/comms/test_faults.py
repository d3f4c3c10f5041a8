"""A bad line: 5 % of the telegrams lost and 5 % corrupted in each direction (comms/faults.py, issue 14 "Faults").
Against `motiontool drive` in its own process, each operation either completes correctly or fails with a clear
error, and no wrong value is ever written — everything is read back over a clean link to prove it."""

from __future__ import annotations

import io
import random

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms.faults import Faults, FaultyPort
from motiontool.comms.links import open_link
from motiontool.comms.protocol import LinkError
from motiontool.headless import RunOptions, run_program
from motiontool.paramdb import database
from tests.comms.drive_process import DrivePool, drive_process
from tests.test_samples import SAMPLES, parse_header

pytestmark = pytest.mark.wire

BAD = "drop=5,corrupt=5,timeout=0.1"


class Loopback:
    def __init__(self):
        self.written, self.pending = [], b""

    def write(self, data):
        self.written.append(bytes(data))
        self.pending += data
        return len(data)

    def read(self, size=1):
        data, self.pending = self.pending[:size], self.pending[size:]
        return data


def test_the_faulty_port_spoils_at_the_given_rates_and_repeats_with_a_seed():
    runs = []
    for _ in range(2):
        port = FaultyPort(Loopback(), Faults(drop=5, corrupt=5, duplicate=5, seed=3))
        for i in range(2000):
            port.write(bytes([i & 0xFF] * 8))
        runs.append((port.faults.counts, port._port.written))
    counts, written = runs[0]
    assert runs[0] == runs[1]                                       # the same seed spoils the same telegrams
    assert 60 <= counts["drop"] <= 140 and 60 <= counts["corrupt"] <= 140 and 50 <= counts["duplicate"] <= 150
    spoilt = [w for w in written if len(set(w)) > 1]
    assert len(spoilt) >= counts["corrupt"] - 5                      # one byte differs in a corrupted telegram
    assert len(written) == 2000 - counts["drop"] + counts["duplicate"]


@pytest.fixture(scope="module")
def pool():
    pool = DrivePool("--clock", "virtual", "--node", "1", "--node", "2", "--master-node", "1")
    yield pool
    pool.close()


@pytest.mark.slow
@pytest.mark.parametrize("seed", [1, 2])
def test_every_parameter_write_is_right_or_refused_clearly(pool, seed):
    drive = pool.take()
    try:
        bad, clean = open_link(f"{drive.url}#1,{BAD},seed={seed}"), open_link(drive.url + "#1")
        rng = random.Random(seed)
        before = {p.number: clean.read_parameter(p.number) for p in database()}
        intended, unsure = {}, {}
        for p in database():
            if p.read_only:
                continue
            low, high = p.to_raw(p.minimum), p.to_raw(p.maximum)
            value = rng.choice(sorted(p.options)) if p.options else rng.randint(low, high)
            try:
                bad.write_parameter(p.number, value)
                intended[p.number] = value
            except LinkError as exc:
                assert str(exc), "a failure says what failed"
                unsure[p.number] = value
        after = {p.number: clean.read_parameter(p.number) for p in database()}
        for number, value in intended.items():
            assert after[number] == value, number
        for number, value in unsure.items():                        # the write may or may not have arrived
            assert after[number] in (before[number], value), number
        reads = errors = 0
        for p in database():
            try:
                assert bad.read_parameter(p.number) == after[p.number], p.label
                reads += 1
            except LinkError:
                errors += 1
        counts = bad.bus.port.faults.counts
        assert counts["drop"] > 10 and counts["corrupt"] > 10 and bad.bus.stats.repeats > 20
        assert reads > 200 and len(intended) > 150
        bad.close()
        clean.close()
    finally:
        drive.stop()


SOME_SAMPLES = [p for p in SAMPLES if p.name[:2] in ("01", "07", "13", "20", "28")]


@pytest.mark.slow
@pytest.mark.parametrize("path", SOME_SAMPLES, ids=[p.stem for p in SOME_SAMPLES])
def test_samples_print_the_same_or_fail_clearly(path, pool):
    header = parse_header(path)
    options = RunOptions(seconds=header.seconds, settings=[f"{n}={v}" for n, v in header.settings],
                         inputs=[f"{n}={v}@{t}" for n, v, t in header.inputs])
    out, err = io.StringIO(), io.StringIO()
    reference = run_program(path, options, out, err), out.getvalue(), err.getvalue()
    drive = pool.take()
    try:
        options.link = f"{drive.url}#1,{BAD},retries=6,seed={len(path.name)}"
        out, err = io.StringIO(), io.StringIO()
        code = run_program(path, options, out, err)
        if code == reference[0] and err.getvalue() == reference[2]:
            assert out.getvalue() == reference[1]
        else:                                                        # a clear error, never wrong output
            assert code == 2 and err.getvalue().startswith("motiontool run: "), err.getvalue()
            assert reference[1].startswith(out.getvalue().rsplit("\n", 1)[0])
    finally:
        drive.stop()


def image(source, debug=False):
    result = compile_source(source, "p.m", debug=debug)
    assert result.ok
    return result.image.to_bytes()


@pytest.mark.slow
def test_downloads_arrays_cam_debugger_and_recordings_over_a_bad_line(tmp_path):
    import subprocess
    import sys

    from motiontool.cameditor.transfer import download_config, upload_config
    from motiontool.formats.zbc import read_config

    conf = tmp_path / "c.zbc"
    built = subprocess.run([sys.executable, "-m", "motiontool", "cam", "build", "--name", "c", "--master-length",
                            "4000", "--point", "0,0,C", "--point", "1500,1200,T", "--point", "2500,2400,T", "--point",
                            "4000,3600,C", "-o", str(conf)], capture_output=True, text=True, timeout=120)
    assert built.returncode == 0, built.stderr
    with drive_process("--clock", "virtual") as drive:
        bad = open_link(f"{drive.url}#1,{BAD},retries=6,seed=11")
        clean = open_link(drive.url + "#1")
        # the CAM editor's Write to controller: a clean upload gives back exactly the file's curve
        config = read_config(conf)
        download_config(bad, config)
        assert [a.values for a in upload_config(clean).arrays] == [a.values for a in config.arrays]
        # arrays: what the bad link wrote is exactly what a clean link reads
        values = list(range(-3000, 3000, 3))
        bad.call("restore_arrays", arrays=[{"name": "big", "values": values}, {"name": "small", "values": [1, 2]}])
        assert clean.read_array(0) == values and clean.read_array(1) == [1, 2]
        bad.write_array(1, [7, 8])
        assert clean.read_array(1) == [7, 8] and bad.read_array(0) == values
        # a download is applied whole or not at all; then start, break, debugger
        source = "\n".join(f"v{i} = {i}" for i in range(200)) + "\nPRINT \"done \", v199\n"
        bad.download(image(source, debug=True), name="long")
        prints = []
        bad.subscribe(lambda e: prints.append(e.text) if e.kind == "print" else None)
        bad.call("set_breakpoints", lines=[150])
        bad.start(step=True)
        bad.advance(5)
        assert bad.status().line == 1
        bad.call("step")
        bad.advance(5)
        assert bad.status().line == 2
        bad.continue_program()
        bad.advance(50)
        assert (clean.status().program_state, clean.status().line) == ("break", 150)
        assert bad.call("read_variables", names=["v10", "v148"]) == [10, 148]
        bad.call("write_variable", name="v149", value=-1)
        assert clean.call("read_variables", names=["v149"]) == [-1]
        bad.continue_program()
        bad.advance(50)
        bad.flush_events()
        assert prints == ["done 199"]
        # a TESTSETP recording uploads identically (into fresh array memory: DIMs find arrays by position)
        bad.call("reset", what="arrays")
        bad.download(image("DIM rec[3000]\nTESTSETP 1 4097 4098 4102 rec\nTESTSTART 1000\nVEL 100\nACC 100\n"
                           "DEC 100\nPOSA 2000\nWAITAX\n"))
        bad.start()
        bad.advance(3000)
        assert bad.call("upload_recording", index=0) == clean.call("upload_recording", index=0)
        counts = bad.bus.port.faults.counts
        assert counts["drop"] + counts["corrupt"] > 10
        bad.close()
        clean.close()


@pytest.mark.slow
def test_polling_scope_and_two_nodes_over_a_bad_line(tmp_path, pool):
    """Free Run (polling): every poll is right or refused, times only grow; two nodes behind one drive print what
    the embedded bus prints, or the run fails with a clear error."""
    from motiontool.scope.acquisition import Polling, new_curve
    from motiontool.scope.curves import Scope

    master, slave = tmp_path / "m.m", tmp_path / "s.m"
    master.write_text("PULSVEL 2500\nDELAY 1000\nPRINT \"master \", MAPOS\n")
    slave.write_text("DELAY 1000\nPRINT \"slave \", MAPOS, \" \", GET SYNCFACTS\n")
    options = RunOptions(seconds=3, settings=["2:SYNCFACTS=7"], nodes=[f"2:{slave}"])
    out, err = io.StringIO(), io.StringIO()
    reference = run_program(master, options, out, err), out.getvalue(), err.getvalue()
    drive = pool.take()
    try:
        options.link = f"{drive.url},{BAD},retries=6,seed=5"
        out, err = io.StringIO(), io.StringIO()
        code = run_program(master, options, out, err)
        assert (code, out.getvalue(), err.getvalue()) == reference or (
            code == 2 and err.getvalue().startswith("motiontool run: "))
        bad = open_link(f"{drive.url}#1,{BAD},seed=6")
        bad.download(image("VEL 100\nACC 100\nDEC 100\nmain:\nPOSA 5000\nPOSA 0\nGOTO main\n"))
        bad.start()
        scope = Scope()
        for signal in ("APOS", "CPOS"):
            new_curve(scope, signal, "poll", "polled")
        polling = Polling(scope, bad)
        polling.start()
        refused = 0
        for _ in range(60):
            bad.advance(20)
            try:
                polling.poll()
            except LinkError:
                refused += 1
        times, values = scope.curves[0].buffer.arrays()
        assert len(times) == polling.polls == 60 - refused and polling.polls > 40
        assert (times[1:] > times[:-1]).all() and values.max() > 0
        bad.close()
    finally:
        drive.stop()
