"""Where a test's screenshot goes: $MOTIONTOOL_SHOTS when set (a person looking at them, or
`MOTIONTOOL_SHOTS=docs/screenshots` to refresh the documentation's), else the temporary folder: a test run never
writes into the checkout."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path


def shot_path(name: str) -> Path:
    folder = Path(os.environ.get("MOTIONTOOL_SHOTS") or tempfile.gettempdir())
    folder.mkdir(parents=True, exist_ok=True)
    return folder / name
