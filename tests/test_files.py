"""Saves and reads as a user meets them through the `motiontool` command (issue 18, items 5, 7, 8).

Saves are atomic and keep what the user had: the target's mode (a new file gets the umask's), a symbolic link stays
a link, and temporary files a killed save left behind are removed. Readers refuse what would never end (devices,
pipes) or exhaust memory (files beyond a size limit) with a clear error, and read digits only in ASCII.
"""

from __future__ import annotations

import os
import stat
import time

import pytest

from motiontool import cli
from motiontool.aposs import preprocess
from motiontool.formats import zbc

PROGRAM = 'PRINT "hello"\n'
STAMPING = ["--name", "stamping", "--master-length", "4000", "--intervals", "40", "--point", "0,0,C",
            "--point", "1500,1200,T", "--point", "2500,2400,T", "--point", "4000,3600,C"]


def program(tmp_path, text: str = PROGRAM):
    path = tmp_path / "p.m"
    path.write_text(text, encoding="utf-8")
    return path


def mode(path) -> int:
    return stat.S_IMODE(os.stat(path).st_mode)


# --- atomic saves -------------------------------------------------------------------------------------------------
def test_a_save_keeps_the_mode_of_the_file_it_replaces(tmp_path, capsys):
    source, image = program(tmp_path), tmp_path / "p.img"
    image.write_bytes(b"old")
    os.chmod(image, 0o644)
    assert cli.main(["compile", str(source), "-o", str(image)]) == 0
    assert mode(image) == 0o644  # was 0600 after every save
    assert image.read_bytes().startswith(b"MTIMG")
    os.chmod(image, 0o640)
    assert cli.main(["compile", str(source), "-o", str(image)]) == 0
    assert mode(image) == 0o640


def test_a_new_file_gets_the_mode_the_umask_gives(tmp_path, capsys):
    source = program(tmp_path)
    old = os.umask(0o027)
    try:
        assert cli.main(["compile", str(source), "-o", str(tmp_path / "new.img")]) == 0
    finally:
        os.umask(old)
    assert mode(tmp_path / "new.img") == 0o640


def test_a_save_through_a_symbolic_link_replaces_its_target(tmp_path, capsys):
    source = program(tmp_path)
    (tmp_path / "images").mkdir()
    real = tmp_path / "images" / "real.img"
    real.write_bytes(b"old")
    link = tmp_path / "current.img"
    link.symlink_to(real)
    assert cli.main(["compile", str(source), "-o", str(link)]) == 0
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert real.read_bytes().startswith(b"MTIMG")
    dangling = tmp_path / "later.img"
    dangling.symlink_to(tmp_path / "images" / "later.img")
    assert cli.main(["compile", str(source), "-o", str(dangling)]) == 0
    assert dangling.is_symlink() and (tmp_path / "images" / "later.img").read_bytes().startswith(b"MTIMG")
    assert sorted(p.name for p in (tmp_path / "images").iterdir()) == ["later.img", "real.img"]  # no temp left


def test_temporary_files_of_a_killed_save_are_removed_by_the_next_save(tmp_path, capsys):
    source, image = program(tmp_path), tmp_path / "p.img"
    an_hour_ago = time.time() - 3600 * 2
    dead_writer = tmp_path / ".p.img.999999999-0123abcd.tmp"       # our pattern, its process is gone
    old_version = tmp_path / ".p.img.k3j9_x2a.tmp"                  # the pattern of earlier versions, old
    fresh = tmp_path / f".p.img.{os.getpid()}-89abcdef.tmp"         # a save in progress (this process)
    foreign = tmp_path / ".p.img.backup.tmp"                        # not ours: never touched
    other_file = tmp_path / ".q.img.999999999-0123abcd.tmp"         # another file's: not this save's business
    for path in (dead_writer, old_version, fresh, foreign, other_file):
        path.write_bytes(b"x" * 1000)
        os.utime(path, (an_hour_ago, an_hour_ago))
    os.utime(fresh, None)
    assert cli.main(["compile", str(source), "-o", str(image)]) == 0
    left = {p.name for p in tmp_path.iterdir()}
    assert dead_writer.name not in left and old_version.name not in left
    assert {fresh.name, foreign.name, other_file.name} <= left


