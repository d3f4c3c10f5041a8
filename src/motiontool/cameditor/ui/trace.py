"""Measured trace overlay of the CAM editor (beyond the manual, issue 6 item 5, decision C14).

Toolbar "Trace…": pick a CSV written by ``motiontool run --trace`` or by the oscilloscope's CSV export, choose the
master and slave columns (MAPOS / CMASTERCPOS and APOS proposed) and their scale factors; the slave position is
drawn over the master position modulo the current curve's master cycle as a grey dashed curve on top of the
designed profile, so the measured motion can be compared with the design.  "Clear trace" removes it.  The
parsing is Qt-free (motiontool.cameditor.trace).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QComboBox, QDialog, QDialogButtonBox, QFormLayout, QLabel, QVBoxLayout

from motiontool.camcurve.model import Curve
from motiontool.cameditor.trace import TraceError, TraceTable, guess_columns, read_trace, wrap
from motiontool.cameditor.ui.dialogs import _spin

TRACE_FILTER = "Traces (*.csv);;All files (*)"
TRACE_PEN = pg.mkPen((70, 70, 70), width=1.8, style=Qt.PenStyle.DashLine)


class TraceColumnsDialog(QDialog):
    """Master and slave column, scale factors and slave offset for a loaded trace."""

    def __init__(self, parent, table: TraceTable) -> None:
        super().__init__(parent)
        self.setWindowTitle("Overlay measured trace")
        self.table = table
        master, slave = guess_columns(table.names)
        self.master, self.slave = QComboBox(), QComboBox()
        for combo, current in ((self.master, master), (self.slave, slave)):
            combo.addItems(table.names)
            combo.setCurrentText(current or table.names[0 if combo is self.master else min(1, len(table.names) - 1)])
        self.master_scale = _spin(1.0, -1e9, 1e9, 6)
        self.slave_scale = _spin(1.0, -1e9, 1e9, 6)
        self.slave_offset = _spin(0.0, decimals=3)
        form = QFormLayout()
        form.addRow("Master position column", self.master)
        form.addRow("Slave position column", self.slave)
        form.addRow("Master scale [MU per unit]", self.master_scale)
        form.addRow("Slave scale [UU per unit]", self.slave_scale)
        form.addRow("Slave offset [UU]", self.slave_offset)
        layout = QVBoxLayout(self)
        source = Path(table.source).name
        kind = "motiontool run --trace" if table.layout == "trace" else "oscilloscope export"
        layout.addWidget(QLabel(f"<b>{source}</b> ({kind}, {len(table.names)} columns)"))
        layout.addLayout(form)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout.addWidget(buttons)


class TraceOverlay:
    """The overlay item on the editor's diagram and the actions that load and clear it."""

    def __init__(self, editor) -> None:
        self.editor = editor
        plot = editor.diagram.getPlotItem()
        self.item = pg.PlotDataItem(pen=TRACE_PEN, connect="finite")
        self.item.setZValue(5)  # above the designed curve's line, below the fix point markers
        plot.addItem(self.item)
        self.legend = pg.LegendItem(offset=(-10, 10), pen=pg.mkPen(150, 150, 150), brush=pg.mkBrush(255, 255, 255, 220))
        self.legend.setParentItem(plot.getViewBox())
        self.legend.hide()
        self.table: TraceTable | None = None
        self.settings: dict | None = None
        self.master = self.slave = np.zeros(0)

    # -- actions ---------------------------------------------------------------------------------------------------
    def load_dialog(self) -> None:
        path = self.editor.prompts.open_path("Overlay measured trace", "", TRACE_FILTER)
        if path is not None:
            self.load(path)

    def load(self, path: Path) -> TraceColumnsDialog | None:
        """Read the trace and open the column dialog (non-blocking, ``editor.dialog``); None when refused."""
        try:
            table = read_trace(path)
        except TraceError as exc:
            self.editor.message(f"Trace: {exc}")
            return None
        dialog = TraceColumnsDialog(self.editor, table)
        dialog.accepted.connect(lambda: self.apply(table, dialog.master.currentText(), dialog.slave.currentText(),
                                                   master_scale=dialog.master_scale.value(),
                                                   slave_scale=dialog.slave_scale.value(),
                                                   slave_offset=dialog.slave_offset.value()))
        self.editor.show_dialog(dialog)
        return dialog

    def apply(self, table: TraceTable, master: str, slave: str, *, master_scale: float = 1.0, slave_scale: float = 1.0,
              slave_offset: float = 0.0) -> bool:
        if master == slave:
            self.editor.message("Trace: choose different columns for the master and the slave position")
            return False
        try:
            self.master, self.slave = table.master_slave(master, slave)
        except TraceError as exc:
            self.editor.message(f"Trace: {exc}")
            return False
        self.table = table
        self.settings = {"master": master, "slave": slave, "master_scale": master_scale, "slave_scale": slave_scale,
                         "slave_offset": slave_offset}
        self.show(self.editor.curve())
        self.editor.message(f"Trace {Path(table.source).name}: {slave} over {master}, {len(self.slave)} samples",
                            error=False)
        return True

    def clear(self) -> None:
        self.table = self.settings = None
        self.master = self.slave = np.zeros(0)
        self.item.setData([], [])
        self.legend.hide()

    # -- drawing ---------------------------------------------------------------------------------------------------
    def show(self, curve: Curve | None) -> None:
        """Draw the trace wrapped onto ``curve``'s master cycle (nothing without a curve or a trace)."""
        if curve is None or self.settings is None:
            self.item.setData([], [])
            self.legend.hide()
            return
        s = self.settings
        if s["master_scale"]:  # unwrap before aligning time bases (the cycle in the column's own units)
            self.master, self.slave = self.table.master_slave(s["master"], s["slave"],
                                                              curve.master_length / s["master_scale"])
        x, y = wrap(self.master, self.slave, curve.master_length, curve.slave_length, s["master_scale"],
                    s["slave_scale"], s["slave_offset"])
        self.item.setData(x, y)
        self.legend.clear()
        self.legend.addItem(self.item, f"measured ({Path(self.table.source).name}): {s['slave']} over {s['master']}")
        self.legend.show()

    @property
    def data(self) -> tuple[np.ndarray, np.ndarray]:
        """What is drawn (x, y with NaN gaps)."""
        x, y = self.item.getData()
        return (np.zeros(0), np.zeros(0)) if x is None else (x, y)
