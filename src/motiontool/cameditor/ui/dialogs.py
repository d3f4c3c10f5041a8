"""Small dialogs of the CAM editor: Add CAM array, Curve Data "Set" (length/intervals, gradients), and the Add
dialogs of the two tables, which take several value pairs at once [DG L3582, L3737-3743, L3974, L4060]."""

from __future__ import annotations

import math
import re

from PySide6.QtWidgets import (
    QCheckBox,
    QDialog,
    QDialogButtonBox,
    QDoubleSpinBox,
    QFormLayout,
    QLabel,
    QLineEdit,
    QPlainTextEdit,
    QSpinBox,
    QVBoxLayout,
)

from motiontool.camcurve.model import MAX_NAME_LENGTH

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_PAIR_RE = re.compile(rf"\s*({_NUMBER})\s*[,;\s]\s*({_NUMBER})\s*")
BIG = 1_000_000_000.0


def parse_pairs(text: str) -> list[tuple[float, float]]:
    """Lines of "a, b" (comma, semicolon or blank between); raises ValueError naming the line."""
    pairs = []
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        m = _PAIR_RE.fullmatch(line)
        if not m:
            raise ValueError(f"line {number}: expected two numbers, got {line.strip()!r}")
        a, b = float(m.group(1)), float(m.group(2))
        if not (math.isfinite(a) and math.isfinite(b)):
            raise ValueError(f"line {number}: numbers must be finite")
        pairs.append((a, b))
    return pairs


def _spin(value: float, low: float = -BIG, high: float = BIG, decimals: int = 0) -> QDoubleSpinBox:
    box = QDoubleSpinBox()
    box.setDecimals(decimals)
    box.setRange(low, high)
    box.setValue(value)
    return box


def _buttons(dialog: QDialog) -> QDialogButtonBox:
    buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
    buttons.accepted.connect(dialog.accept)
    buttons.rejected.connect(dialog.reject)
    return buttons


class AddCurveDialog(QDialog):
    """Initial attributes of a new curve array: name, master length, intervals, Interpolation enabled."""

    def __init__(self, parent=None, name: str = "curve") -> None:
        super().__init__(parent)
        self.setWindowTitle("Add CAM array")
        form = QFormLayout(self)
        self.name = QLineEdit(name)
        self.name.setMaxLength(MAX_NAME_LENGTH)
        self.master_length = _spin(4000, 1)
        self.intervals = QSpinBox()
        self.intervals.setRange(1, 100_000)
        self.intervals.setValue(40)
        self.interpolation = QCheckBox("Interpolation enabled")
        self.interpolation.setChecked(True)
        form.addRow("Name of Curve:", self.name)
        form.addRow("Master Length [MU]:", self.master_length)
        form.addRow("Number of Intervals:", self.intervals)
        form.addRow("", self.interpolation)
        form.addRow(_buttons(self))


class SetLengthDialog(QDialog):
    """Curve Data "Set": master length and number of intervals together; Interpolation enabled [DG L3737, L3785]."""

    def __init__(self, parent, master_length: float, intervals: int, interpolation: bool) -> None:
        super().__init__(parent)
        self.setWindowTitle("Set master length")
        form = QFormLayout(self)
        self.master_length = _spin(master_length, 1)
        self.intervals = QSpinBox()
        self.intervals.setRange(1, 100_000)
        self.intervals.setValue(intervals)
        self.interpolation = QCheckBox("Interpolation enabled")
        self.interpolation.setChecked(interpolation)
        self.size = QLabel()
        for box in (self.master_length, self.intervals):
            box.valueChanged.connect(self._update)
        self._update()
        form.addRow("Master Length [MU]:", self.master_length)
        form.addRow("Number of Intervals:", self.intervals)
        form.addRow("Interval size [MU]:", self.size)
        form.addRow("", self.interpolation)
        form.addRow(QLabel("The slave length is not changed."))
        form.addRow(_buttons(self))

    def _update(self) -> None:
        self.size.setText(f"{self.master_length.value() / self.intervals.value():g}")


class GradientDialog(QDialog):
    """Start and end gradients of the "Specify ..." curve types [DG L3716-3727]."""

    def __init__(self, parent, start: float, end: float) -> None:
        super().__init__(parent)
        self.setWindowTitle("Set gradients")
        form = QFormLayout(self)
        self.start = _spin(start, decimals=6)
        self.end = _spin(end, decimals=6)
        form.addRow("Start gradient [UU/MU]:", self.start)
        form.addRow("End gradient [UU/MU]:", self.end)
        form.addRow(_buttons(self))


class PairsDialog(QDialog):
    """Add several pairs at once, one "a, b" per line, in any order [DG L3974, L4060]."""

    def __init__(self, parent, title: str, first: str, second: str, text: str = "") -> None:
        super().__init__(parent)
        self.setWindowTitle(title)
        layout = QVBoxLayout(self)
        layout.addWidget(QLabel(f"One pair per line: {first}, {second}"))
        self.text = QPlainTextEdit(text)
        self.text.setTabChangesFocus(True)
        layout.addWidget(self.text)
        self.error = QLabel()
        self.error.setStyleSheet("color: #b00000")
        layout.addWidget(self.error)
        layout.addWidget(_buttons(self))
        self.pairs: list[tuple[float, float]] = []

    def accept(self) -> None:
        try:
            self.pairs = parse_pairs(self.text.toPlainText())
        except ValueError as exc:
            self.error.setText(str(exc))
            return
        super().accept()


class PairDialog(QDialog):
    """Double-click on a start/stop pair: change Start and Stop [DG L4068-4070]."""

    def __init__(self, parent, k: int, start: float, stop: float) -> None:
        super().__init__(parent)
        self.setWindowTitle(f"Start Stop pair {k}")
        form = QFormLayout(self)
        self.start = _spin(start, 0)
        self.stop = _spin(stop, 0)
        form.addRow("Start [MU]:", self.start)
        form.addRow("Stop [MU]:", self.stop)
        form.addRow(_buttons(self))
