"""The CAM-Editor window [DG L3540-3583, ide-spec 4.4-4.19, 4.78]: toolbar, curve profile diagram, index cards,
display options and the two tables in four resizable panes.  Every edit goes through cameditor.editing; a
refused edit leaves the curve as it was and shows the model's reason in the message line."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from PySide6.QtCore import QEvent, Qt
from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import (
    QComboBox,
    QLabel,
    QLineEdit,
    QMainWindow,
    QSplitter,
    QStyle,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from motiontool.camcurve.layout import element_count
from motiontool.camcurve.model import Curve, CurveError
from motiontool.camcurve.spline import curve_info
from motiontool.cameditor import editing
from motiontool.cameditor.history import History
from motiontool.cameditor.limits import slave_limits
from motiontool.cameditor.transfer import download_config, upload_config
from motiontool.cameditor.ui.apc_panel import ApcPanel
from motiontool.cameditor.ui.cards import (
    CurveDataCard,
    CurveInfoCard,
    DisplayOptions,
    encoder_card,
    sync_marker_card,
    synchronization_card,
)
from motiontool.cameditor.ui.diagram import CurveDiagram, Overlay
from motiontool.cameditor.ui.edits import CurveEdits
from motiontool.cameditor.ui.tables import FixPointTable, StartStopTable
from motiontool.cameditor.ui.trace import TraceOverlay
from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError
from motiontool.fileio import reason, write_error
from motiontool.formats.dat import DatError, read_dat, write_dat
from motiontool.formats.zbc import EXTENSIONS, ArrayEntry, ConfigError, ConfigFile, read_config, write_config
from motiontool.qtjobs.prompts import window_prompts

FILE_FILTER = "CAM configuration (*.zbc *.cnf);;All files (*)"


class Slot:
    """One controller array in the editor (DIM order); curve arrays carry their curve and own undo list."""

    def __init__(self, name: str, values: list[int], curve: Curve | None = None) -> None:
        self.name = name
        self.values = values
        self.curve = curve
        self.history = History()

    def label(self, number: int) -> str:
        return f"{number} {self.curve.name if self.curve else 'Array'}"  # "Array" for non-curves [DG L3563]


class CamEditor(QMainWindow):
    def __init__(self, link_provider: Callable[[], Link | None] | None = None, parent=None,
                 controller: Callable[[], int | None] | None = None, wait=None, prompts=None) -> None:
        super().__init__(parent)
        self.link_provider = link_provider or (lambda: None)
        self.controller = controller or (lambda: None)  # the number of the controller Read/Write talk to
        # wait(window, text, work): the IDE's link_jobs.waiting (the request on a thread while this window paints);
        # an editor without the IDE (a test's embedded link) asks in place
        self.wait = wait or (lambda _window, _text, work: work())
        self._prompts = prompts  # the APOSS window's (issue 27 item 5); None: the Qt dialogs over this window
        self.confirm = True  # ask before discarding changes / overwriting a controller (tests switch it off)
        self.parameters: dict[str, int | float] = {}
        self.slots: list[Slot] = []
        self.current = -1
        self.path: Path | None = None
        self.modified = False
        self.dialog = None  # the open non-blocking dialog, if any
        self.edits = CurveEdits(self)   # undo/redo, mouse, table and card edits
        self.resize(1400, 900)
        self._build_panes()
        self.trace_overlay = TraceOverlay(self)  # measured trace over the curve (decision C14)
        self._build_toolbar()
        self._connect()
        self.refresh()

    # -- layout --------------------------------------------------------------------------------------------------
    def _build_panes(self) -> None:
        self.diagram = CurveDiagram()
        self.curve_data = CurveDataCard()
        self.curve_info = CurveInfoCard()
        self.sync_card = synchronization_card()
        self.marker_card = sync_marker_card()
        self.encoder_card = encoder_card()
        self.cards = QTabWidget()
        for card, title in ((self.curve_data, "Curve Data"), (self.curve_info, "Curve Info"),
                            (self.sync_card, "Synchronization"), (self.marker_card, "Sync. Marker"),
                            (self.encoder_card, "Encoder Data")):
            self.cards.addTab(card, title)
        self.options = DisplayOptions()
        self.fix_table = FixPointTable()
        self.pair_table = StartStopTable()
        self.top = QSplitter(Qt.Orientation.Horizontal)
        self.top.addWidget(self.diagram)
        self.top.addWidget(self.cards)
        self.bottom = QSplitter(Qt.Orientation.Horizontal)
        for w in (self.options, self.fix_table, self.pair_table):
            self.bottom.addWidget(w)
        self.main_split = QSplitter(Qt.Orientation.Vertical)
        self.main_split.addWidget(self.top)
        self.main_split.addWidget(self.bottom)
        self.message_line = QLabel()
        self.message_line.setWordWrap(True)
        self.message_line.hide()
        # the second curve kind: APC CAM tables (cameditor/ui/apc_panel.py); the toolbar serves the MCO curves
        self.apc_panel = ApcPanel(curve_provider=self.curve, curve_sink=self._add_converted_curve)
        self.kinds = QTabWidget()
        self.kinds.addTab(self.main_split, "Fix-point curves (MCO)")
        self.kinds.addTab(self.apc_panel, "APC tables (DPL)")
        central = QWidget()
        layout = QVBoxLayout(central)
        layout.setContentsMargins(4, 2, 4, 4)
        layout.addWidget(self.message_line)
        layout.addWidget(self.kinds)
        self.setCentralWidget(central)
        self.reset_splitters()

    def reset_splitters(self) -> None:
        """Default pane sizes [DG L3553, L3572]."""
        self.main_split.setSizes([640, 260])
        self.top.setSizes([930, 470])
        self.bottom.setSizes([420, 560, 420])

    def _action(self, text: str, slot, *, icon=None, shortcut=None, tip: str = "") -> QAction:
        action = QAction(text, self)
        if icon is not None:
            action.setIcon(self.style().standardIcon(icon))
        if shortcut:
            action.setShortcut(QKeySequence(shortcut))
        action.setToolTip(tip or text)
        action.triggered.connect(lambda *_: slot())
        return action

    def _build_toolbar(self) -> None:
        sp = QStyle.StandardPixmap
        self.actions_by_name = {
            "new": self._action("New", self.new_file, icon=sp.SP_FileIcon, shortcut="Ctrl+N"),
            "open": self._action("Open", self.open_dialog, icon=sp.SP_DialogOpenButton, shortcut="Ctrl+O"),
            "save": self._action("Save", self.save, icon=sp.SP_DialogSaveButton, shortcut="Ctrl+S"),
            "save_as": self._action("Save As", self.save_as_dialog),
            "zoom_reset": self._action("Zoom Reset", self.zoom_reset, tip="Show the whole curve"),
            "zoom_in": self._action("Zoom +", lambda: self.zoom(0.5), tip="Zoom In ×2 (central part)"),
            "zoom_out": self._action("Zoom −", lambda: self.zoom(2.0), tip="Zoom Out ×2"),
            "reset_splitters": self._action("Splitters", self.reset_splitters, tip="Reset splitters"),
            "undo": self._action("Undo", self.edits.undo, icon=sp.SP_ArrowBack, shortcut="Ctrl+Z"),
            "redo": self._action("Redo", self.edits.redo, icon=sp.SP_ArrowForward, shortcut="Ctrl+Y"),
            "snap_all": self._action("Snap all", self.edits.snap_all, tip="Snap all Fix points and Start Stop points "
                                                                          "on the interpolation grid"),
            # arrows as the IDE's download: down to the controller (Write), up from it (Read)
            "read": self._action("Read from controller", self.read_from_controller, icon=sp.SP_ArrowUp,
                                 tip="Read from controller: replaces all parameters and arrays"),
            "write": self._action("Write to controller", self.write_to_controller, icon=sp.SP_ArrowDown,
                                  tip="Write to controller: parameters and arrays"),
            "import": self._action("Import", self.import_dialog, tip="Import a .dat curve (replaces the selected "
                                                                     "curve)"),
            "export": self._action("Export", self.export_dialog, tip="Export the selected curve as .dat"),
            "trace": self._action("Trace…", self.trace_overlay.load_dialog,
                                  tip="Overlay a measured trace (motiontool run --trace CSV or oscilloscope CSV "
                                      "export): slave over master, modulo the master cycle"),
            "clear_trace": self._action("Clear trace", self.trace_overlay.clear, tip="Remove the measured trace"),
            "add": self._action("Add CAM array", self.add_array_dialog),
            "delete": self._action("Delete array", self.delete_array, icon=sp.SP_TrashIcon),
        }
        self.array_combo = QComboBox()
        self.array_combo.setMinimumContentsLength(18)
        self.length_field = QLineEdit()
        self.length_field.setReadOnly(True)
        self.length_field.setMaximumWidth(60)
        self.length_field.setToolTip("Minimum array length: the DIM size the program needs")
        # two rows: with Read/Write named, one row no longer fits 1400 px and hid Add/Delete array behind »
        rows = ((("new", "open", "save", "save_as"), None, ("zoom_reset", "zoom_in", "zoom_out", "reset_splitters"),
                 ("undo", "redo", "snap_all")),
                (("read", "write", "import", "export"), ("trace", "clear_trace"), ("add", "delete")))
        for number, groups in enumerate(rows):
            if number:
                self.addToolBarBreak()
            bar = self.addToolBar("CAM-Editor" if not number else "CAM-Editor transfer")
            bar.setObjectName("cam_toolbar" if not number else "cam_toolbar_2")
            self.kinds.currentChanged.connect(lambda index, *, b=bar: b.setVisible(index == 0))  # MCO curves' toolbar
            bar.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonIconOnly)  # text where there is no icon
            for group in groups:
                if group is None:
                    bar.addWidget(QLabel(" Array: "))
                    bar.addWidget(self.array_combo)
                    bar.addWidget(QLabel(" Length: "))
                    bar.addWidget(self.length_field)
                else:
                    for name in group:
                        bar.addAction(self.actions_by_name[name])
                bar.addSeparator()
        for name in ("read", "write"):  # icon-only they were taken for each other (issue 23 item 10)
            bar.widgetForAction(self.actions_by_name[name]).setToolButtonStyle(
                Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        self.name_controller()

    def name_controller(self) -> None:
        """"Read from controller N" / "Write to controller N": the controller the buttons talk to, as now."""
        number = self.controller() if self.link_provider() is not None else None
        suffix = f" {number}" if number is not None else ""
        self.actions_by_name["read"].setText(f"Read from controller{suffix}")
        self.actions_by_name["write"].setText(f"Write to controller{suffix}")

    def changeEvent(self, event) -> None:  # noqa: N802 - Qt override
        super().changeEvent(event)
        if event.type() == QEvent.Type.ActivationChange and self.isActiveWindow():
            self.name_controller()  # Select Controller may have chosen another one meanwhile

    def _connect(self) -> None:
        self.array_combo.activated.connect(self.select_array)
        box, edits = self.diagram.box, self.edits
        box.point_hovered.connect(edits.hovered)
        box.point_dragged.connect(edits.dragged)
        box.double_clicked.connect(edits.double_clicked)
        box.context_requested.connect(edits.menu_requested)
        box.user_zoomed.connect(lambda: self.options.boxes["auto_scale"].setChecked(False))
        self.options.changed.connect(lambda: self.redraw())
        self.cards.currentChanged.connect(lambda _i: edits.show_follow())
        self.fix_table.model.edit_requested.connect(edits.fix_point_edited, Qt.ConnectionType.QueuedConnection)
        self.fix_table.view.delete_requested.connect(lambda row: edits.edit("Delete point", editing.delete_point, row))
        self.fix_table.add_clicked.connect(edits.add_points_dialog)
        self.pair_table.add_clicked.connect(edits.add_pairs_dialog)
        self.pair_table.edit_requested.connect(edits.edit_pair_dialog)
        self.pair_table.view.delete_requested.connect(lambda row: edits.edit("Delete pair", editing.delete_pair,
                                                                              row + 1))
        self.pair_table.pair_selected.connect(lambda _k: self.redraw())
        self.curve_data.field_edited.connect(edits.curve_field_edited)
        self.curve_data.set_length_clicked.connect(edits.set_length_dialog)
        self.curve_data.set_gradients_clicked.connect(edits.set_gradients_dialog)
        self.curve_info.cycles_edited.connect(lambda text: edits.curve_field_edited("cycles_per_min", text))
        for card in (self.sync_card, self.marker_card, self.encoder_card):
            card.parameter_edited.connect(edits.parameter_edited)

    # -- drawing ----------------------------------------------------------------------------------------------------
    def overlay(self) -> Overlay:
        """What the diagram shows besides the selected curve (Display Options, selected pair, limits, markers)."""
        return self.options.overlay(self.curve(), self.parameters, self.pair_table.selected_pair())

    def redraw(self, *, zoom: bool = False) -> None:
        curve = self.curve()
        self.diagram.box.accuracy = self.options.accuracy.value()
        if curve is None:
            self.diagram.clear_curve()
        else:
            self.diagram.show_curve(curve, self.overlay())
            self.curve_info.show_info(curve, curve_info(curve), slave_limits(curve, self.parameters))
            if zoom or self.options["auto_scale"]:
                self.diagram.zoom_reset()
        self._update_undo()
        self.setWindowTitle(self.title())
        self.trace_overlay.show(curve)  # re-wrapped onto the shown curve's master cycle

    def zoom_reset(self) -> None:
        """Zoom Reset: the whole curve; restores both zoom and pan [DG L3569, L3626]."""
        self.diagram.zoom_reset()

    def zoom(self, factor: float) -> None:
        self.options.boxes["auto_scale"].setChecked(False)
        self.diagram.zoom(factor)

    def show_dialog(self, dialog) -> None:
        """Dialogs are opened non-blocking (window-modal); ``self.dialog`` is the open one."""
        self.dialog = dialog
        dialog.finished.connect(lambda _r: setattr(self, "dialog", None))
        dialog.open()

    # -- state -----------------------------------------------------------------------------------------------------
    def slot(self) -> Slot | None:
        return self.slots[self.current] if 0 <= self.current < len(self.slots) else None

    def curve(self) -> Curve | None:
        slot = self.slot()
        return slot.curve if slot else None

    def message(self, text: str, *, error: bool = True) -> None:
        """The message line: a refused edit's reason (red) or a notice; nothing the user had is lost."""
        self.message_line.setText(text)
        self.message_line.setStyleSheet("background: #ffe4e4; color: #a00000; padding: 3px" if error
                                        else "background: #fff6d5; color: #5a4500; padding: 3px")
        self.message_line.setVisible(bool(text))
        if text:
            self.statusBar().showMessage(text, 8000)

    def title(self) -> str:
        """The curve name, its array number and element count (the DIM size) [DG L1467, ide-spec 4.10]."""
        name = self.path.name if self.path else "Untitled"
        text = f"CAM-Editor - {name}{' *' if self.modified else ''}"
        curve = self.curve()
        if curve is not None:
            text += f" - {curve.name} [array {self.current}, {element_count(curve)} elements]"
        return text

    def refresh(self, *, zoom: bool = False) -> None:
        """Show the current slot everywhere."""
        self.array_combo.clear()
        for number, slot in enumerate(self.slots):
            self.array_combo.addItem(slot.label(number))
        self.array_combo.setCurrentIndex(self.current)
        curve = self.curve()
        slot = self.slot()
        self.length_field.setText(str(element_count(curve)) if curve else (str(len(slot.values)) if slot else ""))
        for card in (self.curve_data, self.curve_info):
            card.setEnabled(curve is not None)
        for w in (self.fix_table, self.pair_table):
            w.setEnabled(curve is not None)
        self.fix_table.model.set_curve(curve)
        self.pair_table.set_curve(curve)
        if curve is not None:
            self.curve_data.show_curve(curve)
        for card in (self.sync_card, self.marker_card, self.encoder_card):
            card.show_parameters(self.parameters)
        for name in ("export", "import", "snap_all"):
            self.actions_by_name[name].setEnabled(curve is not None)
        self.actions_by_name["delete"].setEnabled(slot is not None)
        self.redraw(zoom=zoom)

    def _update_undo(self) -> None:
        slot = self.slot()
        history = slot.history if slot and slot.curve else None
        for name, can, label in (("undo", history and history.can_undo, history and history.undo_label()),
                                 ("redo", history and history.can_redo, history and history.redo_label())):
            action = self.actions_by_name[name]
            action.setEnabled(bool(can))  # greyed when there is nothing to undo [DG L3575]
            action.setToolTip(f"{action.text()} {label}" if label else action.text())

    # -- arrays ------------------------------------------------------------------------------------------------------
    def select_array(self, index: int) -> None:
        self.current = index
        self.message("")
        self.refresh(zoom=True)

    def add_array_dialog(self) -> None:
        from motiontool.cameditor.ui.dialogs import AddCurveDialog

        taken = {s.curve.name for s in self.slots if s.curve}
        name = next(f"curve{n}" for n in range(1, 1000) if f"curve{n}" not in taken)
        dialog = AddCurveDialog(self, name)
        dialog.accepted.connect(lambda: self.add_array(dialog.name.text(), dialog.master_length.value(),
                                                       dialog.intervals.value(), dialog.interpolation.isChecked()))
        self.show_dialog(dialog)

    def add_array(self, name: str, master_length: float, intervals: int, interpolation: bool) -> bool:
        """Append a curve array after the last array and select it [DG L3582]."""
        if any(s.curve and s.curve.name == name or s.name == name for s in self.slots):
            self.message(f"Add CAM array: an array named {name!r} exists already")
            return False
        try:
            curve = editing.new_curve(name, master_length, intervals, interpolation)
        except CurveError as exc:
            self.message(f"Add CAM array: {exc}")
            return False
        self.slots.append(Slot(name, [], curve))
        self.current = len(self.slots) - 1
        self.set_modified()
        self.refresh(zoom=True)
        return True

    def _add_converted_curve(self, curve: Curve) -> None:
        """APC table → MCO curve: a new curve array (a free name), shown in the Fix-point curves tab."""
        taken = {s.curve.name for s in self.slots if s.curve} | {s.name for s in self.slots}
        name = next(n for n in (curve.name, *(f"{curve.name[:13]}{k}" for k in range(2, 1000))) if n not in taken)
        self.slots.append(Slot(name, [], replace(curve, name=name)))
        self.current = len(self.slots) - 1
        self.set_modified()
        self.kinds.setCurrentWidget(self.main_split)
        self.refresh(zoom=True)

    def delete_array(self) -> None:
        if self.slot() is None:
            return
        del self.slots[self.current]
        self.current = min(self.current, len(self.slots) - 1)
        self.set_modified()
        self.refresh(zoom=True)

    # -- files -----------------------------------------------------------------------------------------------------
    @property
    def prompts(self):
        return window_prompts(self, self._prompts)

    def _discard_ok(self) -> bool:
        if not self.modified or not self.confirm:
            return True
        return self.prompts.confirm("CAM-Editor", "Discard the changes?")

    def set_modified(self, *, modified: bool = True) -> None:
        self.modified = modified
        self.setWindowTitle(self.title())

    def load_config(self, config: ConfigFile, path: Path | None) -> None:
        self.parameters = dict(config.parameters)
        self.slots = []
        for entry in config.arrays:
            curve = config.curve(entry.curve) if entry.curve else None
            self.slots.append(Slot(entry.name, list(entry.values), curve))
        self.current = next((i for i, s in enumerate(self.slots) if s.curve), 0 if self.slots else -1)
        self.path = path
        self.set_modified(modified=False)
        self.message("")
        self.refresh(zoom=True)

    def new_file(self) -> None:
        """File → New / Create empty file: no curves [ide-spec 4.6]."""
        if self._discard_ok():
            self.load_config(ConfigFile(), None)

    def open_dialog(self) -> None:
        if not self._discard_ok():
            return
        path = self.prompts.open_path("Open CAM configuration", "", FILE_FILTER)
        if path is not None:
            self.open_file(path)

    def open_file(self, path: Path) -> bool:
        try:
            config = read_config(path)
        except ConfigError as exc:
            self.message(f"Cannot open: {exc}")
            return False
        self.load_config(config, Path(path))
        return True

    def config(self) -> ConfigFile:
        """The editor's contents as a configuration; raises CurveError naming a curve the array cannot hold."""
        config = ConfigFile(parameters=dict(self.parameters))
        for slot in self.slots:
            if slot.curve is None:
                config.arrays.append(ArrayEntry(slot.name, list(slot.values)))
                continue
            try:
                config.add_curve(slot.curve)
            except CurveError as exc:
                raise CurveError(exc.field, f"curve {slot.curve.name}: {exc.message}", exc.point) from None
        return config

    def save(self) -> bool:
        return self.save_file(self.path) if self.path else self.save_as_dialog()

    def save_as_dialog(self) -> bool:
        path = self.prompts.save_path("Save CAM configuration", str(self.path or ""), FILE_FILTER)
        return self.save_file(path) if path is not None else False

    def save_file(self, path: Path) -> bool:
        """Save atomically as .zbc or .cnf [DG L3483-3485]; nothing is written when a curve cannot be stored."""
        path = Path(path)
        if path.suffix.lower() not in EXTENSIONS:
            path = path.with_suffix(".zbc")
        try:
            write_config(path, self.config())
        except OSError as exc:  # the curves stay in the editor, still marked changed (decisions R7)
            self._write_failed("Save", path, exc, "The curves are still in the editor: save them somewhere else.")
            return False
        except (CurveError, ConfigError) as exc:
            self.message(f"Not saved: {exc}")
            return False
        self.path = path
        self.set_modified(modified=False)
        self.message(f"Saved {path.name}", error=False)
        return True

    def read_from_controller(self) -> bool:
        """Replace all parameters and arrays by the controller's [DG L3579]."""
        link = self.link_provider()
        if link is None:
            self.message("Read from controller: no controller is connected (Settings → Interface)")
            return False
        if not self._discard_ok():
            return False
        try:
            config = self.wait(self, f"{self._controller_name()}: reading parameters and arrays …",
                               lambda: upload_config(link))
        except (LinkError, ConfigError) as exc:
            self.message(f"Read from controller failed: {exc}")
            return False
        self.load_config(config, self.path)
        self.set_modified(modified=True)
        return True

    def _controller_name(self) -> str:
        cid = self.controller()
        return f"Controller {cid}" if cid else "The controller"

    def write_to_controller(self) -> bool:
        """Download parameters and arrays; they overwrite the controller's [ide-spec 4.3, DG L3487]."""
        link = self.link_provider()
        if link is None:
            self.message("Write to controller: no controller is connected (Settings → Interface)")
            return False
        if self.confirm and not self.prompts.confirm("CAM-Editor", "Write all parameters and arrays of this file "
                                                     "to the controller? Its own parameters and arrays are "
                                                     "overwritten."):
            return False
        try:
            config = self.config()
            self.wait(self, f"{self._controller_name()}: writing parameters and arrays …",
                      lambda: download_config(link, config))
        except (CurveError, ConfigError, LinkError) as exc:
            self.message(f"Write to controller failed: {exc}")
            return False
        self.message("Parameters and arrays written to the controller", error=False)
        return True

    def import_dialog(self) -> None:
        path = self.prompts.open_path("Import curve", "", "CAM export (*.dat);;All files (*)")
        if path is not None:
            self.import_dat(path)

    def import_dat(self, path: Path) -> bool:
        """Replace the selected curve by an exported one; anything else is refused [DG L3580]."""
        if self.curve() is None:
            self.message("Import: select a curve first")
            return False
        try:
            curve = read_dat(path).to_curve()
        except DatError as exc:  # names the file and line
            self.message(f"Import refused: {exc}")
            return False
        except OSError as exc:
            self.message(f"Import refused: {path.name}: {exc.strerror or exc}")
            return False
        return self.edits.set_curve(curve, "Import")

    def export_dialog(self) -> None:
        curve = self.curve()
        if curve is None:
            return
        path = self.prompts.save_path("Export curve", f"{curve.name}.dat", "CAM export (*.dat)")
        if path is not None:
            self.export_dat(path)

    def export_dat(self, path: Path) -> bool:
        try:
            write_dat(path, self.curve())
        except OSError as exc:
            self._write_failed("Export", path, exc, "The curve is unchanged.")
            return False
        except CurveError as exc:
            self.message(f"Export failed: {exc}")
            return False
        self.message(f"Exported {Path(path).name}", error=False)
        return True

    def _write_failed(self, title: str, path: Path, exc: OSError, kept: str) -> None:
        self.message(f"{title} failed: {write_error(path, exc)}")
        if self.confirm:
            self.prompts.warn(f"CAM-Editor — {title}", f"Cannot write {path}:\n{reason(exc)}.", detail=kept,
                              critical=True)

    def closeEvent(self, event) -> None:  # noqa: N802 - Qt override
        if self._discard_ok():
            event.accept()
        else:
            event.ignore()
