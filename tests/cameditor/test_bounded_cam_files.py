"""Issue 26 item 4: .dat and .zbc readers and `cam build` refuse sizes beyond the controller's array memory before
they allocate anything (decisions R15): one line naming the file, the field and the limit, exit 1, inputs kept."""

from __future__ import annotations

import resource
import subprocess
import sys

import pytest

from motiontool.camcurve.model import MAX_ARRAY_ELEMENTS, MAX_INTERVALS
from motiontool.formats.dat import dat_text
from tests.camcurve.conftest import stamping_curve
from tests.cameditor.test_camcli import STAMPING

GB = 1 << 30


def _limited() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (GB, GB))


def motiontool(*argv: str, cwd=None) -> subprocess.CompletedProcess:
    """The command line in a child limited to 1 GB of address space (the bombs took 2.5 GB)."""
    return subprocess.run([sys.executable, "-m", "motiontool", *argv], capture_output=True, text=True, cwd=cwd,
                          preexec_fn=_limited, timeout=300)


def _one_line_refusal(result: subprocess.CompletedProcess, *words: str) -> None:
    assert result.returncode == 1, result.stderr
    assert "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    for word in words:
        assert word in result.stderr, result.stderr


def test_the_array_limit_is_the_simulated_controllers():
    from motiontool.kernel.arrays import MAX_ARRAY_ELEMENTS as KERNEL

    assert MAX_ARRAY_ELEMENTS == KERNEL


def test_a_dat_declaring_ten_million_intervals_is_refused_at_its_header(tmp_path):
    dat = tmp_path / "c.dat"
    dat.write_text(dat_text(stamping_curve()).replace("intervals = 40", "intervals = 10000000"))
    before = dat.read_bytes()
    result = motiontool("cam", "import", str(dat), "-o", str(tmp_path / "out.zbc"))
    _one_line_refusal(result, str(dat), "intervals", str(MAX_INTERVALS))
    assert dat.read_bytes() == before and not (tmp_path / "out.zbc").exists()


def test_a_dat_declaring_more_elements_than_the_array_memory_is_refused(tmp_path):
    dat = tmp_path / "c.dat"
    dat.write_text(dat_text(stamping_curve()).replace("elements = 92", "elements = 999999999"))
    result = motiontool("cam", "import", str(dat), "-o", str(tmp_path / "out.zbc"))
    _one_line_refusal(result, str(dat), "elements", str(MAX_ARRAY_ELEMENTS))


def test_a_zbc_curve_of_10_to_the_8_intervals_is_refused_by_export(tmp_path):
    zbc = tmp_path / "c.zbc"
    assert motiontool("cam", "build", *STAMPING, "-o", str(zbc)).returncode == 0
    text = zbc.read_text()
    zbc.write_text(text.replace("intervals = 40", "intervals = 100000000"))
    before = zbc.read_bytes()
    result = motiontool("cam", "export", str(zbc), "-o", str(tmp_path / "c.dat"))
    _one_line_refusal(result, str(zbc), "intervals", str(MAX_INTERVALS))
    assert zbc.read_bytes() == before and not (tmp_path / "c.dat").exists()


def test_zbc_arrays_beyond_the_array_memory_are_refused_at_their_size_line(tmp_path):
    zbc = tmp_path / "a.zbc"
    zbc.write_text("# motiontool configuration file, format 1\n[array a]\nsize = 2\nvalues = 1 2\n[array b]\n"
                   f"size = {MAX_ARRAY_ELEMENTS - 1}\n[end]\n")
    result = motiontool("cam", "info", str(zbc))
    _one_line_refusal(result, f"{zbc}:6", "array b", str(MAX_ARRAY_ELEMENTS))


def test_forty_thousand_one_element_arrays_are_read_in_linear_time(tmp_path):
    """A list scan per [array] section made this 100 s; a CPU limit far above the linear reader's second (not a
    wall-clock assertion: a busy machine does not fail it)."""
    lines = ["# motiontool configuration file, format 1"]
    for k in range(40_000):
        lines += [f"[array a{k}]", "size = 1", "values = 0"]
    zbc = tmp_path / "many.zbc"
    zbc.write_text("\n".join([*lines, "[end]"]) + "\n")
    code = ("import resource, sys; resource.setrlimit(resource.RLIMIT_CPU, (20, 20));"
            "from motiontool.formats.zbc import read_config; print(len(read_config(sys.argv[1]).arrays))")
    result = subprocess.run([sys.executable, "-c", code, str(zbc)], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0 and result.stdout == "40000\n", result.stderr


@pytest.mark.parametrize(("options", "words"), [
    (["--intervals", str(MAX_INTERVALS)], ["intervals", str(MAX_ARRAY_ELEMENTS)]),
    (["--intervals", "4000000"], ["--intervals", str(MAX_INTERVALS)]),
    (["--name", ""], ["--name", "1 to 16"]),
    (["--cycles-per-min", "1e-320"], ["cycles_per_min", "from 1"]),
])
def test_cam_build_refuses_what_the_controller_cannot_hold(tmp_path, options, words):
    out = tmp_path / "c.zbc"
    argv = [a for a in STAMPING]
    for option, value in zip(options[::2], options[1::2], strict=True):
        if option in argv:
            argv[argv.index(option) + 1] = value
        else:
            argv += [option, value]
    result = motiontool("cam", "build", *argv, "-o", str(out))
    _one_line_refusal(result, *words)
    assert not out.exists()
