"""Index cards Curve Data, Curve Info, Synchronization, Sync. Marker and Encoder Data, and the display-option
panel [DG L3686-3958, ide-spec 4.38-4.73].  Cards only show values and emit edit requests; the editor applies
them through the model and refreshes the cards."""

from __future__ import annotations

import math

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QButtonGroup,
    QCheckBox,
    QFormLayout,
    QGridLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QRadioButton,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from motiontool.camcurve.model import MAX_NAME_LENGTH, Curve, CurveType
from motiontool.camcurve.spline import CurveInfo
from motiontool.cameditor.limits import SlaveLimits, marker_detection, parameter, percent, slave_limits
from motiontool.cameditor.ui.diagram import Overlay
from motiontool.paramdb import database

CURVE_TYPE_LABELS = ("Average start and end gradients", "Set end gradient to start gradient",
                     "Set both start and end gradients to 0", "Specify start and end gradients",
                     "Specify gradients (immediate)")
OVER_LIMIT = "color: #c00000; font-weight: bold"


def fmt(value: float, digits: int = 6) -> str:
    if not math.isfinite(value):
        return "-"
    return f"{value:g}" if float(value).is_integer() else f"{value:.{digits}g}"


class NumberField(QLineEdit):
    """A value entered with Enter or on leaving the field is reported once; the shown text is the model's."""

    entered = Signal(str)

    def __init__(self, width: int = 90) -> None:
        super().__init__()
        self.setMaximumWidth(width)
        self.setAlignment(Qt.AlignmentFlag.AlignRight)
        self._shown = ""
        self.editingFinished.connect(self._finished)

    def show_value(self, text: str) -> None:
        self._shown = text
        self.setText(text)

    def _finished(self) -> None:
        if self.text() != self._shown:
            self.entered.emit(self.text())


class CurveDataCard(QWidget):
    """Curve Data [DG L3692-3793]."""

    field_edited = Signal(str, str)  # Curve field, text
    set_length_clicked = Signal()
    set_gradients_clicked = Signal()

    FIELDS = (("slave_stop_position", "Slave Stop Position:"), ("correction_start", "Correction Start:"),
              ("correction_end", "Correction End:"), ("master_marker_pos", "Master Marker Pos.:"),
              ("slave_marker_pos", "Slave Marker Pos.:"))

    def __init__(self) -> None:
        super().__init__()
        grid = QGridLayout(self)
        self.name = NumberField(160)
        self.name.setMaxLength(MAX_NAME_LENGTH)
        self.name.setAlignment(Qt.AlignmentFlag.AlignLeft)
        self.name.entered.connect(lambda text: self.field_edited.emit("name", text))
        grid.addWidget(QLabel("Name of Curve:"), 0, 0)
        grid.addWidget(self.name, 0, 1, 1, 3)
        types = QGroupBox("Type of Curve")
        tl = QVBoxLayout(types)
        tl.setSpacing(1)
        self.type_group = QButtonGroup(self)
        for value, label in enumerate(CURVE_TYPE_LABELS):
            radio = QRadioButton(label)
            self.type_group.addButton(radio, value)
            tl.addWidget(radio)
        self.type_group.idClicked.connect(lambda i: self.field_edited.emit("curve_type", str(i)))
        row = QHBoxLayout()
        self.gradients = QLabel()
        self.set_gradients = QPushButton("Set...")
        self.set_gradients.clicked.connect(self.set_gradients_clicked)
        row.addWidget(self.gradients, 1)
        row.addWidget(self.set_gradients)
        tl.addLayout(row)
        grid.addWidget(types, 1, 0, 1, 4)
        left = QFormLayout()
        self.master_length = QLabel()
        self.slave_length = QLabel()
        self.interpolation = QCheckBox("Interpolation enabled")
        self.interpolation.setEnabled(False)  # only in the Add and Set dialogs [DG L3785]
        self.intervals = QLabel()
        self.set_length = QPushButton("Set...")
        self.set_length.clicked.connect(self.set_length_clicked)
        left.addRow("Master Length:", self.master_length)
        left.addRow("Slave Length:", self.slave_length)
        left.addRow(self.interpolation)
        left.addRow("Number of Intervals:", self.intervals)
        left.addRow(self.set_length)
        right = QFormLayout()
        self.fields: dict[str, NumberField] = {}
        for name, label in self.FIELDS:
            field = NumberField()
            field.entered.connect(lambda text, *, n=name: self.field_edited.emit(n, text))
            self.fields[name] = field
            right.addRow(label, field)
        grid.addLayout(left, 2, 0, 1, 2)
        grid.addLayout(right, 2, 2, 1, 2)
        grid.setRowStretch(3, 1)

    def show_curve(self, curve: Curve) -> None:
        self.name.show_value(curve.name)
        self.type_group.button(int(curve.curve_type)).setChecked(True)
        specified = curve.curve_type in (CurveType.SPECIFIED_GRADIENTS, CurveType.SPECIFIED_IMMEDIATE)
        self.set_gradients.setEnabled(specified)
        self.gradients.setText(f"Start {fmt(curve.start_gradient)}, end {fmt(curve.end_gradient)} UU/MU"
                               if specified else "")
        self.master_length.setText(fmt(curve.master_length))
        self.slave_length.setText(fmt(curve.slave_length))
        self.interpolation.setChecked(curve.interpolation)
        self.intervals.setText(str(curve.intervals))
        for name, field in self.fields.items():
            field.show_value(fmt(getattr(curve, name)))


