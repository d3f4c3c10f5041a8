"""Running the oscilloscope (DG 4620-4712, 5859-5869): Start / Pause / Stop, the display refresh and poll timers,
the Free Run trigger and the Tune test move. A part of `ScopeWindow` (scope/ui/window.py), `window.run`: it owns
what a run is made of (acquisitions, trigger, timers, link jobs) and reaches the window's widgets through `window`."""

from __future__ import annotations

import contextlib
import threading
from typing import TYPE_CHECKING

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QProgressDialog

from motiontool.comms.protocol import LinkError
from motiontool.scope import derived
from motiontool.scope.acquisition import FreeRun, Polling, SingleShot
from motiontool.scope.tune import PID_PARAMETERS, Tune
from motiontool.scope.ui.dialogs import TriggerDialog
from motiontool.scope.ui.poll_job import PollJob, wait

if TYPE_CHECKING:
    from motiontool.scope.ui.window import ScopeWindow

LIST_EVERY = 4          # list values and title every 4th chart refresh while recording
LIVE_WINDOW_S = 10      # default time shown while recording (decision S32)
REFRESH_MS = 50         # display refresh while recording (LIST_EVERY: list and title)


class RunControl:
    """Start/Pause/Stop, timers, trigger and Tune of one ScopeWindow."""

    def __init__(self, window: ScopeWindow) -> None:
        self.window = window
        self.free_run: FreeRun | None = None
        self.polling = Polling(window.scope, None)
        self.single_shot: SingleShot | None = None
        self.tune: Tune | None = None
        self.paused = False
        self.trigger = None          # (curve name, Trigger) for Free Run, or None
        self.trigger_single = True
        self.recording_status = None
        self.live_window_ms = LIVE_WINDOW_S * 1000.0
        self._live_width: float | None = None
        self._ticks = 0
        # the timers are the window's children: they go with it
        self.refresh_timer = QTimer(window)
        self.refresh_timer.setInterval(REFRESH_MS)
        self.refresh_timer.timeout.connect(self.tick)
        self.poll_timer = QTimer(window)
        self.poll_timer.timeout.connect(self._poll)
        self.tune_timer = QTimer(window)
        self.tune_timer.setInterval(100)
        self.tune_timer.timeout.connect(self._tune_tick)
        self.poll_job = PollJob(window)                     # the polls' link requests, off the GUI thread
        self.status_job = PollJob(window, "scope-status")   # the Single Shot recording's progress
        self.tune_job = PollJob(window, "scope-tune")       # whether Tune's test move has ended

    @property
    def running(self) -> bool:
        return bool((self.free_run and self.free_run.running) or self.polling.running or
                    (self.single_shot and self.single_shot.running))

    def title(self) -> str:
        """What the window title says about the run: "" when nothing records."""
        if self.polling.running:
            return f" {self.polling.title()}"   # "[<poll ms>ms <load>%]" (DG 5416)
        if self.free_run is not None and self.free_run.running and self.free_run.link_dropped is not None:
            return f" [PDO: {self.free_run.link_dropped} lost]"   # a link that counts lost values (S31)
        if self.single_shot is not None and self.single_shot.running:
            rec = self.recording_status
            return " [recording]" if rec is None else f" [recording {rec.samples}/{rec.limit}]"
        return ""

    def feed(self, data) -> None:
        """Samples from the link (the GUI thread)."""
        if self.free_run is not None:
            self.free_run.feed(data)

    def curve_renamed(self, before: str, after: str) -> None:
        if self.trigger is not None and self.trigger[0] == before:
            self.trigger = (after, self.trigger[1])

    # --- run -------------------------------------------------------------------------------------------------
    def start(self) -> None:
        w, scope = self.window, self.window.scope
        link = w.link
        if link is None:
            w.prompts.warn("Oscilloscope", "No controller connected (Reconnect first).")
            return
        resume = self.paused
        if resume:
            span = scope.time_span()
            if span:
                scope.pauses.append(span[1])  # the red bar where recording resumed (DG 5943)
        else:
            scope.pauses.clear()
        self.paused = False
        try:
            if scope.variant == "single_shot":
                group = next((g for g in scope.groups if g.method == "single_shot" and g.active), None)
                if group is None:
                    raise ValueError("No active Single Shot group")
                self.single_shot = SingleShot(scope, link, group.name)
                self.single_shot.start(run=lambda request: wait(w, "Starting the Single Shot recording …",
                                                                request))
            else:
                groups = [g for g in scope.groups if g.method == "free_run" and g.active
                          and any(c.active for c in scope.members(g.name))]
                if groups:
                    self.free_run = FreeRun(scope, link, groups[0].name)
                    self.free_run.trigger, self.free_run.single = self.trigger, self.trigger_single
                    self.free_run.start(clear=not resume,
                                        run=lambda request: wait(w, "Starting the recording …", request))
                self.polling.link = link
                if self.polling.curves():
                    self.polling.start(clear=not resume)
                    self.poll_timer.setInterval(scope.settings.poll_ms)
                    self.poll_timer.start()
                if not groups and not self.polling.curves():
                    raise ValueError("No active curve to record: add a curve first")
        except (ValueError, LinkError) as exc:
            w.prompts.warn("Oscilloscope", str(exc)) if w.ask else None
            w.statusBar().showMessage(str(exc), 10000)
            return
        w.chart.live = True
        self._live_width = None   # the next tick sets the live window
        self.refresh_timer.start()
        w.update_title()

    def pause(self) -> None:
        if self.running and self.window.scope.variant != "single_shot":
            self.stop_acquisition()
            self.paused = True
            self._finish_run()

    def stop(self) -> None:
        """Stop ends only the recording; the program keeps running (DG 4627, 5859). Single Shot uploads now."""
        w = self.window
        was_single = self.single_shot is not None and self.single_shot.running
        self.stop_acquisition()
        if was_single:
            progress = QProgressDialog("Uploading the recording …", None, 0, 0, w)
            progress.setWindowTitle("Single Shot")
            progress.show()
            try:
                sets = self.single_shot.stop(run=lambda request: wait(w, "Uploading the recording …", request))
                w.statusBar().showMessage(f"Uploaded {sets} sample sets", 10000)
            except LinkError as exc:
                w.statusBar().showMessage(f"Upload failed: {exc}", 10000)
            progress.close()
        self.paused = False
        self._finish_run()

    def stop_acquisition(self) -> None:
        """The recording ends; nothing is uploaded or redrawn (closing the window, Pause)."""
        self.poll_timer.stop()
        self.polling.stop()
        if self.free_run is not None:
            with contextlib.suppress(LinkError):
                self.free_run.stop(run=lambda request: wait(self.window, "Stopping the recording …", request))

    def _finish_run(self) -> None:
        w = self.window
        self.refresh_timer.stop()
        w.chart.live = False
        w.chart.set_pauses(w.scope.pauses)
        w.zoom_reset()
        w.update_title()

    def trigger_dialog(self, *, dialog: TriggerDialog | None = None) -> None:
        """Set the Free Run trigger; a dialog given here has been filled in and accepted already."""
        w = self.window
        if dialog is None:
            dialog = TriggerDialog([c.name for c in w.scope.curves], w)
            dialog.exec()
        if dialog.result() != TriggerDialog.Accepted:
            return
        try:
            self.trigger = dialog.trigger()
        except ValueError as exc:
            w.prompts.warn("Trigger", str(exc))
            return
        self.trigger_single = dialog.single.isChecked()
        w.statusBar().showMessage("Trigger off" if self.trigger is None else
                                  f"Trigger: {self.trigger[0]} {self.trigger[1].edge} {self.trigger[1].level:g}",
                                  5000)

    def set_poll_ms(self, ms: int) -> None:
        self.window.scope.settings.poll_ms = ms
        if self.poll_timer.isActive():
            self.poll_timer.setInterval(ms)
        self.window.update_title()

    def set_live_window(self, seconds: int) -> None:
        self.live_window_ms = seconds * 1000.0
        self._live_width = None   # applied at the next refresh, also during a recording

    def delete_data(self) -> None:
        """Delete data: samples not saved yet are asked for first, Save / Discard / Cancel as on closing (issue 23
        item 11: they went without a word); saved ones can be loaded again."""
        if not self.window.confirm_unsaved():
            return
        self.window.scope.clear_data()
        self.window.redraw()

    def _poll(self) -> None:
        """Every poll_ms: the reads go on the poll thread, one poll at a time (on a slow line a poll is left out
        rather than queued: the window never waits for the wire, issue 27 item 2)."""
        if self.polling.running:
            run = self.polling.runs
            self.poll_job.run(self.polling.read, lambda result: self._polled(run, result))

    def _polled(self, run: int, result) -> None:
        if not self.polling.running or run != self.polling.runs:
            return          # stopped (and maybe started again) while the poll was on the line
        if isinstance(result, Exception):
            self.window.statusBar().showMessage(f"Polling stopped: {result}", 10000)
            self.stop()
            return
        self.polling.take(*result)

    def tick(self) -> None:
        """Every REFRESH_MS while recording: the chart follows the data."""
        w = self.window
        if self.single_shot is not None and self.single_shot.running:
            self._ticks += 1
            if self._ticks % LIST_EVERY == 0:  # progress in the title; nothing is drawn (DG 5867)
                shot = self.single_shot
                self.status_job.run(shot.status, lambda status: self._recording_progress(shot, status))
            return
        if self.free_run is not None and not self.free_run.running and not self.polling.running:
            self._finish_run()  # a single triggered capture is complete
            return
        derived.refresh(w.scope)
        span = w.scope.time_span()
        if span and (self.free_run is None or self.free_run.trigger is None):  # follow the newest data
            self._follow(span)
        w.chart.refresh(navigation=False)  # the navigation pane is not drawn while recording (DG 5843)
        self._ticks += 1
        if self._ticks % LIST_EVERY == 0:  # numbers people read: 5 updates a second are plenty
            w.list.update_values(mouse_t=w.mouse_t)
            w.update_title()

    def _recording_progress(self, shot, status) -> None:
        """The Single Shot recording's status, asked on the status thread (of this recording: a new one started
        meanwhile is not stopped by its predecessor's last status)."""
        if self.single_shot is not shot or not shot.running:
            return
        self.recording_status = None if isinstance(status, Exception) else status
        self.window.update_title()
        if self.recording_status is not None and not self.recording_status.running:
            # full ('stop when full'): the run has ended, and "when the run ends, the Oscilloscope will
            # upload" (DG 5434) - it waited for Stop (issue 23 item 11)
            self.stop()

    def _follow(self, span: tuple[float, float]) -> None:
        """Show the live window (Live box, default 10 s) ending at the newest sample, filling from the left until
        the recording is that long. A zoom made during this run is kept; the previous run's zoom is not (it
        left ~1 s windows behind, issue 23 item 8)."""
        chart = self.window.chart
        x0, x1 = chart.view.viewRange()[0]
        width = self.live_window_ms
        if self._live_width is not None and abs((x1 - x0) - self._live_width) > 0.01 * self._live_width:
            width = x1 - x0   # the user zoomed while recording
        o = chart.origin()
        lo = max(span[0], span[1] - width) - o
        if self._live_width is None or width != self._live_width or span[1] - o > x1 or span[1] - o < x0:
            chart.view.setXRange(lo, lo + width, padding=0)
            self._live_width = width

    # --- tune ------------------------------------------------------------------------------------------------
    def tune_chosen(self) -> None:
        """Tune became the variant: its gains are read at once when there is a link (else before the first run)."""
        w = self.window
        if w.link is not None:
            self.tune = Tune(w.scope, w.link, w.tune_panel.config())
            with contextlib.suppress(LinkError):
                w.tune_panel.set_parameters(self.tune.read_parameters())

    def run_tune(self) -> None:
        w = self.window
        if w.link is None:
            return
        if self.tune is None:
            self.tune = Tune(w.scope, w.link)
        self.tune.link = w.link
        self.tune.config = w.tune_panel.config()
        panel, tune = w.tune_panel, self.tune
        try:   # each request on a thread while the window paints (user input waits: Run cannot start twice)
            if not panel.as_read:  # never read (no link when Tune was chosen): read before anything is written
                panel.set_parameters(wait(w, "Reading the gains …", tune.read_parameters))
            panel.generation += 1  # a re-read still on its way predates this write
            changed = panel.changed()   # only the user's edits: the rest may be newer there
            wait(w, "Writing the gains …", lambda: tune.write_parameters(changed))
            if not panel.overlay.isChecked():
                for g in [g for g in w.scope.groups if g.name.startswith("Tune run")]:
                    for c in w.scope.members(g.name):
                        w.scope.remove_curve(c.name)
            wait(w, "Starting the test move …", tune.begin)
        except (ValueError, LinkError) as exc:
            panel.state.setText(str(exc))
            return
        panel.set_parameters(tune.run_parameters)  # begin() read what this run uses: show it
        panel.run.setEnabled(False)
        panel.state.setText("Test move running …")
        self.tune_timer.start()

    def refresh_tune(self) -> None:
        """Re-read the gains when the Tune window comes to the front (Parameters ▸ Axis or a program may have
        changed them meanwhile), on a worker thread so the window never waits for the line."""
        link, panel = self.window.link, self.window.tune_panel
        if link is None or self.window.scope.variant != "tune" or self.tune_timer.isActive():
            return
        generation = panel.generation

        def read() -> None:
            try:
                values = {name: int(link.read_parameter(name)) for name in PID_PARAMETERS}
            except (LinkError, ValueError):
                return  # the next activation or run reads again; a lost link is said by the window
            with contextlib.suppress(RuntimeError):  # the window was closed meanwhile
                panel.read_done.emit((generation, values))

        threading.Thread(target=read, name="tune-read", daemon=True).start()

    def _tune_tick(self) -> None:
        """Every 100 ms while the test move runs: is it over? Asked on a thread; one question at a time."""
        self.tune_job.run(self.tune.finished, self._tune_checked)

    def _tune_checked(self, done) -> None:
        if done is False or not self.tune_timer.isActive():   # still moving, or the run was given up meanwhile
            return
        self.tune_timer.stop()   # before the upload: the timer fires on while it waits
        w, panel = self.window, self.window.tune_panel
        result = None
        try:
            if isinstance(done, Exception):
                raise done
            result = self.tune.finish(run=lambda request: wait(w, "Uploading the test move …", request))
        except LinkError as exc:
            panel.state.setText(f"Test failed: {exc}")
        panel.run.setEnabled(True)
        if result is not None:
            panel.add_result(result)
            settle = "not settled" if result.settling_ms is None else f"settled after {result.settling_ms:.0f} ms"
            panel.state.setText(f"Run {result.run}: overshoot {result.overshoot:.4g} UU, {settle}, "
                                f"peak tracking error {result.peak_tracking_error:.4g}")
            w.list.rebuild()
            w.zoom_reset()
