"""Crafted files against the commands that read them, each in its own process under `ulimit -v 4000000`
(issue 26, done-when: no crafted file of at most 2 MB makes any command take more than 10 s or 1 GB, and every
refusal names the file, the field and the limit).

The shapes are benchmarks/fuzz_files.py's hostile cases (sizes declared far beyond the data, zlib bombs, deep
parentheses, a BOM with CRLF). A .dat goes to `motiontool cam import`, a .zbc to `motiontool cam info` and
`motiontool run --config`, a DPL program to `motiontool check`; the formats only the IDE reads (.zbo, program
images) go to the IDE's reader in a bare Python process.

    .venv/bin/python benchmarks/hostile_files.py

prints one line per case and command (`hostile_<case>_<command>: S s, M MB, exit E`) and the worst figures; exits
1 when a case takes more than 10 s or 1 GB, or a refusal is not one line naming the file and the limit.
"""

from __future__ import annotations

import importlib.util
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ADDRESS_SPACE = 4_000_000 * 1024          # ulimit -v 4000000 (KiB)
MAX_SECONDS, MAX_MB, MAX_FILE = 10.0, 1024, 2 << 20


def _fuzz_files():
    spec = importlib.util.spec_from_file_location("motiontool_fuzz_files", ROOT / "benchmarks" / "fuzz_files.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


READER = {"zbo": "from motiontool.scope.zbo import load; load(sys.argv[1])",
          "image": "from motiontool.aposs.image import ProgramImage; "
                   "ProgramImage.from_bytes(open(sys.argv[1], 'rb').read())"}
IDE = [sys.executable, "-c", "import sys\ntry:\n    {}\nexcept Exception as exc:\n"
       "    print(exc, file=sys.stderr); sys.exit(1)"]


def commands(fmt: str, path: Path, folder: Path) -> list[tuple[str, list[str]]]:
    tool = [sys.executable, "-m", "motiontool"]
    if fmt == "dat":
        return [("cam_import", [*tool, "cam", "import", "-o", str(folder / "out.zbc"), str(path)])]
    if fmt == "zbc":
        program = folder / "idle.m"
        program.write_text("DELAY 1\n")
        return [("cam_info", [*tool, "cam", "info", str(path)]),
                ("run_config", [*tool, "run", str(program), "--seconds", "0.01", "--config", str(path)])]
    if fmt == "dpl":
        return [("check", [*tool, "check", str(path)])]
    return [("ide_reader", [IDE[0], IDE[1], IDE[2].format(READER[fmt]), str(path)])]


def limit() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


def run(argv: list[str]) -> tuple[int, str, float]:
    started = time.monotonic()
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=limit,
                            cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    try:
        out, err = proc.communicate(timeout=MAX_SECONDS * 3)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
    return proc.returncode, out + err, time.monotonic() - started   # check prints its diagnostics on stdout


def main() -> int:
    fuzz = _fuzz_files()
    failures: list[str] = []
    worst_s = worst_mb = 0.0
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        for name, fmt, data, words in fuzz.hostile_cases():
            if len(data) > MAX_FILE:
                print(f"# {name}: {len(data)} bytes, beyond the 2 MB of the question; still run")
            suffix = {"image": ".mti", "dpl": ".dpl"}.get(fmt, f".{fmt}")
            path = folder / f"case{suffix}"
            path.write_bytes(data)
            for command, argv in commands(fmt, path, folder):
                before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
                code, err, seconds = run(argv)
                peak = max(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, before) / 1024
                key = "".join(c if c.isalnum() else "_" for c in name.lower())
                print(f"hostile_{key}_{command}: {seconds:.2f} s, {peak:.0f} MB (children's peak so far), "
                      f"exit {code}")
                worst_s, worst_mb = max(worst_s, seconds), max(worst_mb, peak)
                lines = [line for line in err.splitlines() if line.strip()]
                if seconds > MAX_SECONDS or peak > MAX_MB:
                    failures.append(f"{name} ({command}): {seconds:.1f} s, {peak:.0f} MB")
                if words is None:
                    if code != 0:
                        failures.append(f"{name} ({command}): a valid file was refused: {err.strip()[:200]}")
                elif code != 1 or len(lines) != 1 or not all(w in lines[0] for w in words) \
                        or (fmt != "image" and str(path) not in lines[0]):
                    failures.append(f"{name} ({command}): exit {code}, stderr {err.strip()[:300]!r}")
    print(f"hostile_files_worst_seconds: {worst_s:.2f} s")
    print(f"hostile_files_worst_peak: {worst_mb:.0f} MB")
    for failure in failures:
        print(f"FAILED {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
