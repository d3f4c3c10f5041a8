"""Browsing a large recording (issue 8): 8 curves × 10 M samples, panning and zooming; prints
`scope_browse_fps` (goal ≥ 30 fps) and the first draw, which builds the min/max pyramids. The same measurement
is part of benchmarks/scope_render.py."""

import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
sys.path.insert(0, os.path.dirname(__file__))

from PySide6.QtWidgets import QApplication  # noqa: E402

from scope_render import browse  # noqa: E402


def main() -> None:
    app = QApplication.instance() or QApplication(sys.argv)
    fps, build = browse(app)
    print(f"scope_browse_fps: {fps:.1f} fps")
    print(f"scope_browse_first_draw: {build:.2f} s")


if __name__ == "__main__":
    main()
