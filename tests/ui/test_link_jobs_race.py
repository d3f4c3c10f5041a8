"""wait_off_gui's quick answers (ui/link_jobs.py): an answer that is in the box before the GUI thread first looks
must not let the relay be deleted while the worker thread still emits from it. Under load that crashed a test
worker (a segfault in wait_off_gui); here 3 000 instant requests with the deferred deletes run at once after each
crashed every time before the fix. In a process of its own, so a crash is a failure, not a lost worker."""

from __future__ import annotations

import os
import subprocess
import sys

PROBE = """
from PySide6.QtCore import QCoreApplication, QEvent
from PySide6.QtWidgets import QApplication
app = QApplication([])
from motiontool.ui.link_jobs import wait_off_gui
for i in range(3000):
    assert wait_off_gui(lambda: i) == i
    QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
print("answered 3000")
"""


def test_instant_answers_never_crash_the_wait():
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}
    proc = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, timeout=120, env=env)
    assert (proc.returncode, proc.stdout.strip()) == (0, "answered 3000"), proc.stderr[-2000:]
