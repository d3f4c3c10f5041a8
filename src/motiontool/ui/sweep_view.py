"""Tools ▸ Sweep Results: a finished `motiontool sweep` as a table and a plot (issue 30 item 2, decision R22).

One varied parameter gives a line plot of the chosen measure over it, two or more a heat map over the first two.
Failed points stay in the table, red, with their error. Any point's run opens in the oscilloscope: the program is
run again at that point on a fresh simulated controller (as the sweep ran it) on a worker thread, recording the
measures' signals and the axis' APOS, CPOS and TRACKERR."""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtGui import QColor
from PySide6.QtWidgets import (
    QComboBox,
    QDoubleSpinBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QMainWindow,
    QPushButton,
    QSplitter,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from motiontool.paramdb import database
from motiontool.scope.curves import PALETTE, Curve, Scope, Source
from motiontool.session.prompts import Prompts
from motiontool.sweep.measures import format_value
from motiontool.sweep.results import ResultsError, SweepResults, read_results
from motiontool.ui.link_jobs import LinkJobs
from motiontool.ui.prompts import QtPrompts

AXIS_SIGNALS = ("APOS", "CPOS", "TRACKERR")   # what a point's run shows beside the measures' signals (MCO)
FAILED = QColor(255, 220, 220)
MAX_TICKS = 12


class SweepView(QMainWindow):
    def __init__(self, results: SweepResults, path: Path, program: str = "", parent=None,
                 prompts: Prompts | None = None):
        super().__init__(parent)
        self.prompts = prompts.within(self) if prompts is not None else QtPrompts(self)   # the window's, over this
        self.results, self.path = results, path
        self.setWindowTitle(f"Sweep Results – {path.name}")
        self.jobs = LinkJobs(self)
        self.scopes: list[QMainWindow] = []
        self.measure = QComboBox()
        self.measure.addItems(results.measures)
        self.measure.currentIndexChanged.connect(self.draw)
        self.table = self._table()
        self.table.itemSelectionChanged.connect(self._selection_changed)
        self.table.itemDoubleClicked.connect(lambda _item: self.open_point())
        self.plot = pg.PlotWidget()
        self.plot.scene().sigMouseClicked.connect(self._plot_clicked)
        self.program = QLineEdit(program)
        self.program.setPlaceholderText("the swept program (.m or .dpl): to open a point's run")
        browse = QPushButton("Browse…")
        browse.clicked.connect(self._browse)
        # the sweep's own default; the CSV does not say which --seconds it ran with
        self.seconds = QDoubleSpinBox(decimals=1, minimum=0.1, maximum=3600.0, value=60.0, suffix=" s")
        self.seconds.setToolTip("virtual time of the point's run: give the sweep's --seconds (default 60) to see "
                                "the run its row measured")
        self.open_button = QPushButton("Open Point in Scope")
        self.open_button.clicked.connect(self.open_point)
        self.status = QLabel()
        self.status.setWordWrap(True)
        self._bar: pg.ColorBarItem | None = None
        self.setCentralWidget(self._layout(browse))
        self.draw()
        self._selection_changed()
        self.resize(1000, 600)

    # --- building ----------------------------------------------------------------------------------------------
    def _table(self) -> QTableWidget:
        r = self.results
        headers = ["point", *r.keys, *r.measures, "error"]
        table = QTableWidget(len(r.numbers), len(headers))
        table.setHorizontalHeaderLabels(headers)
        table.verticalHeader().hide()
        table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        table.setSelectionBehavior(QTableWidget.SelectionBehavior.SelectRows)
        table.setSelectionMode(QTableWidget.SelectionMode.SingleSelection)
        for row, number in enumerate(r.numbers):
            cells = [str(number), *(str(v) for v in r.points[row]), *(_shown(v) for v in r.values[row]),
                     r.errors[row]]
            for col, text in enumerate(cells):
                item = QTableWidgetItem(text)
                if col and col <= len(r.keys) + len(r.measures):
                    item.setTextAlignment(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
                if r.errors[row]:
                    item.setBackground(FAILED)
                    item.setToolTip(r.errors[row])
                table.setItem(row, col, item)
        table.resizeColumnsToContents()
        table.horizontalHeader().setStretchLastSection(True)    # the error column takes the room that is left
        return table

    def _layout(self, browse: QPushButton) -> QWidget:
        top = QHBoxLayout()
        top.addWidget(QLabel("Measure:"))
        top.addWidget(self.measure, 1)
        r = self.results
        top.addWidget(QLabel(f"{len(r.numbers)} points, {r.failed} failed"))
        split = QSplitter()
        split.addWidget(self.table)
        split.addWidget(self.plot)
        split.setSizes([450, 550])
        run = QHBoxLayout()
        run.addWidget(QLabel("Program:"))
        run.addWidget(self.program, 1)
        run.addWidget(browse)
        run.addWidget(QLabel("Run for"))
        run.addWidget(self.seconds)
        run.addWidget(self.open_button)
        body = QWidget()
        layout = QVBoxLayout(body)
        layout.addLayout(top)
        layout.addWidget(split, 1)
        layout.addLayout(run)
        layout.addWidget(self.status)
        return body

    # --- the plot ------------------------------------------------------------------------------------------------
    def draw(self) -> None:
        r, m = self.results, max(self.measure.currentIndex(), 0)
        self.plot.clear()
        self._mark = pg.ScatterPlotItem(size=14, pen=pg.mkPen("w", width=2), brush=None, symbol="s")
        self.plot.setLabel("bottom", _key_label(r.keys[0]))
        if len(r.keys) == 1:
            x, y = r.line(m)
            self.plot.setLabel("left", r.measures[m])
            self.plot.plot(x, y, pen=pg.mkPen(PALETTE[0], width=2), symbol="o", symbolSize=6, connect="finite")
            self.plot.getAxis("bottom").setTicks(None)
            self.plot.getAxis("left").setTicks(None)
        else:
            xs, ys, grid = r.grid(m)
            self.plot.setLabel("left", _key_label(r.keys[1]))
            self.plot.setTitle(r.measures[m] + ("" if len(r.keys) == 2 else " (the last point of each cell)"))
            image = pg.ImageItem(grid)      # cells by index: the parameters need not be evenly spaced
            self.plot.addItem(image)
            finite = grid[np.isfinite(grid)]
            low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
            levels = (low, high if high > low else low + 1)
            if self._bar is None:    # one colour bar for the window's life, beside the plot
                self._bar = pg.ColorBarItem(values=levels, colorMap="viridis", interactive=False)
                self._bar.setImageItem(image, insert_in=self.plot.getPlotItem())
            else:
                self._bar.setImageItem(image)
                self._bar.setLevels(levels)
            self.plot.getAxis("bottom").setTicks([_ticks(xs)])
            self.plot.getAxis("left").setTicks([_ticks(ys)])
        self.plot.addItem(self._mark)
        self._show_mark()
        self.plot.autoRange()

    def _show_mark(self) -> None:
        """A ring on the plot where the point selected in the table is."""
        rows = self.table.selectionModel().selectedRows()
        if not rows:
            self._mark.setData([], [])
            return
        r, row, m = self.results, rows[0].row(), max(self.measure.currentIndex(), 0)
        if len(r.keys) == 1:
            self._mark.setData([float(r.points[row, 0])], [float(r.values[row, m])], symbol="o")
        else:
            xs, ys, _ = r.grid(m)
            i = int(np.searchsorted(xs, r.points[row, 0]))
            j = int(np.searchsorted(ys, r.points[row, 1]))
            self._mark.setData([i + 0.5], [j + 0.5], symbol="s")

    def _plot_clicked(self, event) -> None:
        """A click on a heat-map cell or near a point of the line selects that point in the table."""
        pos = self.plot.getPlotItem().vb.mapSceneToView(event.scenePos())
        r = self.results
        if len(r.keys) == 1:
            x = r.points[:, 0]
            candidates = np.flatnonzero(np.abs(x - pos.x()) == np.abs(x - pos.x()).min()) if x.size else []
        else:
            xs, ys, _ = r.grid(0)
            i, j = math.floor(pos.x()), math.floor(pos.y())
            if not (0 <= i < xs.size and 0 <= j < ys.size):
                return
            candidates = np.flatnonzero((r.points[:, 0] == xs[i]) & (r.points[:, 1] == ys[j]))
        if len(candidates):
            self.table.selectRow(int(candidates[-1]))

    # --- a point's run -------------------------------------------------------------------------------------------
    def _selection_changed(self) -> None:
        rows = self.table.selectionModel().selectedRows()
        self.open_button.setEnabled(bool(rows))
        self._show_mark()

    def _browse(self) -> None:
        chosen = self.prompts.open_path("Swept program", self.program.text(), "Programs (*.m *.dpl);;All files (*)")
        if chosen is not None:
            self.program.setText(str(chosen))

    def open_point(self) -> None:
        rows = self.table.selectionModel().selectedRows()
        if not rows or self.jobs.pending:     # a double click while a point runs does not queue a second one
            return
        row = rows[0].row()
        program = self.program.text().strip()
        if not program:
            self.status.setText("Give the swept program (Program: Browse…) to run a point again.")
            return
        number = self.results.numbers[row]
        values = tuple(int(v) for v in self.results.points[row])
        seconds = self.seconds.value()
        self.open_button.setEnabled(False)
        self.status.setText(f"Running point {number} ({self._point_text(row)}) for {seconds:g} s …")
        self.jobs.run(lambda: run_point(Path(program), self.results, values, seconds),
                      lambda result: self._ran(number, row, result))

    def _point_text(self, row: int) -> str:
        return ", ".join(f"{k}={v}" for k, v in zip(self.results.keys, self.results.points[row], strict=True))

    def _ran(self, number: int, row: int, result) -> None:
        self._selection_changed()
        if isinstance(result, Exception):
            self.status.setText(f"Point {number}: {result}")
            return
        from motiontool.scope.ui.window import ScopeWindow

        scope = point_scope(result, f"point {number}: {self._point_text(row)}")
        window = ScopeWindow(None, scope.variant, scope=scope, parent=self, ask=False, prompts=self.prompts)
        window.setWindowTitle(f"Oscilloscope – sweep point {number} ({self._point_text(row)})")
        window.zoom_reset()
        window.show()
        self.scopes = [s for s in self.scopes if s.isVisible()] + [window]
        errors = "; ".join(result.errors)
        self.status.setText(f"Point {number} opened in the oscilloscope" + (f" (it stopped: {errors})" if errors
                                                                              else ""))


def run_point(program: Path, results: SweepResults, values: tuple[int, ...], seconds: float):
    """The point's run (on the jobs thread): compiled and checked as the sweep does; ValueError says why not."""
    from motiontool.sweep.points import SweepError
    from motiontool.sweep.runner import record_run
    from motiontool.sweep.setup import prepare

    diagnostics = io.StringIO()
    try:
        job = prepare(program, list(results.keys), list(results.measures), [], seconds, [], diagnostics)
    except (SweepError, OSError) as exc:
        raise ValueError(str(exc)) from None
    if job is None:
        raise ValueError(" ".join(diagnostics.getvalue().split())[:300] or f"{program.name} does not compile")
    signals = job.signals()
    if job.kind == "aposs":
        signals += [s for s in AXIS_SIGNALS if s not in signals]
    run = record_run(job, values, signals)
    if run.refused:
        raise ValueError(run.refused)
    return run


def point_scope(run, label: str) -> Scope:
    """A scope of a recorded run: one curve per signal, not connected to a controller."""
    scope = Scope("free_run")
    scope.settings.relative_origin = True
    for k, (name, values) in enumerate(run.series.items()):
        curve = Curve(name, Source(method="file", signal=name, controller=None, info={"sweep": label}),
                      colour=PALETTE[k % len(PALETTE)])
        curve.buffer.set_capacity(max(run.t.size, 1))
        curve.buffer.extend(run.t, values)
        scope.add_curve(curve)
    return scope


def _key_label(key: str) -> str:
    """An MCO parameter with its name ("32-60 KPROP"); anything else (a DPL drive parameter) as given."""
    try:
        p = database().get(key)
    except (KeyError, ValueError):
        return key
    return p.label


def _shown(value: float) -> str:
    """As the CSV writes it (sweep.measures.format_value); a missing measure is an empty cell."""
    return "" if math.isnan(value) else format_value(float(value))


def _ticks(values: np.ndarray) -> list[tuple[float, str]]:
    """Cell centres labelled with the parameter's values, at most MAX_TICKS of them."""
    step = max(1, math.ceil(values.size / MAX_TICKS))
    return [(i + 0.5, _shown(float(v))) for i, v in enumerate(values) if i % step == 0]


def open_sweep_results(w) -> SweepView | None:
    """Tools ▸ Sweep Results…: choose a sweep's CSV; the program of the open editor is offered for its runs."""
    editor = w.current_editor()
    path = editor.file_path if editor is not None else None
    folder = str(Path(path).parent) if path is not None else ""      # a sweep is usually beside its program
    chosen = w.prompts.open_path("Sweep Results", folder, "Sweep results (*.csv);;All files (*)")
    if chosen is None:
        return None
    try:
        results = read_results(chosen)
    except (ResultsError, OSError) as exc:
        w.prompts.warn("Sweep Results", str(exc))
        return None
    program = str(path) if path is not None and Path(path).suffix.lower() in (".m", ".dpl") else ""
    view = SweepView(results, chosen, program, parent=w, prompts=w.prompts)
    view.setWindowFlag(Qt.WindowType.Window)
    view.show()
    w._sweeps = [v for v in getattr(w, "_sweeps", []) if v.isVisible()] + [view]
    return view
