"""Hostile arguments on the command line (issue 26, items 1-3): an output that is an input is refused before
anything runs, every number is ASCII digits of bounded length, finite and in range, and a write that fails is one
line, exit 1, with the old file left as it was (decisions R12-R14)."""

from __future__ import annotations

import resource
import signal
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from motiontool import cli

BIG = "9" * 5000
LOOP = "main:\nDELAY 10\nGOTO main\n"
DPL = "Initial {\n}\n"
CURVE = ["--name", "A", "--point", "0,0", "--point", "10,5", "--point", "20,10", "--point", "30,0"]


def program(tmp_path, text: str = 'PRINT "hello"\n', name: str = "p.m"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def refused(capsys, args, *words) -> str:
    """Run the CLI in-process: exit 1, one line on stderr containing every word, nothing on stdout."""
    assert cli.main([str(a) for a in args]) == 1
    out = capsys.readouterr()
    lines = out.err.splitlines()
    assert len(lines) == 1 and "Traceback" not in out.err, out.err
    for word in words:
        assert word in lines[0], (word, lines[0])
    assert out.out == ""
    return lines[0]


def curve_file(tmp_path, capsys):
    zbc = tmp_path / "c.zbc"
    assert cli.main(["cam", "build", *CURVE, "-o", str(zbc)]) == 0
    capsys.readouterr()
    return zbc


# --- 1: an output onto an input ----------------------------------------------------------------------------------
def test_an_output_that_is_the_input_is_refused_and_the_input_kept(tmp_path, capsys):
    """`compile prog.m -o prog.m` replaced the source by the image, `run --trace prog.m` by a CSV, exit 0."""
    source = program(tmp_path)
    before = source.read_bytes()
    (tmp_path / "hard.m").hardlink_to(source)
    (tmp_path / "link.m").symlink_to(source)
    for args in (["compile", source, "-o", source], ["compile", source, "-o", tmp_path / "hard.m"],
                 ["run", source, "--trace", tmp_path / "link.m"], ["run", source, "--record", source],
                 ["run", source, "--trace", tmp_path / "." / "p.m"],
                 ["run", "--node", f"2:{source}", "--trace", source]):
        line = refused(capsys, args, "is the same as output file", str(source))
        assert line.startswith(f"motiontool {args[0]}: input file ")
        assert source.read_bytes() == before
        assert source.is_file() and not source.is_symlink()


def test_config_and_curve_files_are_not_overwritten_by_an_output(tmp_path, capsys):
    zbc = curve_file(tmp_path, capsys)
    before = zbc.read_bytes()
    refused(capsys, ["cam", "export", zbc, "-o", zbc], f"input file {zbc} is the same as output file {zbc} (-o)")
    refused(capsys, ["run", program(tmp_path), "--config", zbc, "--trace", zbc], "(--config)", "(--trace)")
    assert zbc.read_bytes() == before
    dat = tmp_path / "c.dat"
    assert cli.main(["cam", "export", str(zbc), "-o", str(dat)]) == 0
    dat_before = dat.read_bytes()
    refused(capsys, ["cam", "import", dat, "-o", dat], "is the same as output file")
    assert dat.read_bytes() == dat_before


def test_two_outputs_that_are_one_file_are_refused(tmp_path, capsys):
    source = program(tmp_path)
    refused(capsys, ["run", source, "--trace", tmp_path / "x.csv", "--record", tmp_path / "x.csv"],
            "are the same file", "(--trace)", "(--record)")
    assert not (tmp_path / "x.csv").exists()


# --- 2: numbers ----------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(("options", "words"), [
    (["--seconds", "\u0665"], ["--seconds \u0665:", "above 0 and at most 864000"]),
    (["--seconds", BIG], ["--seconds 999", "(5000 characters)", "at most 864000"]),
    (["--seconds", "1e999"], ["--seconds 1e999:", "at most 864000"]),
    (["--interval", "\u00b2", "--trace", "t.csv"], ["--interval \u00b2:", "from 1 to 3600000"]),
    (["--interval", BIG, "--trace", "t.csv"], ["--interval 999", "from 1 to 3600000"]),
    (["--set", f"KPROP={BIG}"], ["--set KPROP=999", "(5000 characters)", "to 4294967295"]),
    (["--set", "KPROP=\u0665"], ["--set KPROP=\u0665:", "to 4294967295"]),
    (["--input", f"1=1@{BIG}"], ["--input 1=1@", "time", "from 0 to"]),
    (["--input", f"{BIG}=1"], ["--input 999", "input", "from 0 to 9999"]),
    (["--input", "53=" + "1" + "0" * 40], ["--input 53=1000", "value", "from -32768 to 32767"]),
    (["--input", "\u0662=1"], ["--input \u0662=1: input", "from 0 to 9999"]),
    (["--signals", BIG, "--trace", "t.csv"], ["--signals 999", "to 2147483647"]),
    (["--signals", "\u0665", "--trace", "t.csv"], ["--signals \u0665:", "to 2147483647"]),
    (["--node", f"{BIG}:p.m"], ["--node 999", "node id", "from 1 to 32"]),
    (["--node", "\u0662:p.m"], ["--node \u0662:", "from 1 to 32"]),
    (["--master-node", "\u0662", "--node", "2:p.m"], ["--master-node \u0662:", "from 1 to 32"]),
    (["--link", f"fc:socket://127.0.0.1:1#{BIG}"], ["#999", "address", "from 0 to"]),
    (["--link", "fc:socket://127.0.0.1:1#\u0662"], ["#\u0662", "address"]),
    (["--link", "sim,realtime=nan"], ["realtime=nan", "from 0 to"]),
    (["--link", "sim,realtime=inf"], ["realtime=inf", "from 0 to"]),
    (["--timeout", BIG], ["--timeout 999", "(5000 characters)", "from 0 to 864000"]),
    (["--timeout", "\u0665"], ["--timeout \u0665:", "from 0 to 864000"]),
    (["--timeout", "nan"], ["--timeout nan:", "from 0 to 864000"]),
    (["--timeout", "-1"], ["--timeout -1:", "from 0 to 864000"]),
    (["--timeout", "inf"], ["--timeout inf:", "from 0 to 864000"]),
])
def test_hostile_numbers_in_run_options_are_one_line_errors(tmp_path, capsys, monkeypatch, options, words):
    """5000 digits ended in int()'s ValueError, other scripts' digits were taken ("--seconds ٥" ran 5 s),
    realtime=nan hung 12 s: now one line naming the option and its range, exit 1, nothing run."""
    monkeypatch.chdir(tmp_path)
    source = program(tmp_path)
    before = source.read_bytes()
    refused(capsys, ["run", source, *options], *words)
    assert source.read_bytes() == before
    assert not (tmp_path / "t.csv").exists()


