"""The CAM editor's second curve kind: APC CAM tables (seed 004 §4.7; model in cameditor.apctable).

The diagram shows the CAM reference over the master (cycles repeating, the ratio applied) with the segment joins
marked, and below it the slave speed relative to the master, so a speed step at a join is seen at once. The
segment table edits In / Out / law / Out2; the settings edit start, size, ratio, single shot and the
delta-segment limit; the findings list what the checks say. Export writes the DPL an Initial task needs, Import
reads the CAM of any DPL program, the calculators fill a trapezoid, and Test run runs the table on the simulated
APC through a Link and draws the measured reference over the drawing.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QPushButton,
    QSizePolicy,
    QSpinBox,
    QSplitter,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from motiontool.apc.calculators import trapezoid_from_slave, trapezoid_from_times
from motiontool.apc.camlaws import LAW_NAMES
from motiontool.camcurve.model import Curve
from motiontool.cameditor.apcconvert import curve_to_smooth_table, table_to_curve
from motiontool.cameditor.apcdpl import DplImportError, import_dpl, table_program, table_to_dpl
from motiontool.cameditor.apctable import ApcCamTable, ApcSegment, ApcTableError
from motiontool.fileio import atomic_write_text
from motiontool.qtjobs.prompts import prompts_for

WORKED_EXAMPLE = ApcCamTable("Cam", (ApcSegment(109227, 109227, 2), ApcSegment(218454, 436908, 0),
                                     ApcSegment(54613, 54613, 3)))   # §4.7.2, L1261-1376
COLUMNS = ("In (master)", "Out (slave)", "Law", "Out2 (linear)")
INT31 = 2_147_483_647


def _spin(low: int, high: int, value: int) -> QSpinBox:
    box = QSpinBox()
    box.setRange(low, high)
    box.setValue(value)
    return box


class ApcPanel(QWidget):
    """Edits one APC CAM table; `table_changed` after every accepted change."""

    table_changed = Signal()

    def __init__(self, parent=None, *, curve_provider: Callable[[], Curve | None] | None = None,
                 curve_sink: Callable[[Curve], None] | None = None) -> None:
        super().__init__(parent)
        self.curve_provider = curve_provider or (lambda: None)
        self.curve_sink = curve_sink
        self.table = WORKED_EXAMPLE
        self.trace: tuple[np.ndarray, np.ndarray] | None = None
        self._loading = False
        self._build()
        self.set_table(WORKED_EXAMPLE)

    # --- layout ------------------------------------------------------------------------------------------------
    def _build(self) -> None:
        self.plot = pg.PlotWidget(background="w")
        self.plot.setLabel("left", "slave reference", units="counts")
        self.plot.showGrid(x=True, y=True, alpha=0.25)
        self.speed_plot = pg.PlotWidget(background="w")
        self.speed_plot.setLabel("left", "speed ratio")
        self.speed_plot.setLabel("bottom", "master", units="counts")
        self.speed_plot.setXLink(self.plot)
        self.speed_plot.showGrid(x=True, y=True, alpha=0.25)
        self.message = QLabel()
        self.message.setWordWrap(True)
        self.message.setSizePolicy(QSizePolicy.Policy.Preferred, QSizePolicy.Policy.Maximum)
        self.grid = QTableWidget(0, len(COLUMNS))
        self.grid.setHorizontalHeaderLabels(COLUMNS)
        self.grid.horizontalHeader().setStretchLastSection(True)
        self.findings = QListWidget()
        self.findings.setWordWrap(True)
        self.name = QLineEdit()
        self.start = _spin(0, 65535, 0)
        self.size = _spin(0, 65535, 0)
        self.size.setSpecialValueText("to the end")
        self.numerator = _spin(0, INT31, 1000)
        self.denominator = _spin(1, INT31, 1000)
        self.single_shot = QCheckBox("single shot")
        self.seg_limit = _spin(0, 65535, 256)
        self.master_rpm = _spin(1, 40000, 100)
        self.counts_per_rev = _spin(1, 1 << 30, 65536)
        self.cycles = _spin(1, 10, 2)
        form = QFormLayout()
        form.addRow("Name:", self.name)
        form.addRow("Start index:", self.start)
        form.addRow("Size:", self.size)
        form.addRow("Ratio N / D:", self._pair(self.numerator, self.denominator))
        form.addRow("", self.single_shot)
        form.addRow("Delta-segment limit:", self.seg_limit)
        form.addRow("Master speed (rpm):", self.master_rpm)
        form.addRow("Master counts/rev:", self.counts_per_rev)
        form.addRow("Cycles shown:", self.cycles)
        self.buttons = {name: QPushButton(text) for name, text in (
            ("add", "Add segment"), ("delete", "Delete segment"), ("trapezoid", "Trapezoid…"),
            ("import", "Import DPL…"), ("export", "Export DPL…"), ("from_mco", "From MCO curve"),
            ("to_mco", "To MCO curve"), ("test", "Test run"))}
        buttons = QVBoxLayout()
        for button in self.buttons.values():
            buttons.addWidget(button)
        side = QWidget()
        side_layout = QVBoxLayout(side)
        side_layout.addLayout(form)
        side_layout.addLayout(buttons)
        side_layout.addWidget(QLabel("Checks:"))
        side_layout.addWidget(self.findings)
        plots = QSplitter(Qt.Orientation.Vertical)
        plots.addWidget(self.plot)
        plots.addWidget(self.speed_plot)
        plots.addWidget(self.grid)
        plots.setSizes([420, 160, 220])
        top = QSplitter(Qt.Orientation.Horizontal)
        top.addWidget(plots)
        top.addWidget(side)
        top.setSizes([950, 330])
        layout = QVBoxLayout(self)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.addWidget(self.message)
        layout.addWidget(top)
        self.grid.itemChanged.connect(lambda *_: self._edited())
        for box in (self.start, self.size, self.numerator, self.denominator, self.seg_limit, self.master_rpm,
                    self.counts_per_rev, self.cycles):
            box.valueChanged.connect(lambda *_: self._edited())
        self.single_shot.toggled.connect(lambda *_: self._edited())
        self.name.editingFinished.connect(self._edited)
        actions = {"add": self.add_segment, "delete": self.delete_segment, "trapezoid": self.trapezoid_dialog,
                   "import": self.import_dialog, "export": self.export_dialog, "from_mco": self.from_mco,
                   "to_mco": self.to_mco, "test": self.test_run}
        for name, slot in actions.items():
            self.buttons[name].clicked.connect(lambda *_, f=slot: f())

    @staticmethod
    def _pair(a: QWidget, b: QWidget) -> QWidget:
        w = QWidget()
        row = QHBoxLayout(w)
        row.setContentsMargins(0, 0, 0, 0)
        row.addWidget(a)
        row.addWidget(QLabel("/"))
        row.addWidget(b)
        return w

    # --- the table ---------------------------------------------------------------------------------------------
    def set_table(self, table: ApcCamTable) -> None:
        """Show `table` in every widget (no edit is recorded)."""
        self._loading = True
        try:
            self.table = table
            self.grid.setRowCount(len(table.segments))
            self.grid.setVerticalHeaderLabels([str(i) for i in range(len(table.segments))])  # APC counts from 0
            for row, s in enumerate(table.segments):
                for col, value in ((0, s.master), (1, s.slave), (3, s.slave2)):
                    self.grid.setItem(row, col, QTableWidgetItem(str(value)))
                law = QComboBox()
                law.addItems([f"{n} {name}" for n, name in enumerate(LAW_NAMES)])
                law.setCurrentIndex(s.law)
                law.currentIndexChanged.connect(lambda *_: self._edited())
                self.grid.setCellWidget(row, 2, law)
            self.name.setText(table.name)
            self.start.setValue(table.start)
            self.size.setValue(table.size or 0)
            self.numerator.setValue(table.ratio[0])
            self.denominator.setValue(table.ratio[1])
            self.single_shot.setChecked(table.single_shot)
            self.seg_limit.setValue(table.delta_seg_limit)
        finally:
            self._loading = False
        self.trace = None
        self.redraw()

    def replace_table(self, table: ApcCamTable) -> None:
        """A new table from a command (import, calculator, conversion, a segment added or deleted)."""
        self.set_table(table)
        self.table_changed.emit()

    def _read_widgets(self) -> ApcCamTable:
        segments = []
        for row in range(self.grid.rowCount()):
            values = []
            for col in (0, 1, 3):
                item = self.grid.item(row, col)
                text = item.text().strip() if item is not None else "0"
                try:
                    values.append(int(text or "0", 0))
                except ValueError:
                    raise ApcTableError("segments", f"segment {row}: '{text}' is not a whole number of counts",
                                        row) from None
            segments.append(ApcSegment(values[0], values[1], self.grid.cellWidget(row, 2).currentIndex(), values[2]))
        return ApcCamTable(self.name.text().strip() or "Cam", tuple(segments), start=self.start.value(),
                           size=self.size.value() or None, ratio=(self.numerator.value(), self.denominator.value()),
                           single_shot=self.single_shot.isChecked(), delta_seg_limit=self.seg_limit.value())

    def _edited(self) -> None:
        if self._loading:
            return
        try:
            table = self._read_widgets()
        except ApcTableError as exc:  # the widgets keep what the user typed; the last good table stays drawn
            self.show_message(str(exc))
            return
        self.table = table
        self.trace = None
        self.redraw()
        self.table_changed.emit()

    def show_message(self, text: str, *, error: bool = True) -> None:
        self.message.setText(text)
        self.message.setStyleSheet(("background: #ffe4e4; color: #a00000;" if error else
                                    "background: #e8f4e8; color: #1d5a1d;") + " padding: 3px" if text else "")

    def add_segment(self) -> None:
        last = self.table.segments[-1]
        self.replace_table(self.table.with_segments(self.table.segments + (ApcSegment(last.master, 0, 0),)))

    def delete_segment(self) -> None:
        row = self.grid.currentRow()
        segments = list(self.table.segments)
        if len(segments) < 2 or not 0 <= row < len(segments):
            self.show_message("select a segment to delete (a CAM keeps at least one)")
            return
        del segments[row]
        try:
            table = ApcCamTable(self.table.name, tuple(segments), start=min(self.table.start, len(segments) - 1),
                                ratio=self.table.ratio, single_shot=self.table.single_shot,
                                delta_seg_limit=self.table.delta_seg_limit)
        except ApcTableError as exc:
            self.show_message(str(exc))
            return
        self.replace_table(table)

    # --- drawing -----------------------------------------------------------------------------------------------
    def master_speed(self) -> float:
        """Master counts per second at the set master speed."""
        return self.master_rpm.value() / 60 * self.counts_per_rev.value()

    def redraw(self) -> None:
        table = self.table
        cycles = self.cycles.value()
        masters, slaves = table.samples(points=min(4000, 600 * cycles), cycles=cycles)
        self.plot.clear()
        self.speed_plot.clear()
        if self.plot.plotItem.legend is None:
            self.plot.addLegend(offset=(10, 10))
        self.plot.plot(masters, slaves, pen=pg.mkPen((30, 80, 230, 150), width=6), name="table (drawing)")
        joins, position = [], 0
        for _ in range(cycles):
            for s in table.window:
                position += s.master
                joins.append(position)
        self.plot.plot(joins, [table.reference(m) for m in joins], pen=None, symbol="o", symbolSize=7,
                       symbolBrush=(210, 30, 30), name="segment ends")
        m = np.asarray(masters, dtype=float)
        speed = np.diff(slaves) / np.maximum(np.diff(m), 1)
        self.speed_plot.plot(m[1:], speed, pen=pg.mkPen((0, 150, 0), width=1.5))
        if self.trace is not None:
            self.plot.plot(*self.trace, pen=pg.mkPen((220, 0, 220), width=1.5), name="test run on the simulated APC")
        self.findings.clear()
        findings = table.check(master_speed=self.master_speed())
        for f in findings:
            self.findings.addItem(f"{f.severity}: {f.message}")
        if not findings:
            self.findings.addItem("no speed steps; the delta-segment limit holds at this master speed")
        self.show_message(f"{table.name}: {len(table.window)} segments, one cycle master {table.master_length} / "
                          f"slave {table.slave_travel} counts (before the ratio)", error=False)

    # --- files, calculators, conversions -----------------------------------------------------------------------
    def export_dialog(self, *, path: Path | None = None) -> bool:
        """Export DPL: the Initial-task lines for this table (or a whole runnable program for a .dpl file)."""
        if path is None:
            path = prompts_for(self).save_path("Export DPL", f"{self.table.name}.dpl",
                                               "DPL program (*.dpl);;DPL lines (*.txt)")
            if path is None:
                return False
        text = table_program(self.table, master_rpm=self.master_rpm.value(),
                             counts_per_rev=self.counts_per_rev.value()) \
            if path.suffix.lower() == ".dpl" else table_to_dpl(self.table)
        atomic_write_text(path, text)
        self.show_message(f"exported to {path}", error=False)
        return True

    def import_dialog(self, *, path: Path | None = None) -> bool:
        if path is None:
            path = prompts_for(self).open_path("Import DPL", "", "DPL programs (*.dpl);;All files (*)")
            if path is None:
                return False
        try:
            table = import_dpl(path.read_text(encoding="utf-8"), str(path))
        except DplImportError as exc:  # its messages name the file already
            self.show_message(str(exc))
            return False
        except (OSError, UnicodeDecodeError) as exc:
            self.show_message(f"{path}: {exc}")
            return False
        self.replace_table(table)
        return True

    def trapezoid_dialog(self, *, values: dict | None = None) -> bool:
        """The manual's calculators (§4.7.11/12): from slave distances or from times; replaces the segments."""
        if values is None:
            values = TrapezoidDialog.ask(self)
            if values is None:
                return False
        try:
            if values["mode"] == "distances":
                t, _ = trapezoid_from_slave(values["pmt"], values["pst"], values["psa"], values["psd"])
            else:
                t = trapezoid_from_times(values["a1"], values["a2"], values["a3"], values["pst"], values["vm"])
            table = self.table.with_segments(ApcSegment(x, y, law) for x, y, law in
                                             zip(t.master, t.slave, (2, 0, 3), strict=True))
        except (ValueError, ZeroDivisionError, ApcTableError) as exc:
            self.show_message(f"trapezoid: {exc}")
            return False
        self.replace_table(table)
        return True

    def from_mco(self) -> bool:
        curve = self.curve_provider()
        if curve is None:
            self.show_message("no MCO curve is selected in the Fix-point curves tab")
            return False
        try:
            # speed continuous at every join; the laws alone stepped it at each of 81 Linear joins (decision C21)
            result = curve_to_smooth_table(curve, name=None, tolerance=2.0)
        except ValueError as exc:
            self.show_message(f"From MCO curve: {exc}")
            return False
        self.replace_table(result.table)
        self.show_message(f"from '{curve.name}': {len(result.table.segments)} Square1 segments with a linear "
                          f"OutArray2 part, speed continuous at every join; largest position error "
                          f"{result.max_error:.2f} counts", error=False)
        return True

    def to_mco(self) -> bool:
        result = table_to_curve(self.table, points_per_segment=16)
        if self.curve_sink is not None:
            self.curve_sink(result.curve)
        self.show_message(f"MCO curve '{result.curve.name}' with {len(result.curve.fix_points)} fix points; the "
                          f"spline through them is within {result.max_error:.1f} counts", error=False)
        return True

    def test_run(self) -> float | None:
        """Run the table on the simulated APC (a Link, virtual time): the measured CAM reference is drawn over
        the table, and the largest difference is reported (0: the simulator does what the editor shows)."""
        from motiontool.comms.links import open_link
        from motiontool.dpl.image import DplImage

        table, rpm, cpr = self.table, self.master_rpm.value(), self.counts_per_rev.value()
        step = (rpm * cpr) // 60000                          # master counts per 1 ms sample (MULDIV truncates)
        if step <= 0:
            self.show_message("the master speed gives no master counts per millisecond")
            return None
        duration = min(120_000, table.master_length * self.cycles.value() // step + 2)
        rows: list[list[int]] = []
        link = open_link("apcsim")                               # virtual time: `advance` moves it
        link.subscribe(lambda e: rows.extend(e.data["values"]) if e.kind == "samples" else None)
        try:
            link.download(DplImage("cam_test.dpl", table_program(table, master_rpm=rpm, counts_per_rev=cpr))
                          .to_bytes(), name="cam_test.dpl")
            link.stream(["APC_RF_POS", "APC_PROF_OUT_POS"], interval_ms=1)
            link.start()
            link.advance(duration)
            link.stream([], interval_ms=1)
            link.flush_events()
        finally:
            link.close()
        engaged = rows[1][0] - step                         # the CAM engages in the first sample
        masters = np.array([r[0] - engaged for r in rows[1:]])
        measured = np.array([r[1] for r in rows[1:]])
        drawn = np.array([table.reference(int(m)) for m in masters])
        self.trace = (masters, measured)
        self.redraw()
        worst = float(np.max(np.abs(measured - drawn))) if len(drawn) else 0.0
        self.show_message(f"test run on the simulated APC: {len(masters)} samples at {rpm} rpm, largest difference "
                          f"from the drawing {worst:g} counts", error=worst != 0)
        return worst


class TrapezoidDialog(QDialog):
    """The manual's two calculators for a Square1 / Linear / Square2 trapezoid."""

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Trapezoid calculator")
        form = QFormLayout(self)
        self.mode = QComboBox()
        self.mode.addItems(["from slave distances (§4.7.11)", "from times (§4.7.12)"])
        self.fields = {key: QLineEdit(default) for key, default in (
            ("pmt", "382294"), ("pst", "600748"), ("psa", "109227"), ("psd", "54613"),
            ("a1", "1"), ("a2", "2"), ("a3", "0.5"), ("vm", "109227"))}
        form.addRow("Calculate:", self.mode)
        for key, label in (("pmt", "Master total Pmt"), ("pst", "Slave total Pst"), ("psa", "Slave accel Psa"),
                           ("psd", "Slave decel Psd"), ("a1", "Accel time A1 (s)"), ("a2", "Constant time A2 (s)"),
                           ("a3", "Decel time A3 (s)"), ("vm", "Master speed Vm (counts/s)")):
            form.addRow(label + ":", self.fields[key])
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def values(self) -> dict:
        from fractions import Fraction

        out: dict = {"mode": "distances" if self.mode.currentIndex() == 0 else "times"}
        for key, field in self.fields.items():
            out[key] = Fraction(field.text().strip()) if key in ("a1", "a2", "a3", "vm") else int(field.text(), 0)
        return out

    @classmethod
    def ask(cls, parent) -> dict | None:
        dialog = cls(parent)
        if not dialog.exec():
            return None
        try:
            return dialog.values()
        except ValueError as exc:
            parent.show_message(f"trapezoid: {exc}")
            return None
