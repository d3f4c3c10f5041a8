"""FFT view (beyond the manual): the amplitude spectra of the visible curves between cursors A and B, or over
the visible time range when the cursors are not both set."""

from __future__ import annotations

import pyqtgraph as pg
from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget

from motiontool.scope.spectrum import amplitude_spectrum


class FftView(QWidget):
    def __init__(self, window, parent=None):
        super().__init__(parent)
        self.setWindowTitle("Oscilloscope — FFT")
        ta, tb = window.scope.cursors
        if ta is not None and tb is not None and window.chart.cursors[0].isVisible():
            t0, t1 = sorted((ta, tb))
        else:
            x0, x1 = window.chart.view.viewRange()[0]
            t0, t1 = x0 + window.chart.origin(), x1 + window.chart.origin()
        self.range = (t0, t1)
        self.plot = pg.PlotWidget()
        self.plot.setBackground("w")
        self.plot.setLabel("bottom", "frequency", units="Hz")
        self.plot.setLabel("left", "amplitude")
        self.plot.showGrid(x=True, y=True, alpha=0.3)
        self.plot.addLegend()
        self.spectra: dict[str, tuple] = {}
        skipped = []
        for curve in window.scope.curves:
            if not curve.visible:
                continue
            t, y = curve.raw()
            try:
                f, a = amplitude_spectrum(t, curve.scaled(y), t0, t1)
            except ValueError as exc:
                skipped.append(f"{curve.name}: {exc}")
                continue
            self.spectra[curve.name] = (f, a)
            self.plot.plot(f[1:], a[1:], pen=pg.mkPen(curve.colour), name=curve.name)  # without DC
        layout = QVBoxLayout(self)
        note = f"{t0:.0f} … {t1:.0f} ms, mean removed, Hann window"
        layout.addWidget(QLabel(note + ("" if not skipped else "   (skipped: " + "; ".join(skipped) + ")")))
        layout.addWidget(self.plot)
        self.resize(900, 500)
