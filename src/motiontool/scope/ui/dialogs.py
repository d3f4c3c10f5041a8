"""Dialogs and panels of the oscilloscope: Single Shot recording set-up (DG 5287-5324), Add Curve (a compact
form of the SDO/Variable/Derived tabs, DG 5424-5674), the Tune panel (ide-spec 6.60) and curve Properties
(DG 5070-5236)."""

from __future__ import annotations

from PySide6.QtCore import Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import (
    QCheckBox,
    QColorDialog,
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QDoubleSpinBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QRadioButton,
    QSpinBox,
    QTableWidget,
    QTableWidgetItem,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from motiontool.qtjobs.prompts import prompts_for
from motiontool.scope.curves import FORMATS, INTERPOLATIONS, Curve, Group, Scaling
from motiontool.scope.derived import KINDS
from motiontool.scope.select import CHOICES, canonical
from motiontool.scope.trigger import Trigger
from motiontool.scope.tune import PID_PARAMETERS, TestConfiguration, TuneResult
from motiontool.scope.ui.signal_browser import Fetch, SignalBrowser


class RecordingDialog(QDialog):
    """Single Shot: storage location, storage mode, sample count, sample interval (DG 5289-5322)."""

    def __init__(self, group: Group, parent=None):
        super().__init__(parent)
        self.setWindowTitle("Select Test Recording")
        self.group = group
        form = QFormLayout(self)
        self.dynmem = QRadioButton("Dynamic Memory")
        self.array = QRadioButton("Array:")
        self.array_name = QLineEdit("" if group.destination == "DYNMEM" else group.destination)
        (self.dynmem if group.destination == "DYNMEM" else self.array).setChecked(True)
        row = QHBoxLayout()
        for w in (self.dynmem, self.array, self.array_name):
            row.addWidget(w)
        form.addRow("Storage Location:", row)
        self.cyclic = QRadioButton("Cyclic")
        self.stop_full = QRadioButton("Stop when full")
        (self.cyclic if group.cyclic else self.stop_full).setChecked(True)
        row = QHBoxLayout()
        row.addWidget(self.cyclic)
        row.addWidget(self.stop_full)
        form.addRow("Storage Mode:", row)
        self.fill = QRadioButton("Fill available space")
        self.fixed = QRadioButton("Fixed count:")
        self.count = QSpinBox()
        self.count.setRange(1, 10_000_000)
        self.count.setValue(group.count or 1000)
        (self.fixed if group.count else self.fill).setChecked(True)
        row = QHBoxLayout()
        for w in (self.fill, self.fixed, self.count):
            row.addWidget(w)
        form.addRow("Sample Count:", row)
        self.interval = QSpinBox()
        self.interval.setRange(1, 60_000)
        self.interval.setSuffix(" ms")
        self.interval.setValue(group.interval_ms)
        form.addRow("Sample Interval:", self.interval)
        buttons = QDialogButtonBox(QDialogButtonBox.Ok | QDialogButtonBox.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def accept(self) -> None:
        g = self.group
        g.destination = self.array_name.text().strip() if self.array.isChecked() and \
            self.array_name.text().strip() else "DYNMEM"
        g.cyclic = self.cyclic.isChecked()
        g.count = self.count.value() if self.fixed.isChecked() else 0
        g.interval_ms = self.interval.value()
        super().accept()


class AddCurveDialog(QDialog):
    """Add Curve: a link signal (SDO index, SYSVAR, parameter, signal name or program variable) into a
    group or polled; or a derived curve of the existing ones."""

    def __init__(self, groups: list[str], curves: list[str], parent=None, fetch: Fetch | None = None):
        super().__init__(parent)
        self.setWindowTitle("Add Curve")
        self.fetch = fetch      # the controller's list_signals, for Browse… (None: not connected)
        form = QFormLayout(self)
        self.kind = QComboBox()
        self.kind.addItems(["Signal", "Variable", "Derived"])
        form.addRow("Type:", self.kind)
        self.signal = QLineEdit("APOS")
        self.signal.setToolTip("APOS, CPOS, TRACKERR, AVEL …, a parameter (KPROP, 32-60), a SYSVAR index (4097, "
                               "0x01250001) or, for Variable, a program variable (name or array[i]); an APOSS "
                               "suffix records one byte, word or bit of it: 4104.b2, 4104.sw1, 4104.3")
        self.browse = QPushButton("Browse…")
        self.browse.setToolTip("Choose from the signals the controller can record")
        self.browse.clicked.connect(self.browse_signals)
        row = QHBoxLayout()
        row.addWidget(self.signal, 1)
        row.addWidget(self.browse)
        form.addRow("Signal / variable:", row)
        self.method = QComboBox()
        self.method.addItems(groups + ["Polled (no group)"])
        form.addRow("Method / group:", self.method)
        self.derived_kind = QComboBox()
        self.derived_kind.addItems(list(KINDS))
        form.addRow("Derived type:", self.derived_kind)
        self.base = QComboBox()
        self.base.addItems(curves)
        self.second = QComboBox()
        self.second.addItems(curves)
        form.addRow("Base curve:", self.base)
        form.addRow("Second curve:", self.second)
        self.expression = QLineEdit()
        self.expression.setPlaceholderText("e.g. (b - a) * 0.5   (a = base, b = second)")
        form.addRow("Expression:", self.expression)
        self.name = QLineEdit()
        form.addRow("Name:", self.name)
        buttons = QDialogButtonBox(QDialogButtonBox.Ok | QDialogButtonBox.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def browse_signals(self) -> None:
        browser = SignalBrowser(self.fetch, self)
        if browser.exec() and browser.choice:
            self.signal.setText(browser.choice)
            if self.kind.currentText() != "Signal":
                self.kind.setCurrentText("Signal")


class TunePanel(QWidget):
    """The test move, the 32-6* PID parameters with "apply and run", and the results of every run."""

    read_done = Signal(object)   # (generation, {name: value}) from a worker thread's read (run_control)

    def __init__(self, config: TestConfiguration, parent=None):
        super().__init__(parent)
        layout = QVBoxLayout(self)
        form = QFormLayout()
        self.distance = QSpinBox()
        self.distance.setRange(-100_000_000, 100_000_000)
        self.distance.setValue(config.distance)
        self.distance.setSuffix(" UU")
        self.velocity = QSpinBox()
        self.velocity.setRange(1, 100)
        self.velocity.setValue(config.velocity)
        self.acceleration = QSpinBox()
        self.acceleration.setRange(1, 100)
        self.acceleration.setValue(config.acceleration)
        self.settle = QSpinBox()
        self.settle.setRange(0, 20_000)
        self.settle.setValue(config.settle_ms)
        self.settle.setSuffix(" ms")
        self.band = QDoubleSpinBox()
        self.band.setRange(0.001, 1e6)
        self.band.setValue(config.band)
        for label, w in (("Distance", self.distance), ("VEL", self.velocity), ("ACC / DEC", self.acceleration),
                         ("Settle time", self.settle), ("Settling band ±", self.band)):
            form.addRow(label, w)
        self.pid: dict[str, QSpinBox] = {}
        self.as_read: dict[str, int] = {}   # the controller's values when last read, by name
        self.generation = 0                 # counts the writes: a read asked before one is dropped
        self.read_done.connect(self._read_arrived)
        for name in PID_PARAMETERS:
            box = QSpinBox()
            box.setRange(0, 100_000)
            self.pid[name] = box
            form.addRow(name, box)
        layout.addLayout(form)
        self.overlay = QCheckBox("Overlay runs")
        self.overlay.setChecked(True)
        layout.addWidget(self.overlay)
        self.run = QPushButton("Apply and run test")
        layout.addWidget(self.run)
        self.state = QLabel("")
        layout.addWidget(self.state)
        self.results = QTableWidget(0, 5)
        self.results.setHorizontalHeaderLabels(["Run", "KPROP", "Overshoot", "Settling ms", "Peak TE"])
        layout.addWidget(self.results)

    def config(self) -> TestConfiguration:
        return TestConfiguration(self.distance.value(), self.velocity.value(), self.acceleration.value(),
                                 self.settle.value(), self.band.value())

    def set_parameters(self, values: dict[str, int]) -> None:
        """The controller's values as just read. A field the user has edited keeps the edit; the others show the
        new value. What was read is remembered, so "Apply" writes only the edits: the panel once wrote back the
        gains it read when it opened, undoing a KPROP set meanwhile in Parameters ▸ Axis (issue 23)."""
        for name, value in values.items():
            box = self.pid.get(name)
            if box is None:
                continue
            if name not in self.as_read or box.value() == self.as_read[name]:
                box.setValue(int(value))
            self.as_read[name] = int(value)

    def parameters(self) -> dict[str, int]:
        return {name: box.value() for name, box in self.pid.items()}

    def _read_arrived(self, answer) -> None:
        generation, values = answer
        if generation == self.generation:   # else a write came after this read was asked: it is stale
            self.set_parameters(values)

    def changed(self) -> dict[str, int]:
        """The fields the user changed since the values were read (a field never read is not written: it shows
        no controller value, only the box's 0)."""
        return {name: box.value() for name, box in self.pid.items()
                if name in self.as_read and box.value() != self.as_read[name]}

    def add_result(self, r: TuneResult) -> None:
        row = self.results.rowCount()
        self.results.insertRow(row)
        cells = [str(r.run), str(r.parameters.get("KPROP", "")), f"{r.overshoot:.4g}",
                 "—" if r.settling_ms is None else f"{r.settling_ms:.0f}", f"{r.peak_tracking_error:.4g}"]
        for col, text in enumerate(cells):
            self.results.setItem(row, col, QTableWidgetItem(text))


WHOLE_VALUE = "(whole value)"
SELECTABLE = ("free_run", "single_shot", "polled", "variable")   # methods whose samples a selection applies to


class PropertiesDialog(QDialog):
    """Curve properties (DG 5070-5236): Display (colour, format, interpolation, scaling, range validation,
    smoothing, unit), Axis (min height, automatic / user range, centre zero, zero mark, share) and Source."""

    def __init__(self, curve: Curve, others: list[str], parent=None):
        super().__init__(parent)
        self.curve = curve
        self.setWindowTitle(f"Properties — {curve.name}")
        tabs = QTabWidget()
        layout = QVBoxLayout(self)
        layout.addWidget(tabs)
        # Display
        display = QWidget()
        form = QFormLayout(display)
        self.colour = QLineEdit(curve.colour)
        pick = QPushButton("Select…")
        pick.clicked.connect(self._pick_colour)
        row = QHBoxLayout()
        row.addWidget(self.colour)
        row.addWidget(pick)
        form.addRow("Color:", row)
        self.fmt = QComboBox()
        self.fmt.addItems(list(FORMATS))
        self.fmt.setCurrentText(curve.fmt)
        form.addRow("Format:", self.fmt)
        self.interpolation = QComboBox()
        self.interpolation.addItems(list(INTERPOLATIONS))
        self.interpolation.setCurrentText(curve.interpolation)
        form.addRow("Interpolation:", self.interpolation)
        self.scaling = QCheckBox("Enable scaling")
        self.scaling.setChecked(curve.scaling is not None)
        sc = curve.scaling or Scaling()
        self.formula = QComboBox()
        self.formula.addItems(["(y-offset)*scale", "(y*scale)-offset"])
        self.formula.setCurrentIndex(0 if sc.offset_first else 1)
        self.offset = _number(sc.offset)
        self.scale = _number(sc.scale)
        form.addRow(self.scaling, self.formula)
        form.addRow("Offset:", self.offset)
        form.addRow("Scale:", self.scale)
        self.low = QLineEdit("" if curve.range_low is None else repr(curve.range_low))
        self.high = QLineEdit("" if curve.range_high is None else repr(curve.range_high))
        form.addRow("Range validation low:", self.low)
        form.addRow("Range validation high:", self.high)
        self.smoothing = QSpinBox()
        self.smoothing.setRange(0, 10_000)
        self.smoothing.setValue(curve.smoothing)
        self.smoothing.setToolTip("Averages 2w+1 points; large values hide real behaviour (DG 5143-5161)")
        form.addRow("Smoothing width:", self.smoothing)
        self.unit = QComboBox()
        self.unit.setEditable(True)
        self.unit.addItems(["", "UU", "UU/s", "qc", "qc/ms", "ms", "%", "rpm"])
        self.unit.setCurrentText(curve.unit)
        form.addRow("Unit string:", self.unit)
        tabs.addTab(display, "Display")
        # Axis
        axis = QWidget()
        form = QFormLayout(axis)
        a = curve.axis
        self.min_height = _number(a.min_height)
        form.addRow("Min Height:", self.min_height)
        self.automatic = QCheckBox("Automatic scaling")
        self.automatic.setChecked(a.automatic)
        form.addRow(self.automatic)
        self.y_from, self.y_to = _number(a.low), _number(a.high)
        form.addRow("User defined from:", self.y_from)
        form.addRow("to:", self.y_to)
        self.center_zero = QCheckBox("Center zero when reset")
        self.center_zero.setChecked(a.center_zero)
        self.zero_mark = QCheckBox("Display zero mark")
        self.zero_mark.setChecked(a.zero_mark)
        form.addRow(self.center_zero)
        form.addRow(self.zero_mark)
        self.share = QComboBox()
        self.share.addItems(["(own axis)"] + [n for n in others if n != curve.name])
        self.share.setCurrentText(a.share or "(own axis)")
        form.addRow("Share axis of:", self.share)
        tabs.addTab(axis, "Axis")
        # Source (read-only)
        source = QWidget()
        form = QFormLayout(source)
        s = curve.source
        for label, value in (("Type", s.method), ("Signal / index", s.signal), ("Group", s.group),
                             ("Controller", "" if s.controller is None else str(s.controller)),
                             ("Max number of samples", str(curve.buffer.capacity))):
            form.addRow(label + ":", QLabel(value))
        self.old_select = s.select
        self.select = QComboBox()
        self.select.setEditable(True)
        self.select.addItems([WHOLE_VALUE] + CHOICES)
        self.select.setCurrentText(s.select or WHOLE_VALUE)
        self.select.setEnabled(s.method in SELECTABLE)
        self.select.setToolTip("Byte (b1…b4, sb1…sb4 signed), word (w1, w2, sw1, sw2) or bit (1…32) of the 32-bit "
                               "value, like the APOSS suffixes; 1 = least significant. Changing it deletes the "
                               "curve's recorded data, which holds the old selection.")
        form.addRow("Byte/bit selection:", self.select)
        for key, value in s.info.items():
            form.addRow(f"{key}:", QLabel(str(value)))
        tabs.addTab(source, "Source")
        buttons = QDialogButtonBox(QDialogButtonBox.Ok | QDialogButtonBox.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout.addWidget(buttons)

    def _pick_colour(self) -> None:
        colour = QColorDialog.getColor(QColor(self.colour.text()), self)
        if colour.isValid():
            self.colour.setText(colour.name())

    def accept(self) -> None:
        c = self.curve
        try:
            low = float(self.low.text()) if self.low.text().strip() else None
            high = float(self.high.text()) if self.high.text().strip() else None
        except ValueError:
            prompts_for(self).warn("Properties", "Range validation bounds must be numbers or blank")
            return
        try:
            text = self.select.currentText()
            select = None if text == WHOLE_VALUE else canonical(text)
        except ValueError as exc:
            prompts_for(self).warn("Properties", str(exc))
            return
        c.source.select = select
        if QColor(self.colour.text()).isValid():
            c.colour = QColor(self.colour.text()).name()
        c.fmt = self.fmt.currentText()
        c.interpolation = self.interpolation.currentText()
        c.scaling = Scaling(self.offset.value(), self.scale.value(), self.formula.currentIndex() == 0) \
            if self.scaling.isChecked() else None
        c.range_low, c.range_high = low, high
        c.smoothing = self.smoothing.value()
        c.unit = self.unit.currentText()
        a = c.axis
        a.min_height, a.automatic = self.min_height.value(), self.automatic.isChecked()
        a.low, a.high = self.y_from.value(), self.y_to.value()
        a.center_zero, a.zero_mark = self.center_zero.isChecked(), self.zero_mark.isChecked()
        a.share = None if self.share.currentIndex() == 0 else self.share.currentText()
        super().accept()


def _number(value: float) -> QDoubleSpinBox:
    box = QDoubleSpinBox()
    box.setRange(-1e12, 1e12)
    box.setDecimals(6)
    box.setValue(value)
    return box


class TriggerDialog(QDialog):
    """Trigger for Free Run (beyond the manual, halscope-like): curve, level, edge or bit pattern, samples
    before and after the trigger, single capture or re-arming."""

    def __init__(self, curves: list[str], parent=None):
        super().__init__(parent)
        self.setWindowTitle("Trigger")
        form = QFormLayout(self)
        self.enabled = QCheckBox("Trigger enabled")
        form.addRow(self.enabled)
        self.curve = QComboBox()
        self.curve.addItems(curves)
        form.addRow("Curve:", self.curve)
        self.edge = QComboBox()
        self.edge.addItems(["rising", "falling", "either", "pattern"])
        form.addRow("Edge:", self.edge)
        self.level = _number(0.0)
        form.addRow("Level:", self.level)
        self.mask = QLineEdit("0x000000FF")
        self.pattern = QLineEdit("0x00000001")
        form.addRow("Bit mask (pattern):", self.mask)
        form.addRow("Bit pattern:", self.pattern)
        self.pre = QSpinBox()
        self.pre.setRange(0, 1_000_000)
        self.pre.setValue(100)
        self.post = QSpinBox()
        self.post.setRange(1, 1_000_000)
        self.post.setValue(900)
        form.addRow("Samples before:", self.pre)
        form.addRow("Samples from the trigger:", self.post)
        self.single = QCheckBox("Single (stop after one capture)")
        self.single.setChecked(True)
        form.addRow(self.single)
        buttons = QDialogButtonBox(QDialogButtonBox.Ok | QDialogButtonBox.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def trigger(self) -> tuple[str, Trigger] | None:
        """The chosen trigger, or None when disabled; ValueError names a bad field."""
        if not self.enabled.isChecked():
            return None
        try:
            mask, pattern = int(self.mask.text(), 0), int(self.pattern.text(), 0)
        except ValueError:
            raise ValueError("bit mask and pattern: integers such as 0xFF") from None
        return self.curve.currentText(), Trigger(level=self.level.value(), edge=self.edge.currentText(),
                                                 mask=mask, pattern=pattern, pre=self.pre.value(),
                                                 post=self.post.value())