#: text as wide as a Curve Info value usually is (the labels keep this room, see CurveInfoCard; a longer value
#: shows in full as the label's tool tip)
_ROOM = {"max_velocity": "9.9999e-07 UU/MU²   (999.9 %)",
         "physical": "master 99999 MU/s, slave max 99999 UU/s, 99999 UU/s²"}


class CurveInfoCard(QWidget):
    """Curve Info [DG L3797-3839]: cycles/min, maxima against the slave limits, interval size and time."""

    cycles_edited = Signal(str)

    def __init__(self) -> None:
        super().__init__()
        form = QFormLayout(self)
        self.cycles = NumberField()
        self.cycles.entered.connect(self.cycles_edited)
        form.addRow("Cycles/min Master:", self.cycles)
        self.labels: dict[str, QLabel] = {}
        for key, text in (("max_velocity", "Max actual Velocity:"), ("velocity_limit", "Slave Velocity Limit:"),
                          ("max_acceleration", "Max actual Accel.:"), ("acceleration_limit", "Slave Accel. Limit:"),
                          ("max_jerk", "Max actual Jerk:"), ("physical", "At Cycles/min:"),
                          ("interval_size", "Interval Size:"), ("interval_time", "Interval Time (ms):")):
            label = QLabel()
            label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
            # values change on every mouse move of a drag: a fixed room, wide enough for typical values, keeps
            # a new value from laying out the window again (and resizing the diagram)
            label.setFixedSize(label.fontMetrics().horizontalAdvance(_ROOM.get(key, _ROOM["max_velocity"])),
                               label.sizeHint().height())
            self.labels[key] = label
            form.addRow(text, label)

    def show_info(self, curve: Curve, info: CurveInfo, limits: SlaveLimits) -> None:
        """Show the values; called on every mouse move of a drag, so only what changed is touched (a new style
        sheet re-polishes the label)."""
        cycles = fmt(curve.cycles_per_min)
        if self.cycles.text() != cycles or self.cycles._shown != cycles:
            self.cycles.show_value(cycles)
        v_pct, a_pct = percent(info.max_velocity, limits.velocity), percent(info.max_acceleration, limits.acceleration)
        for key, value, pct, unit in (("max_velocity", info.max_velocity, v_pct, "UU/MU"),
                                      ("max_acceleration", info.max_acceleration, a_pct, "UU/MU²")):
            # red above the limit [DG L3809, L3821]
            self._show(key, f"{fmt(value, 5)} {unit}   ({fmt(round(pct, 1))} %)", style=OVER_LIMIT if pct > 100 else "")
        self._show("velocity_limit", f"{fmt(limits.velocity, 5)} UU/MU")
        self._show("acceleration_limit", f"{fmt(limits.acceleration, 5)} UU/MU²")
        self._show("max_jerk", f"{fmt(info.max_jerk, 5)} UU/MU³")
        self._show("physical", f"master {fmt(info.master_velocity, 5)} MU/s, slave max "
                               f"{fmt(info.max_velocity_per_s, 5)} UU/s, {fmt(info.max_acceleration_per_s2, 5)} UU/s²")
        self._show("interval_size", f"{fmt(info.interval_size)} MU")
        # "This time should not be smaller than 30 milliseconds" [DG L3837]
        short = curve.interpolation and info.interval_time_ms < 20
        self._show("interval_time", fmt(round(info.interval_time_ms, 1)) if curve.interpolation
                   else "- (no interpolation)", style=OVER_LIMIT if short else "")
        tip = "shorter than 20-30 ms: use fewer intervals" if short else "30 to 100 ms are suitable"
        if self.labels["interval_time"].toolTip() != tip:
            self.labels["interval_time"].setToolTip(tip)

    def _show(self, key: str, text: str, *, style: str | None = None) -> None:
        label = self.labels[key]
        if label.text() != text:
            label.setText(text)
            if key != "interval_time":  # that one's tool tip is advice
                label.setToolTip(text if label.fontMetrics().horizontalAdvance(text) > label.width() else "")
        if style is not None and label.styleSheet() != style:
            label.setStyleSheet(style)


