"""The project rule "source files under 600 lines" (issue 27): every .py file under src/, tests/ and benchmarks/
has at most MAX_LINES lines; a longer one is split by concept (as benchmarks/fuzz_compiler.py was)."""

from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
TREES = ("src", "tests", "benchmarks")
MAX_LINES = 600


def oversized(root: Path) -> list[str]:
    """'path: N lines' for each .py file under root's TREES longer than MAX_LINES, path relative to root."""
    found = []
    for tree in TREES:
        for path in sorted((root / tree).rglob("*.py")):
            lines = len(path.read_text(encoding="utf-8").splitlines())
            if lines > MAX_LINES:
                found.append(f"{path.relative_to(root).as_posix()}: {lines} lines")
    return found


def test_no_python_file_is_longer_than_600_lines():
    assert oversized(REPO) == [], f"files over {MAX_LINES} lines (split them by concept)"


def test_the_check_counts_lines_and_names_the_file(tmp_path):
    for tree in TREES:
        (tmp_path / tree / "pkg").mkdir(parents=True)
        (tmp_path / tree / "pkg" / "limit.py").write_text("x = 1\n" * MAX_LINES, encoding="utf-8")
    (tmp_path / "benchmarks" / "pkg" / "long.py").write_text("x = 1\n" * (MAX_LINES + 1), encoding="utf-8")
    (tmp_path / "src" / "pkg" / "notes.txt").write_text("x\n" * 1000, encoding="utf-8")
    assert oversized(tmp_path) == [f"benchmarks/pkg/long.py: {MAX_LINES + 1} lines"]
