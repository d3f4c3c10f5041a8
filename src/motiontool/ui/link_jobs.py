"""Link requests the window makes off the GUI thread (decision I34): `LinkJobs.run(work, done)` for a view's reads,
`waiting(window, text, work)` for a command that needs the answer before it goes on, `wait_off_gui(work)` the same
without saying so. They live in `motiontool.qtjobs`, shared with the oscilloscope (`scope/ui/poll_job.py`), which
the layers keep from importing `ui/`; the IDE's modules import them from here."""

from __future__ import annotations

from motiontool.qtjobs.jobs import LinkJobs, wait_off_gui
from motiontool.qtjobs.waiting import _CommandGuard, waiting

__all__ = ["LinkJobs", "_CommandGuard", "wait_off_gui", "waiting"]