class ParameterCard(QWidget):
    """Axis parameters as on Controller → Parameters → Axis, with their internal numbers [DG L3845-3872]."""

    parameter_edited = Signal(str, str)  # parameter number, text

    def __init__(self, groups: list[tuple[str, list[tuple[str | None, str, int]]]]) -> None:
        super().__init__()
        row = QHBoxLayout(self)
        self.fields: dict[str, NumberField] = {}
        db = database()
        for title, entries in groups:
            box = QGroupBox(title) if title else QWidget()
            grid = QGridLayout(box)
            for r, (number, label, internal) in enumerate(entries):
                grid.addWidget(QLabel(label), r, 0)
                field = NumberField()
                if number is None:
                    field.setEnabled(False)
                    field.setToolTip("not in the MCO 305 parameter list")
                else:
                    param = db.get(number)
                    field.setToolTip(f"{param.label}: {param.description}")
                    field.entered.connect(lambda text, *, n=number: self.parameter_edited.emit(n, text))
                    self.fields[number] = field
                grid.addWidget(field, r, 1)
                grid.addWidget(QLabel(f"[{internal}]"), r, 2)
            grid.setRowStretch(len(entries), 1)
            row.addWidget(box)

    def show_parameters(self, values: dict[str, int | float]) -> None:
        db = database()
        for number, field in self.fields.items():
            field.show_value(fmt(values.get(number, db.get(number).default)))


def synchronization_card() -> ParameterCard:
    """Synchronization [DG L3850-3856]; Sync Filter Time [65] has no parameter in the MCO 305 list."""
    return ParameterCard([
        ("", [("33-12", "Position offset:", 54), ("33-27", "Offset Filter Time:", 16),
              ("33-29", "Marker Filter Time:", 18), ("33-28", "Marker Filter Config:", 17),
              ("33-13", "Accuracy:", 0), ("33-25", "Ready / num markers:", 56),
              ("33-24", "Error / num markers:", 57), ("33-14", "Velocity limit (%):", 66),
              ("33-23", "Marker start:", 62)]),
        ("Syncfactor [M:S]", [("33-10", "Master:", 49), ("33-11", "Slave:", 50),
                              ("33-26", "Slave Filter Time:", 106), ("33-32", "Pos. Feed Forward:", 109),
                              (None, "Sync Filter Time:", 65), ("33-33", "Sync Filter Limit:", 110)]),
    ])