@pytest.mark.parametrize(("setting", "words"), [
    (f"1.11={BIG}", ["--set 1.11=999", "to 4294967295"]),
    ("1.11=\u0665", ["--set 1.11=\u0665:", "to 4294967295"]),
    (f"1.11=1@{BIG}", ["time", "from 0 to"]),
])
def test_hostile_numbers_in_dpl_settings(tmp_path, capsys, setting, words):
    source = program(tmp_path, DPL, name="p.dpl")
    refused(capsys, ["run", source, "--seconds", "0.1", "--set", setting], *words)


@pytest.mark.parametrize(("options", "words"), [
    (["--intervals", "\u0664\u0660"], ["--intervals", "\u0664\u0660"]),
    (["--intervals", BIG], ["--intervals", "(5000 characters)"]),
    (["--master-length", "\u0663\u0660"], ["--master-length"]),
    (["--cycles-per-min", "nan"], ["--cycles-per-min"]),
    (["--slave-stop", BIG], ["--slave-stop", "(5000 characters)"]),
])
def test_hostile_numbers_in_cam_build(tmp_path, capsys, options, words):
    """`cam build --intervals ٤٠` built 40 intervals."""
    out = tmp_path / "c.zbc"
    refused(capsys, ["cam", "build", *CURVE, *options, "-o", out], *words)
    assert not out.exists()


