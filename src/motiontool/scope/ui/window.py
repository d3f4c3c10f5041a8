"""The oscilloscope window (DG 4600-6011, ide-spec group 6): toolbar, chart + navigation, curve list.

It talks to the controller only through a comms Link: given a LinkBridge (the IDE's) it uses the bridge's
link and its queued `samples` signal; given a plain Link it relays the link's events into the GUI thread
itself. Opened from a file it has no link at all until Reconnect (DG 5277-5285). Start/Pause/Stop, the refresh
and poll timers, the trigger and the Tune move are its part `run` (`run_control.RunControl`).
"""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QEvent, QObject, Qt, Signal
from PySide6.QtGui import QAction, QActionGroup, QKeySequence
from PySide6.QtWidgets import (
    QDockWidget,
    QLabel,
    QMainWindow,
    QSpinBox,
    QSplitter,
)

from motiontool.fileio import reason
from motiontool.qtjobs.prompts import window_prompts
from motiontool.scope import derived, zbo
from motiontool.scope.acquisition import default_group, new_curve
from motiontool.scope.curves import Scope
from motiontool.scope.export import export_csv
from motiontool.scope.mdf4 import Mdf4Unavailable, export_mdf4
from motiontool.scope.measure import cursor_frequency
from motiontool.scope.numbers import time_text, time_unit
from motiontool.scope.select import with_suffix, without_suffix
from motiontool.scope.testrun import read_testrun
from motiontool.scope.tune import Tune
from motiontool.scope.ui.chart import Chart
from motiontool.scope.ui.curve_list import CurveList
from motiontool.scope.ui.dialogs import AddCurveDialog, PropertiesDialog, RecordingDialog, TunePanel
from motiontool.scope.ui.fft import FftView
from motiontool.scope.ui.list_menu import show_list_menu
from motiontool.scope.ui.poll_job import PollJob
from motiontool.scope.ui.run_control import LIVE_WINDOW_S, RunControl
from motiontool.scope.ui.testsetp_load import load_recordings

TITLES = {"free_run": "Free Run", "polling": "Free Run (polling)", "single_shot": "Single Shot",
          "testsetp": "TESTSETP", "tune": "Tune"}


class _Relay(QObject):
    event = Signal(object)


