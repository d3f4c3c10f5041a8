"""Running the oscilloscope (DG 4620-4712, 5859-5869): Start / Pause / Stop, the display refresh and poll timers,
the Free Run trigger and the Tune test move. A mixin of `ScopeWindow` (scope/ui/window.py), which owns the
widgets, timers and acquisition objects these methods drive."""

from __future__ import annotations

import contextlib
import threading

from PySide6.QtWidgets import QMessageBox, QProgressDialog

from motiontool.comms.protocol import LinkError
from motiontool.scope import derived
from motiontool.scope.acquisition import FreeRun, SingleShot
from motiontool.scope.tune import PID_PARAMETERS, Tune
from motiontool.scope.ui.dialogs import TriggerDialog
from motiontool.scope.ui.poll_job import wait

LIST_EVERY = 4          # list values and title every 4th chart refresh while recording


class RunControl:
    """Start/Pause/Stop, timers, trigger and Tune of a ScopeWindow."""

    @property
    def running(self) -> bool:
        return bool((self.free_run and self.free_run.running) or self.polling.running or
                    (self.single_shot and self.single_shot.running))

    # --- run -------------------------------------------------------------------------------------------------
    def start(self) -> None:
        link = self.link
        if link is None:
            QMessageBox.warning(self, "Oscilloscope", "No controller connected (Reconnect first).")
            return
        resume = self.paused
        if resume:
            span = self.scope.time_span()
            if span:
                self.scope.pauses.append(span[1])  # the red bar where recording resumed (DG 5943)
        else:
            self.scope.pauses.clear()
        self.paused = False
        try:
            if self.scope.variant == "single_shot":
                group = next((g for g in self.scope.groups if g.method == "single_shot" and g.active), None)
                if group is None:
                    raise ValueError("no active Single Shot group")
                self.single_shot = SingleShot(self.scope, link, group.name)
                self.single_shot.start(run=lambda request: wait(self, "Starting the Single Shot recording …",
                                                                request))
            else:
                groups = [g for g in self.scope.groups if g.method == "free_run" and g.active
                          and any(c.active for c in self.scope.members(g.name))]
                if groups:
                    self.free_run = FreeRun(self.scope, link, groups[0].name)
                    self.free_run.trigger, self.free_run.single = self.trigger, self.trigger_single
                    self.free_run.start(clear=not resume,
                                        run=lambda request: wait(self, "Starting the recording …", request))
                self.polling.link = link
                if self.polling.curves():
                    self.polling.start(clear=not resume)
                    self.poll_timer.setInterval(self.scope.settings.poll_ms)
                    self.poll_timer.start()
                if not groups and not self.polling.curves():
                    raise ValueError("no active curve to record: add a curve first")
        except (ValueError, LinkError) as exc:
            QMessageBox.warning(self, "Oscilloscope", str(exc)) if self.ask else None
            self.statusBar().showMessage(str(exc), 10000)
            return
        self.chart.live = True
        self._live_width = None   # the next tick sets the live window
        self.refresh_timer.start()
        self._update_title()

    def pause(self) -> None:
        if self.running and self.scope.variant != "single_shot":
            self._stop_acquisition()
            self.paused = True
            self._finish_run()

    def stop(self) -> None:
        """Stop ends only the recording; the program keeps running (DG 4627, 5859). Single Shot uploads now."""
        was_single = self.single_shot is not None and self.single_shot.running
        self._stop_acquisition()
        if was_single:
            progress = QProgressDialog("Uploading the recording …", None, 0, 0, self)
            progress.setWindowTitle("Single Shot")
            progress.show()
            try:
                sets = self.single_shot.stop(run=lambda request: wait(self, "Uploading the recording …", request))
                self.statusBar().showMessage(f"Uploaded {sets} sample sets", 10000)
            except LinkError as exc:
                self.statusBar().showMessage(f"Upload failed: {exc}", 10000)
            progress.close()
        self.paused = False
        self._finish_run()

    def _stop_acquisition(self) -> None:
        self.poll_timer.stop()
        self.polling.stop()
        if self.free_run is not None:
            with contextlib.suppress(LinkError):
                self.free_run.stop(run=lambda request: wait(self, "Stopping the recording …", request))

    def _finish_run(self) -> None:
        self.refresh_timer.stop()
        self.chart.live = False
        self.chart.set_pauses(self.scope.pauses)
        self.zoom_reset()
        self._update_title()


    def trigger_dialog(self, *, dialog: TriggerDialog | None = None) -> None:
        """Set the Free Run trigger; a dialog given here has been filled in and accepted already."""
        if dialog is None:
            dialog = TriggerDialog([c.name for c in self.scope.curves], self)
            dialog.exec()
        if dialog.result() != TriggerDialog.Accepted:
            return
        try:
            self.trigger = dialog.trigger()
        except ValueError as exc:
            QMessageBox.warning(self, "Trigger", str(exc))
            return
        self.trigger_single = dialog.single.isChecked()
        self.statusBar().showMessage("Trigger off" if self.trigger is None else
                                     f"Trigger: {self.trigger[0]} {self.trigger[1].edge} {self.trigger[1].level:g}",
                                     5000)

    def _set_poll_ms(self, ms: int) -> None:
        self.scope.settings.poll_ms = ms
        if self.poll_timer.isActive():
            self.poll_timer.setInterval(ms)
        self._update_title()

    def delete_data(self) -> None:
        """Delete data: samples not saved yet are asked for first, Save / Discard / Cancel as on closing (issue 23
        item 11: they went without a word); saved ones can be loaded again."""
        if not self.confirm_unsaved():
            return
        self.scope.clear_data()
        self.redraw()

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
            self.statusBar().showMessage(f"Polling stopped: {result}", 10000)
            self.stop()
            return
        self.polling.take(*result)

    def _tick(self) -> None:
        if self.single_shot is not None and self.single_shot.running:
            self._ticks += 1
            if self._ticks % LIST_EVERY == 0:  # progress in the title; nothing is drawn (DG 5867)
                shot = self.single_shot
                self.status_job.run(shot.status, lambda status: self._recording_progress(shot, status))
            return
        if self.free_run is not None and not self.free_run.running and not self.polling.running:
            self._finish_run()  # a single triggered capture is complete
            return
        derived.refresh(self.scope)
        span = self.scope.time_span()
        if span and (self.free_run is None or self.free_run.trigger is None):  # follow the newest data
            self._follow(span)
        self.chart.refresh(navigation=False)  # the navigation pane is not drawn while recording (DG 5843)
        self._ticks += 1
        if self._ticks % LIST_EVERY == 0:  # numbers people read: 5 updates a second are plenty
            self.list.update_values(mouse_t=self.mouse_t)
            self._update_title()


    def _recording_progress(self, shot, status) -> None:
        """The Single Shot recording's status, asked on the status thread (of this recording: a new one started
        meanwhile is not stopped by its predecessor's last status)."""
        if self.single_shot is not shot or not shot.running:
            return
        self._recording_status = None if isinstance(status, Exception) else status
        self._update_title()
        if self._recording_status is not None and not self._recording_status.running:
            # full ('stop when full'): the run has ended, and "when the run ends, the Oscilloscope will
            # upload" (DG 5434) - it waited for Stop (issue 23 item 11)
            self.stop()

    def _follow(self, span: tuple[float, float]) -> None:
        """Show the live window (Live box, default 10 s) ending at the newest sample, filling from the left until
        the recording is that long. A zoom made during this run is kept; the previous run's zoom is not (it
        left ~1 s windows behind, issue 23 item 8)."""
        x0, x1 = self.chart.view.viewRange()[0]
        width = self.live_window_ms
        if self._live_width is not None and abs((x1 - x0) - self._live_width) > 0.01 * self._live_width:
            width = x1 - x0   # the user zoomed while recording
        o = self.chart.origin()
        lo = max(span[0], span[1] - width) - o
        if self._live_width is None or width != self._live_width or span[1] - o > x1 or span[1] - o < x0:
            self.chart.view.setXRange(lo, lo + width, padding=0)
            self._live_width = width

    # --- tune ------------------------------------------------------------------------------------------------
    def run_tune(self) -> None:
        if self.link is None:
            return
        if self.tune is None:
            self.tune = Tune(self.scope, self.link)
        self.tune.link = self.link
        self.tune.config = self.tune_panel.config()
        panel, tune = self.tune_panel, self.tune
        try:   # each request on a thread while the window paints (user input waits: Run cannot start twice)
            if not panel.as_read:  # never read (no link when Tune was chosen): read before anything is written
                panel.set_parameters(wait(self, "Reading the gains …", tune.read_parameters))
            panel.generation += 1  # a re-read still on its way predates this write
            changed = panel.changed()   # only the user's edits: the rest may be newer there
            wait(self, "Writing the gains …", lambda: tune.write_parameters(changed))
            if not self.tune_panel.overlay.isChecked():
                for g in [g for g in self.scope.groups if g.name.startswith("Tune run")]:
                    for c in self.scope.members(g.name):
                        self.scope.remove_curve(c.name)
            wait(self, "Starting the test move …", tune.begin)
        except (ValueError, LinkError) as exc:
            self.tune_panel.state.setText(str(exc))
            return
        panel.set_parameters(self.tune.run_parameters)  # begin() read what this run uses: show it
        self.tune_panel.run.setEnabled(False)
        self.tune_panel.state.setText("Test move running …")
        self.tune_timer.start()

    def refresh_tune(self) -> None:
        """Re-read the gains when the Tune window comes to the front (Parameters ▸ Axis or a program may have
        changed them meanwhile), on a worker thread so the window never waits for the line."""
        link, panel = self.link, self.tune_panel
        if link is None or self.scope.variant != "tune" or self.tune_timer.isActive():
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
        result = None
        try:
            if isinstance(done, Exception):
                raise done
            result = self.tune.finish(run=lambda request: wait(self, "Uploading the test move …", request))
        except LinkError as exc:
            self.tune_panel.state.setText(f"Test failed: {exc}")
        self.tune_panel.run.setEnabled(True)
        if result is not None:
            self.tune_panel.add_result(result)
            settle = "not settled" if result.settling_ms is None else f"settled after {result.settling_ms:.0f} ms"
            self.tune_panel.state.setText(f"Run {result.run}: overshoot {result.overshoot:.4g} UU, {settle}, "
                                          f"peak tracking error {result.peak_tracking_error:.4g}")
            self.list.rebuild()
            self.zoom_reset()