@pytest.mark.parametrize(("options", "words"), [
    (["--set", "KPROP=\u0665"], ["--set KPROP=\u0665:", "to 4294967295"]),
    (["--set", f"KPROP={BIG}"], ["--set KPROP=999", "(5000 characters)"]),
])
def test_hostile_numbers_in_params(capsys, options, words):
    refused(capsys, ["params", "--link", "sim", *options], *words)


@pytest.mark.parametrize(("options", "words"), [
    (["--listen", "fc:socket://127.0.0.1:99999"], ["99999", "from 0 to 65535"]),
    (["--listen", f"fc:socket://127.0.0.1:{BIG}"], ["(5000 characters)", "from 0 to 65535"]),
    (["--listen", "fc:socket://127.0.0.1:\u0665"], ["\u0665", "from 0 to 65535"]),
    (["--listen", "canopen:slcan:socket://127.0.0.1:99999"], ["99999", "from 0 to 65535"]),
    (["--listen", "fc:socket://127.0.0.1:0", "--speed", "inf"], ["--speed inf:", "above 0"]),
    (["--listen", "fc:socket://127.0.0.1:0", "--timeout", "nan"], ["--timeout nan:", "above 0"]),
    (["--listen", "fc:socket://127.0.0.1:0", "--timeout", "-1"], ["--timeout -1:", "above 0"]),
    (["--listen", "fc:socket://127.0.0.1:0", "--node", "\u0662"], ["--node \u0662:", "from 1 to 32"]),
    (["--listen", "fc:socket://127.0.0.1:0", "--node", BIG], ["--node 999", "from 1 to 32"]),
])
def test_hostile_numbers_in_drive_options(capsys, options, words):
    """`drive --listen …:99999` raised OverflowError, a CANopen listener on a bad port said "HubBus was not
    properly shut down", `--speed inf` froze the clock; all are refused before the drive starts."""
    line = refused(capsys, ["drive", *options], *words)
    assert "HubBus" not in line


# --- 3: writes that fail -------------------------------------------------------------------------------------------
def limited(limit: int):
    """A child with a file-size limit of `limit` bytes (`ulimit -f`) that gets EFBIG instead of SIGXFSZ."""
    def preexec():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    return preexec


def motiontool_limited(limit: int, *args, cwd=None):
    return subprocess.run([sys.executable, "-m", "motiontool", *map(str, args)], capture_output=True, text=True,
                          timeout=120, preexec_fn=limited(limit), cwd=cwd)


def assert_write_refused(proc, target, old: bytes | None, reason: str = "File too large"):
    assert proc.returncode == 1, proc.stderr
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1 and f"cannot write {target}" in lines[0] and reason in lines[0], proc.stderr
    if old is None:
        assert not target.exists()
    else:
        assert target.read_bytes() == old  # the old content, not a truncated new one
    assert not list(target.parent.glob(f".{target.name}.*.tmp"))


@pytest.mark.slow  # several seconds on an idle machine: make test runs it, make test-fast does not
def test_writes_beyond_the_file_size_limit_fail_cleanly(tmp_path, capsys):
    """`ulimit -f 1`: `cam build/import -o` ended in tracebacks, `run --trace` and `cam export -o` exited 0 with a
    truncated file. Each old file is kept: the new one is written beside it and renamed only when complete."""
    zbc = curve_file(tmp_path, capsys)
    dat = tmp_path / "c.dat"
    assert cli.main(["cam", "export", str(zbc), "-o", str(dat)]) == 0
    source = program(tmp_path, LOOP)
    trace, old_trace = tmp_path / "t.csv", b"old trace\n"
    trace.write_bytes(old_trace)
    small = len(old_trace) + 50
    assert_write_refused(motiontool_limited(small, "run", source, "--seconds", "1", "--trace", trace), trace,
                         old_trace)
    dpl = program(tmp_path, DPL, name="p.dpl")
    assert_write_refused(motiontool_limited(small, "run", dpl, "--seconds", "1", "--trace", trace), trace, old_trace)
    old_dat, old_zbc = dat.read_bytes(), zbc.read_bytes()
    assert_write_refused(motiontool_limited(100, "cam", "export", zbc, "-o", dat), dat, old_dat)
    assert_write_refused(motiontool_limited(100, "cam", "import", dat, "-o", zbc), zbc, old_zbc)
    assert_write_refused(motiontool_limited(100, "cam", "build", *CURVE[:1], "B", *CURVE[2:], "-o", zbc), zbc,
                         old_zbc)
    image = tmp_path / "p.img"
    assert_write_refused(motiontool_limited(10, "compile", program(tmp_path), "-o", image), image, None)