class ScopeWindow(QMainWindow):
    def __init__(self, link_or_bridge=None, variant: str = "free_run", scope: Scope | None = None,
                 parent=None, ask: bool = True, path: Path | None = None, prompts=None):
        super().__init__(parent)
        self.setAttribute(Qt.WA_DeleteOnClose, False)
        self.ask = ask            # False: no modal dialogs (tests, scripted use)
        self.path = path
        if scope is None:   # a new recording reads from 0: the controller's clock counts from power-up (S32)
            scope = Scope(variant)
            scope.settings.relative_origin = True
        self.scope = scope
        self.bridge = None
        self._prompts = prompts   # None: the bridge's (its APOSS window's), else the Qt dialogs (issue 27 item 5)
        self._link = None
        self._relay = _Relay(self)
        self._relay.event.connect(self._on_event)
        self.mouse_t: float | None = None
        self.run = RunControl(self)
        self._saved_mark: tuple = ()  # the samples as last saved or loaded (unsaved_recording)

        self.chart = Chart(self.scope)
        self.list = CurveList(self.scope)
        self.list.origin = self.chart.origin
        split = QSplitter(Qt.Vertical)
        split.addWidget(self.chart)
        split.addWidget(self.list)
        split.setSizes([520, 200])
        self.setCentralWidget(split)
        self.readout = QLabel("")
        self.statusBar().addPermanentWidget(self.readout)
        self.tune_panel = TunePanel(Tune(self.scope, None).config)
        self.tune_dock = QDockWidget("Tune", self)
        self.tune_dock.setWidget(self.tune_panel)
        self.addDockWidget(Qt.RightDockWidgetArea, self.tune_dock)
        self.tune_panel.run.clicked.connect(self.run.run_tune)
        self._build_actions()
        self.chart.cursor_moved.connect(lambda *_: self._update_readout())
        self.chart.mouse_time.connect(self._mouse_time)
        self.list.visibility_changed.connect(self.redraw)
        self.list.axis_clicked.connect(self.toggle_axis_side)
        self.list.setContextMenuPolicy(Qt.CustomContextMenu)
        self.list.customContextMenuRequested.connect(lambda pos: show_list_menu(self, pos))

        self.state_job = PollJob(self, "scope-state")     # the controller's state for the curve list
        self._state_again = False                         # asked while a question was under way: ask after it
        self.resize(1200, 800)
        if link_or_bridge is not None:
            self.set_link(link_or_bridge)
        self.set_variant(self.scope.variant, initial=True)

    def changeEvent(self, event) -> None:  # noqa: N802 - Qt override
        super().changeEvent(event)
        if event.type() == QEvent.Type.ActivationChange and self.isActiveWindow():
            self.run.refresh_tune()  # back from another window: the gains there may have changed

    @property
    def prompts(self):
        """What this window asks through, shown over it (its APOSS window's prompts when it has one)."""
        return window_prompts(self, self._prompts, self.bridge)

    # --- the link ------------------------------------------------------------------------------------------
    @property
    def link(self):
        return self.bridge.link if self.bridge is not None else self._link

    def set_link(self, link_or_bridge) -> None:
        """Bind to a LinkBridge (anything with a `samples` signal and a `link`) or a plain Link."""
        if hasattr(link_or_bridge, "samples") and hasattr(link_or_bridge, "link"):
            self.bridge = link_or_bridge
            self.bridge.samples.connect(self._on_samples)
            self.bridge.status_changed.connect(self._on_status)
            self.bridge.connection_changed.connect(self._on_connection)
            self.list.interface = getattr(self.bridge, "description", "")
        else:
            self._link = link_or_bridge
            self._link.subscribe(self._relay.event.emit)  # kernel thread → queued into the GUI thread
            self.list.interface = getattr(link_or_bridge, "kind", "")
        self.run.polling.link = self.link
        self._on_status(None)

    def _on_event(self, event) -> None:
        if event.kind == "samples":
            self._on_samples(event.data)
        elif event.kind == "program":
            self._on_status(None)

    def _on_samples(self, data) -> None:
        # the bridge outlives this window: a slot of the window, so Qt drops the connection when the window goes
        self.run.feed(data)

    def _on_status(self, status) -> None:
        """The controller's state in the curve list; `status` None: the IDE's last polled one, else asked on a
        thread (the answer, or the LinkError, comes back here)."""
        link = self.link
        if link is not None and status is None:
            status = getattr(self.bridge, "last_status", None)
            if status is None:
                if not self.state_job.run(link.status, self._state_answered):   # one question at a time
                    self._state_again = True    # its answer may predate what made us ask: ask once more
                return
        if link is None:
            state = "unbound"
        elif isinstance(status, Exception):
            state = "lost"
        else:
            state = {"running": "running", "error": "error"}.get(status.program_state, "connected")
            if status.error:
                state = "error"
        self.list.controller_state = state
        self.list.update_values(mouse_t=self.mouse_t)

    def _state_answered(self, status) -> None:
        self._on_status(status)
        if self._state_again:
            self._state_again = False
            self._on_status(None)

    def _on_connection(self, state: str) -> None:
        self.list.controller_state = "lost" if state == "lost" else self.list.controller_state
        self.list.update_values(mouse_t=self.mouse_t)

    # --- actions -------------------------------------------------------------------------------------------
    def _build_actions(self) -> None:
        tb = self.addToolBar("Oscilloscope")
        tb.setObjectName("scope-toolbar")
        self.mode_group = QActionGroup(self)
        self.mode_actions: dict[str, QAction] = {}
        for variant, title in TITLES.items():
            a = QAction(title, self, checkable=True)
            a.triggered.connect(lambda *_, v=variant: self.set_variant(v))
            self.mode_group.addAction(a)
            tb.addAction(a)
            self.mode_actions[variant] = a
        tb.addSeparator()

        def act(text, slot, *, shortcut=None, checkable=False):
            a = QAction(text, self, checkable=checkable)
            a.triggered.connect(slot)
            if shortcut:
                a.setShortcut(QKeySequence(shortcut))
            tb.addAction(a)
            return a

        self.start_action = act("Start", self.run.start, shortcut="F9")
        self.pause_action = act("Pause", self.run.pause)
        self.stop_action = act("Stop", self.run.stop, shortcut="Shift+F9")
        self.delete_action = act("Delete data", self.run.delete_data)
        self.add_action = act("Add curve", self.add_curve_dialog)
        self.load_action = act("Load TESTSETP", self.load_recordings)
        self.trigger_action = act("Trigger…", self.run.trigger_dialog)
        self.poll_box = QSpinBox()
        self.poll_box.setRange(1, 60_000)
        self.poll_box.setSuffix(" ms")
        self.poll_box.setPrefix("Poll ")
        self.poll_box.setValue(self.scope.settings.poll_ms)
        self.poll_box.setToolTip("Poll rate of polled curves (Settings → Oscilloscope, DG 5975-6001)")
        self.poll_box.valueChanged.connect(self.run.set_poll_ms)
        self.poll_box_action = tb.addWidget(self.poll_box)
        self.live_box = QSpinBox()
        self.live_box.setRange(1, 3600)
        self.live_box.setPrefix("Live ")
        self.live_box.setSuffix(" s")
        self.live_box.setValue(LIVE_WINDOW_S)
        self.live_box.setToolTip("Time shown while recording (newest at the right); a zoom while recording wins")
        self.live_box.valueChanged.connect(self.run.set_live_window)
        self.live_box_action = tb.addWidget(self.live_box)
        tb.addSeparator()
        self.zoom_action = act("Zoom Reset", self.zoom_reset, shortcut="Ctrl+0")
        self.cursor_a = act("Cursor A", lambda on: self.chart.show_cursor(0, on), checkable=True)
        self.cursor_b = act("Cursor B", lambda on: self.chart.show_cursor(1, on), checkable=True)
        self.cursor_a.toggled.connect(self._update_readout)
        self.cursor_b.toggled.connect(self._update_readout)
        self.fft_action = act("FFT", self.show_fft)
        self.shift_action = act("Shift to 0", self.toggle_shift, checkable=True)
        self.shift_action.setChecked(self.chart.shift_to_zero)
        self.export_action = act("Export", self.export_dialog)
        self.save_action = act("Save", self.save_dialog, shortcut="Ctrl+S")
        self.open_action = act("Open", self.open_dialog, shortcut="Ctrl+O")
        self.reconnect_action = QAction("Reconnect", self)
        file_menu = self.menuBar().addMenu("&File")
        for a in (self.open_action, self.save_action):
            file_menu.addAction(a)
        save_template = file_menu.addAction("Save without Data")
        save_template.triggered.connect(lambda: self.save_dialog(with_data=False))
        file_menu.addAction(self.export_action)
        view = self.menuBar().addMenu("&View")
        for a in (self.cursor_a, self.cursor_b, self.zoom_action, self.shift_action):
            view.addAction(a)

    def set_variant(self, variant: str, *, initial: bool = False) -> None:
        """Switch the variant: Free Run adds "Test Group (Free Run)", Single Shot asks for the recording and adds
        "Test Group (Single Shot)", TESTSETP uploads what it finds (DG 5287-5347)."""
        if self.run.running:
            self.run.stop()
        self.scope.variant = variant
        self.mode_actions[variant].setChecked(True)
        names = {g.name for g in self.scope.groups}
        if variant == "free_run" and "Test Group (Free Run)" not in names:
            default_group(self.scope, "free_run")
        elif variant == "single_shot" and "Test Group (Single Shot)" not in names:
            group = default_group(self.scope, "single_shot")
            if self.ask:
                RecordingDialog(group, self).exec()
        self.start_action.setEnabled(variant not in ("testsetp", "tune"))  # DG 5347: Start is disabled
        self.pause_action.setEnabled(variant in ("free_run", "polling"))
        self.load_action.setVisible(variant == "testsetp")
        self.poll_box_action.setVisible(variant in ("free_run", "polling"))
        self.live_box_action.setVisible(variant in ("free_run", "polling"))
        self.trigger_action.setVisible(variant == "free_run")
        self.tune_dock.setVisible(variant == "tune")
        if variant == "tune":
            self.run.tune_chosen()
        self.list.rebuild()
        if variant == "testsetp" and self.link is not None and not initial or (
                variant == "testsetp" and initial and self.link is not None and not self.scope.curves):
            self.load_recordings()
        self.update_title()
        self.redraw()

    # --- curves ----------------------------------------------------------------------------------------------
    def add_signal_curve(self, signal: str, *, group: str | None = None, name: str | None = None):
        """A curve of a link signal in a group ("Test Group (…)") or polled when group is None."""
        method = "polled" if group is None else self.scope.group(group).method
        curve = new_curve(self.scope, signal, group or "", method, name=name)
        self.list.rebuild()
        self.redraw()
        return curve

    def add_derived_curve(self, spec, name: str):
        curve = derived.add_derived(self.scope, spec, name)
        self.list.rebuild()
        self.redraw()
        return curve

    def add_curve_dialog(self, *, dlg: AddCurveDialog | None = None) -> None:
        """Add Curve; a dialog given here is already filled in (scripted use) and counts as accepted."""
        if dlg is None:
            link = self.link
            dlg = AddCurveDialog([g.name for g in self.scope.groups], [c.name for c in self.scope.curves], self,
                                 fetch=link.list_signals if link is not None else None)
            # the group the variant records with, not the first one (Single Shot offered Free Run's, issue 23)
            own = {"free_run": "Test Group (Free Run)", "single_shot": "Test Group (Single Shot)",
                   "polling": "Polled (no group)"}.get(self.scope.variant)
            if own is not None and dlg.method.findText(own) >= 0:
                dlg.method.setCurrentText(own)
            if not dlg.exec():
                return
        try:
            if dlg.kind.currentText() == "Derived":
                spec = derived.DerivedSpec(dlg.derived_kind.currentText(), dlg.base.currentText(),
                                           dlg.second.currentText(), expression=dlg.expression.text(),
                                           variables={"a": dlg.base.currentText(), "b": dlg.second.currentText()})
                self.add_derived_curve(spec, dlg.name.text() or f"{spec.kind} {spec.base}")
            elif dlg.kind.currentText() == "Variable":  # polled through the debug read (DG 5552-5622)
                name = dlg.signal.text().strip()
                new_curve(self.scope, name, "", "variable", name=dlg.name.text() or f"1: {name}")
                self.list.rebuild()
                self.redraw()
            else:
                group = dlg.method.currentText()
                self.add_signal_curve(dlg.signal.text(), group=None if group.startswith("Polled") else group,
                                      name=dlg.name.text() or None)
        except (ValueError, KeyError) as exc:
            self.prompts.warn("Add Curve", str(exc))

    def load_recordings(self) -> None:
        """TESTSETP: one recording is loaded at once; with several the user picks (DG 5326-5333)."""
        load_recordings(self)

    def show_fft(self) -> FftView:
        self._fft = FftView(self)
        self._fft.show()
        return self._fft

    def redraw(self) -> None:
        derived.refresh(self.scope)
        self.chart.refresh(navigation=not self.run.running)
        self.list.sides = (self.chart.left_curve, self.chart.right_curve)
        self.list.update_values(mouse_t=self.mouse_t)
        self._update_readout()

    def zoom_reset(self) -> None:
        derived.refresh(self.scope)
        self.chart.reset_ranges()
        self.redraw()

    def toggle_shift(self, on: bool) -> None:
        self.chart.set_shift(on)
        self.chart.set_pauses(self.scope.pauses)
        for i in (0, 1):
            if self.scope.cursors[i] is not None and self.chart.cursors[i].isVisible():
                self.chart.set_cursor(i, self.scope.cursors[i])
        self.zoom_reset()

    # --- read-outs -------------------------------------------------------------------------------------------
    def _mouse_time(self, t: float) -> None:
        self.mouse_t = t
        if not self.run.running:
            self.list.update_values(mouse_t=t)

    def _update_readout(self, *_) -> None:
        ta, tb = self.scope.cursors
        o = self.chart.origin()   # the times as the axis reads them, all in one unit
        shown = [(n, t - o) for n, t in (("A", ta), ("B", tb)) if t is not None]
        unit = time_unit(max((abs(t) for _n, t in shown), default=0.0))
        parts = [f"{n} {time_text(t, unit)}" for n, t in shown]
        if ta is not None and tb is not None:
            f = cursor_frequency(ta, tb)
            parts.append(f"Δt {time_text(tb - ta, unit)}" + (f"   1/Δt {f:.4g} Hz" if f else ""))
        self.readout.setText("   ".join(parts))
        self.list.update_values(mouse_t=self.mouse_t)

    def toggle_axis_side(self, name: str) -> None:
        """Grid column (DG 4878-4912): a click gives the curve the left axis scale, a second click the right;
        one curve owns each side, the others are scaled generically."""
        if self.chart.left_curve == name:
            self.chart.right_curve, self.chart.left_curve = name, None
            self.chart.left_curve = next((c.name for c in self.scope.curves if c.visible and c.name != name), None)
        else:
            if self.chart.right_curve == name:
                self.chart.right_curve = None
            self.chart.left_curve = name
        self.redraw()

    def update_title(self) -> None:
        title = f"Oscilloscope — {TITLES[self.scope.variant]}"
        if self.path is not None:
            title += f" — {Path(self.path).name}"
        self.setWindowTitle(title + self.run.title())

    def edit_properties(self, name: str, *, dialog: PropertiesDialog | None = None) -> bool:
        """Properties (DG 5070-5236); scaling and ranges take effect at the next Zoom Reset (DG 5197)."""
        if dialog is None:  # else: a dialog already filled in and accepted (scripted use, tests)
            dialog = PropertiesDialog(self.scope.curve(name), [c.name for c in self.scope.curves], self)
            dialog.exec()
        if dialog.result() != PropertiesDialog.Accepted:
            return False
        if dialog.old_select != dialog.curve.source.select:
            self._selection_changed(dialog.curve, dialog.old_select)
        self.list.rebuild()
        self.zoom_reset()
        return True

    def _selection_changed(self, curve, old: str | None) -> None:
        """A new byte/word/bit selection: the recorded values hold the old one, so they go; a name that carries
        the old suffix gets the new one (select.with_suffix), and references follow the rename."""
        curve.buffer.clear()
        base = without_suffix(curve.name, old)
        if old is None or base != curve.name:
            before = curve.name
            after = self.scope.rename_curve(before, with_suffix(base, curve.source.select))
            for side in ("left_curve", "right_curve"):
                if getattr(self.chart, side) == before:
                    setattr(self.chart, side, after)
            self.run.curve_renamed(before, after)

    # --- files ---------------------------------------------------------------------------------------------
    def save_to(self, path: Path | str, *, with_data: bool = True) -> None:
        zbo.save(self.scope, path, with_data)
        self.path = Path(path)
        if with_data:
            self._saved_mark = self._data_mark()
        self.update_title()

    def save_dialog(self, *, with_data: bool = True) -> bool:
        chosen = self.prompts.save_name("Save oscilloscope", self.path or "", "Oscilloscope files (*.zbo)")
        if chosen is None:
            return False
        path = str(chosen)
        path = path if path.lower().endswith(".zbo") else path + ".zbo"  # File ▸ Open knows it by .zbo only
        try:
            self.save_to(path, with_data=with_data)
        except OSError as exc:  # the window and its curves stay as they are (decisions R7)
            self.prompts.warn("Save", f"Cannot write {path}:\n{reason(exc)}.", critical=True,
                              detail="The curves are still in this window: save them somewhere else.")
            return False
        return True

    def _data_mark(self) -> tuple:
        # every write bumps a buffer's version, so an equal mark means the same samples as when saved
        return tuple((id(c.buffer), c.buffer.version) for c in self.scope.curves if len(c.buffer))

    def unsaved_recording(self) -> bool:
        """Samples recorded (or loaded and changed) since the last Save: closing would lose them."""
        mark = self._data_mark()
        return bool(mark) and mark != self._saved_mark

    def confirm_unsaved(self) -> bool:
        """Save / Discard / Cancel for an unsaved recording, as for an unsaved program (issue 23 item 9); True
        when the window may close. No question in scripted use (ask=False, or a main window that asks nothing)."""
        if not self.ask or not getattr(self.parent(), "ask_to_save", True) or not self.unsaved_recording():
            return True
        answer = self.prompts.save_changes("Oscilloscope", f"Save the recording of {self.windowTitle()}?")
        if answer == "save":
            return self.save_dialog()  # cancelled or failed: the window stays, with its curves
        if answer == "discard":
            self._saved_mark = self._data_mark()
            return True
        return False

    def export_to(self, path: Path | str) -> None:
        """Export the curves: MDF4 for a .mf4 path (needs asammdf: Mdf4Unavailable without it), else CSV."""
        if Path(path).suffix.lower() == ".mf4":
            export_mdf4(self.scope, path)
        else:
            export_csv(self.scope, path)

    def export_dialog(self) -> None:
        path = self.prompts.save_name("Export curves", "", "CSV (*.csv *.txt);;MDF4 via asammdf (*.mf4)")
        if path is None:
            return
        try:
            self.export_to(path)
        except OSError as exc:
            self.prompts.warn("Export", f"Cannot write {path}:\n{reason(exc)}.", critical=True)
        except (Mdf4Unavailable, ValueError) as exc:
            self.prompts.warn("Export", str(exc))

    def open_dialog(self) -> None:
        path = self.prompts.open_path("Open oscilloscope", "", "Oscilloscope files (*.zbo);;Old Testrun Files (*.txt)")
        if path is not None:
            try:
                window = open_scope_file(path, prompts=self.prompts)
            except (ValueError, OSError) as exc:
                self.prompts.warn("Open", str(exc))
                return
            window.show()
            self._opened = window

    def closeEvent(self, event) -> None:  # noqa: N802 - Qt override
        if not self.confirm_unsaved():
            event.ignore()
            return
        self.run.stop_acquisition()
        if self._link is not None:
            self._link.unsubscribe(self._relay.event.emit)
        super().closeEvent(event)


def open_scope_file(path: Path | str, parent=None, *, prompts=None) -> ScopeWindow:
    """File → Open of a .zbo or an old Testrun .txt: a scope window that is not connected (DG 5277-5285,
    5357-5376); it asks through `prompts` (the window's that opened it) or the Qt dialogs. NotTestrun (a
    ValueError) means: open the .txt as text instead."""
    path = Path(path)
    scope = read_testrun(path) if path.suffix.lower() == ".txt" else zbo.load(path)
    window = ScopeWindow(None, scope.variant, scope=scope, parent=parent, ask=False, path=path, prompts=prompts)
    window._saved_mark = window._data_mark()
    window.zoom_reset()
    return window