def sync_marker_card() -> ParameterCard:
    """Sync. Marker [DG L3862-3872]: marker types 0/1 encoder Z rising/falling, 2/3 external rising/falling."""
    return ParameterCard([
        ("Master-Marker", [("33-19", "Type:", 60), ("33-15", "Count:", 52), ("33-17", "Distance:", 58),
                           ("33-21", "Tolerance:", 68)]),
        ("Slave-Marker", [("33-20", "Type:", 61), ("33-16", "Count:", 53), ("33-18", "Distance:", 59),
                          ("33-22", "Tolerance:", 69)]),
    ])


def encoder_card() -> ParameterCard:
    """The slave's encoder, user units and limits the Curve Info limits come from [DG L1422-1430, L8131]."""
    return ParameterCard([
        ("User units", [("32-12", "User Unit Numerator:", 0), ("32-11", "User Unit Denominator:", 0)]),
        ("Slave drive", [("32-01", "Encoder resolution:", 0), ("32-80", "Maximum velocity [rpm]:", 0),
                         ("32-81", "Shortest ramp [s]:", 0)]),
    ])


class DisplayOptions(QWidget):
    """The checkbox panel [DG L3876-3958]."""

    changed = Signal()
    OPTIONS = (("velocity", "Velocity", False), ("velocity_limit", "Vel. Limit", False),
               ("acceleration", "Acceleration", False), ("acceleration_limit", "Acc. Limit", False),
               ("jerk", "Jerk", False), ("slave_stop", "Slave Stop", False), ("start_stop", "Start-Stop", True),
               ("engage", "Engage Path", False), ("disengage", "Disengage Path", False),
               ("master_marker", "Master Marker", False), ("slave_marker", "Slave Marker", False),
               ("correction", "Correction", False), ("continuous_recalc", "Continuous Recalc", True),
               ("auto_scale", "Auto Scale", True), ("snap_on_grid", "Snap on Grid", False))

    def __init__(self) -> None:
        super().__init__()
        grid = QGridLayout(self)
        grid.setVerticalSpacing(2)
        self.boxes: dict[str, QCheckBox] = {}
        for i, (key, label, default) in enumerate(self.OPTIONS):
            box = QCheckBox(label)
            box.setChecked(default)
            box.toggled.connect(lambda _on: self.changed.emit())
            self.boxes[key] = box
            grid.addWidget(box, i % 5, i // 5)
        self.accuracy = QSpinBox()
        self.accuracy.setRange(1, 50)
        self.accuracy.setValue(4)
        self.accuracy.valueChanged.connect(lambda _v: self.changed.emit())
        acc = QHBoxLayout()
        acc.addWidget(QLabel("Mouse accuracy:"))
        acc.addWidget(self.accuracy)
        acc.addStretch(1)
        grid.addLayout(acc, 5, 0, 1, 3)

    def __getitem__(self, key: str) -> bool:
        return self.boxes[key].isChecked()

    def overlay(self, curve: Curve | None, parameters: dict[str, int | float], selected_pair: int | None) -> Overlay:
        """The overlay these options ask for, with ``curve``'s limits and marker positions under ``parameters``."""
        ov = Overlay(**{k: self[k] for k in ("velocity", "velocity_limit", "acceleration", "acceleration_limit",
                                             "jerk", "slave_stop", "start_stop", "engage", "disengage",
                                             "master_marker", "slave_marker", "correction")})
        ov.selected_pair = selected_pair
        if curve is not None:
            limits = slave_limits(curve, parameters)
            ov.velocity_limit_value, ov.acceleration_limit_value = limits.velocity, limits.acceleration
            p = parameters
            ov.master_marker_at = marker_detection(curve.master_marker_pos, parameter(p, "33-17"), curve.master_length)
            ov.master_tolerance = parameter(p, "33-21")
            # the slave marker is a slave position; reduced over the slave length when the curve has one
            s_len = abs(curve.slave_length)
            distance = parameter(p, "33-18")
            ov.slave_marker_at = (marker_detection(curve.slave_marker_pos, distance, s_len) if s_len
                                  else curve.slave_marker_pos - distance)
            ov.slave_tolerance = parameter(p, "33-22")
        return ov