def test_run_record_without_recordings_writes_the_header_atomically(tmp_path, capsys):
    source, record = program(tmp_path), tmp_path / "rec.csv"
    record.write_text("old\n")
    os.chmod(record, 0o644)
    assert cli.main(["run", str(source), "--seconds", "0.1", "--record", str(record)]) == 0
    assert record.read_text() == "time_ms\n"
    assert mode(record) == 0o644


# --- bounded reads ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("command", [["check"], ["run", "--seconds", "0.1"], ["compile", "-o", "x.img"]])
def test_a_device_is_refused_as_a_program(tmp_path, capsys, command):
    """`check /dev/zero` ended in MemoryError: a device or pipe would never end."""
    assert cli.main([*command, "/dev/zero"] if command[0] == "check" else
                    [command[0], "/dev/zero", *command[1:]]) == 1
    out = capsys.readouterr()
    assert "/dev/zero:1:1: error: cannot read '/dev/zero': not a regular file" in out.out + out.err


def test_a_pipe_is_refused_without_waiting_for_a_writer(tmp_path, capsys):
    fifo = tmp_path / "p.m"
    os.mkfifo(fifo)
    assert cli.main(["check", str(fifo)]) == 1
    assert "not a regular file" in capsys.readouterr().out


def test_run_config_and_cam_info_refuse_a_device(tmp_path, capsys):
    """`run --config /dev/zero` grew until the OOM killer; `cam info /dev/zero` ended in MemoryError."""
    assert cli.main(["run", str(program(tmp_path)), "--config", "/dev/zero"]) == 1
    assert "/dev/zero: cannot read: not a regular file" in capsys.readouterr().err
    assert cli.main(["cam", "info", "/dev/zero"]) == 1
    assert "cam info: error: /dev/zero: cannot read: not a regular file" in capsys.readouterr().err


def test_files_beyond_the_size_limit_are_refused_before_they_are_read(tmp_path, capsys):
    big = tmp_path / "big.m"
    with open(big, "wb") as f:  # sparse: costs no disk
        f.truncate(preprocess.MAX_SOURCE_BYTES + 1)
    assert cli.main(["check", str(big)]) == 1
    assert "16 MiB, more than the 16 MiB a program file may have" in capsys.readouterr().out
    big_config = tmp_path / "big.zbc"
    with open(big_config, "wb") as f:
        f.truncate(zbc.MAX_BYTES + 1)
    assert cli.main(["cam", "info", str(big_config)]) == 1
    assert "more than the 64 MiB a configuration file may have" in capsys.readouterr().err


# --- numbers ------------------------------------------------------------------------------------------------------
def test_digits_of_other_scripts_are_not_numbers_in_a_configuration(tmp_path, capsys):
    """`KPROP = ٥٠` loaded as 50 (Python's \\d and int() take every script's digits)."""
    conf = tmp_path / "c.zbc"
    conf.write_text("# motiontool configuration file, format 1\n[axis]\n32-60 KPROP = \u0665\u0660\n[end]\n",
                    encoding="utf-8")
    assert cli.main(["run", str(program(tmp_path)), "--config", str(conf)]) == 1
    assert "c.zbc:3: 32-60 KPROP" in capsys.readouterr().err
    conf.write_text("# motiontool configuration file, format 1\n[array a]\nsize = \u0662\nvalues = 1 2\n[end]\n",
                    encoding="utf-8")
    assert cli.main(["cam", "info", str(conf)]) == 1
    assert "c.zbc:3: array a: size" in capsys.readouterr().err


def test_digits_of_other_scripts_and_giant_numbers_in_a_curve_export(tmp_path, capsys):
    conf, dat = tmp_path / "c.zbc", tmp_path / "curve.dat"
    assert cli.main(["cam", "build", *STAMPING, "-o", str(conf)]) == 0
    assert cli.main(["cam", "export", str(conf), "-o", str(dat)]) == 0
    good = dat.read_text().splitlines()
    for k, bad in ((2, "intervals = \u0664\u0660"), (7, "\u0661"), (8, "9" * 5000), (2, "intervals = \u00b2")):
        lines = list(good)
        lines[k] = bad
        dat.write_text("\n".join(lines) + "\n", encoding="utf-8")
        assert cli.main(["cam", "import", str(dat), "-o", str(tmp_path / "out.zbc")]) == 1
        err = capsys.readouterr().err
        assert err.startswith(f"motiontool cam import: error: {dat}:{k + 1}: "), err
        assert "Traceback" not in err