@pytest.mark.parametrize("name", ["x" * 300 + ".zbc", "/".join(["d" * 200] * 25) + "/c.zbc"])
def test_names_beyond_name_max_and_path_max_are_one_line_errors(tmp_path, capsys, name):
    """A name longer than NAME_MAX (or a path beyond PATH_MAX) ended in an OSError traceback."""
    target = tmp_path / name
    zbc = curve_file(tmp_path, capsys)
    dat = tmp_path / "c.dat"
    assert cli.main(["cam", "export", str(zbc), "-o", str(dat)]) == 0
    source = program(tmp_path)
    dpl = program(tmp_path, DPL, name="p.dpl")
    for args in (["cam", "build", *CURVE, "-o", target], ["cam", "import", dat, "-o", target],
                 ["cam", "export", zbc, "-o", target], ["compile", source, "-o", target],
                 ["run", source, "--trace", target], ["run", source, "--record", target],
                 ["run", dpl, "--seconds", "0.1", "--trace", target]):
        refused(capsys, args, "cannot write", "too long")


# --- any hostile text ---------------------------------------------------------------------------------------------

HOSTILE = st.one_of(
    st.sampled_from(["nan", "inf", "-inf", "1e999", "\u0665", "\u00b2", "\u0664\u0660", "-0", "0x", "", " ", BIG,
                     "0x" + "f" * 5000, "1" + "0" * 40, "-1", "99999"]),
    st.text(alphabet=st.sampled_from("0123456789.-+ex\u0665\u00b2\u0662:=@#,"), max_size=40))
NUMERIC = [  # (sub-command and fixed arguments, the option, how its value is written)
    (["run", "{p}"], "--seconds", "{v}"), (["run", "{p}", "--trace", "{t}"], "--interval", "{v}"),
    (["run", "{p}"], "--set", "KPROP={v}"), (["run", "{p}"], "--input", "{v}=1@{v}"),
    (["run", "{p}", "--trace", "{t}"], "--signals", "{v}"), (["run", "{p}"], "--node", "{v}:{p}"),
    (["run", "{p}"], "--link", "sim,realtime={v}"), (["run", "{p}"], "--link", "fc:socket://127.0.0.1:1#{v}"),
    (["run", "{d}"], "--set", "1.11={v}@{v}"), (["params", "--link", "sim"], "--set", "KPROP={v}"),
    (["cam", "build", *CURVE, "-o", "{t}"], "--intervals", "{v}"),
    (["cam", "build", *CURVE, "-o", "{t}"], "--master-length", "{v}"),
]


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=st.sampled_from(NUMERIC), value=HOSTILE)
def test_hostile_text_never_ends_in_a_traceback(tmp_path, capsys, case, value):
    """Any text for a numeric option: exit 0, 1 or 2, never a traceback, the inputs unchanged."""
    source = program(tmp_path)  # ends at once: an accepted --seconds 99999 costs nothing
    dpl = program(tmp_path, DPL, name="p.dpl")
    before = source.read_bytes(), dpl.read_bytes()
    fixed, option, form = case
    names = {"p": str(source), "d": str(dpl), "t": str(tmp_path / "t.csv")}
    args = [a.format(**names) for a in fixed] + [option, form.format(v=value, **names)]
    if args[0] == "run":
        args += ["--seconds", "0.05"] if option != "--seconds" else []
    try:
        code = cli.main(args)
    except SystemExit as exc:  # argparse's own refusals (an option value that looks like an option)
        code = exc.code
    err = capsys.readouterr().err
    assert code in (0, 1, 2) and "Traceback" not in err, (args, err)
    assert (source.read_bytes(), dpl.read_bytes()) == before
