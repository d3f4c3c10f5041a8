"""Issue 26 item 4: .zbo files and program images declaring far more than they hold, and compressed bombs, are
refused with a line naming the file, the field and the limit, in a child limited to 1 GB (decisions R16)."""

from __future__ import annotations

import base64
import json
import resource
import subprocess
import sys
import zlib

import pytest

from motiontool.aposs.image import MAGIC, MAX_BODY_BYTES
from motiontool.scope import zbo
from tests.scope.test_files import example_scope

GB = 1 << 30


def _limited() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (GB, GB))


def _load_in_child(code: str, path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True, text=True,
                          preexec_fn=_limited, timeout=300)


ZBO = ("import sys\nfrom motiontool.scope import zbo\ntry:\n    zbo.load(sys.argv[1])\n"
       "except zbo.ZboError as exc:\n    print(exc)\n")


def _bomb(size: int) -> str:
    """``size`` zero bytes, deflated and in base64: 1 GiB is some 1.4 MB of text."""
    inflate = zlib.compressobj(9)
    chunk = bytes(1 << 20)
    parts = [inflate.compress(chunk) for _ in range(size // len(chunk))]
    return base64.b64encode(b"".join(parts) + inflate.flush()).decode("ascii")


def _doc(capacity: int, count: int, values: str | None = None) -> dict:
    doc = json.loads(zbo.dumps(example_scope()))
    curve = doc["curves"][0]
    curve["capacity"] = capacity
    curve["data"]["count"] = count
    if values is not None:
        curve["data"]["values"] = values
    return doc


def test_a_capacity_of_10_to_the_8_is_refused_before_the_buffer_is_allocated(tmp_path):
    path = tmp_path / "big.zbo"
    path.write_text(json.dumps(_doc(100_000_000, 4)))
    result = _load_in_child(ZBO, path)
    assert result.returncode == 0 and "Traceback" not in result.stderr, result.stderr
    assert str(path) in result.stdout and "capacity" in result.stdout and str(zbo.MAX_SAMPLES) in result.stdout


def test_capacities_of_all_curves_are_bounded_together(tmp_path):
    doc = _doc(zbo.MAX_SAMPLES, 4)
    doc["curves"][1]["capacity"] = zbo.MAX_SAMPLES
    doc["curves"][2]["capacity"] = zbo.MAX_SAMPLES
    path = tmp_path / "three.zbo"
    path.write_text(json.dumps(doc))
    result = _load_in_child(ZBO, path)
    assert "curves[2].capacity" in result.stdout and str(zbo.MAX_FILE_SAMPLES) in result.stdout, result


@pytest.mark.slow  # several seconds on an idle machine: make test runs it, make test-fast does not
def test_a_curve_inflating_to_a_gib_stops_at_its_count(tmp_path):
    path = tmp_path / "bomb.zbo"
    path.write_text(json.dumps(_doc(10_000, 4, _bomb(GB))))
    assert path.stat().st_size < 2_000_000
    result = _load_in_child(ZBO, path)
    assert result.returncode == 0 and "Traceback" not in result.stderr, result.stderr
    assert str(path) in result.stdout and "data.values" in result.stdout and "more than the 4 values" in result.stdout


IMAGE = ("import sys\nfrom motiontool.aposs.image import ImageError, ProgramImage\ntry:\n"
         "    ProgramImage.from_bytes(open(sys.argv[1], 'rb').read())\nexcept ImageError as exc:\n    print(exc)\n")


def test_a_program_image_inflating_beyond_its_limit_is_refused_before_it_is_parsed(tmp_path):
    """250 MB of JSON objects took 3.8 GB to parse; the body is refused at MAX_BODY_BYTES + 1 inflated bytes."""
    body = b'{"code":[' + b"{}," * ((MAX_BODY_BYTES + (1 << 20)) // 3) + b"{}]}"
    path = tmp_path / "bomb.img"
    path.write_bytes(MAGIC + bytes([1]) + zlib.compress(body, 9))
    del body
    result = _load_in_child(IMAGE, path)
    assert result.returncode == 0 and "Traceback" not in result.stderr, result.stderr
    assert f"more than {MAX_BODY_BYTES} bytes" in result.stdout
