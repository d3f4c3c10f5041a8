"""One sha256 per simulated second of a run's rows: the fingerprint the trace-identity tests of the MCO kernel
(tests/kernel/trace_identity.py) and of the APC (tests/apc/trace_identity.py) compare with their golden files."""

from __future__ import annotations

import hashlib


class SecondHashes:
    """Rows (one per ms) hashed by repr, so a change in the last bit of a float shows; one hash per 1000 rows."""

    def __init__(self) -> None:
        self.seconds: list[str] = []
        self.rows = 0
        self._hash = hashlib.sha256()

    def add(self, rows: list[tuple]) -> None:
        self._hash.update(repr(rows).encode())
        self.rows += 1
        if self.rows % 1000 == 0:
            self.seconds.append(self._hash.hexdigest()[:16])
            self._hash = hashlib.sha256()

    def finish(self) -> dict:
        """{"ms", "seconds"} with the last, partial second's hash."""
        if self.rows % 1000:
            self.seconds.append(self._hash.hexdigest()[:16])
        return {"ms": self.rows, "seconds": self.seconds}


def text_hash(lines: list[str]) -> str:
    return hashlib.sha256("\n".join(lines).encode()).hexdigest()[:16]


def first_different_second(name: str, got: dict, want: dict) -> str | None:
    """None when both runs have the same rows; else where the first difference is."""
    if got["ms"] != want["ms"]:
        return f"{name}: {got['ms']} ms run, {want['ms']} ms in the golden file"
    first = next((i for i, (a, b) in enumerate(zip(got["seconds"], want["seconds"], strict=True)) if a != b), None)
    return None if first is None else \
        f"{name}: the trace differs in second {first} (ms {first * 1000}..{first * 1000 + 999})"
