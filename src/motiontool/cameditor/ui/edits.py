"""Curve editing in the CAM-Editor window: undo/redo per curve, mouse editing in the diagram, table and card edits
[DG L3573-3577, L3636-3682, L3960-4070].  A mixin of CamEditor (window.py) so each file stays readable."""

from __future__ import annotations

import math
import time

from PySide6.QtWidgets import QMenu

from motiontool.camcurve.model import LAW_TYPES, Curve, CurveError, CurveType
from motiontool.camcurve.spline import curve_info, profile
from motiontool.cameditor import editing
from motiontool.cameditor.limits import marker_detection, parameter, slave_limits
from motiontool.cameditor.ui.diagram import Overlay
from motiontool.paramdb import ParameterError, database

FOLLOW_INTERVAL = 0.05  # s: the table row and Curve Info follow a drag at up to 20 updates per second
_TEXT_FIELDS = {"name"}
_INT_FIELDS = {"curve_type"}


def parse_number(text: str) -> int | float:
    """A typed number: int when integral (the array stores longs); raises ValueError."""
    value = float(text.strip().replace(",", "."))
    if not math.isfinite(value):
        raise ValueError(f"{text!r} is not a finite number")
    return int(value) if value.is_integer() else value


def _same_drag_state(shown: Curve, moved: Curve, index: int) -> bool:
    """A drag's curves all come from the curve at the drag start with only point ``index`` (and, for the last
    point, the master length) changed, so comparing those tells whether the shown curve is already ``moved``."""
    return shown is moved or (len(shown.fix_points) == len(moved.fix_points) and shown.fix_points[index] ==
                              moved.fix_points[index] and shown.master_length == moved.master_length
                              and shown.intervals == moved.intervals)


class EditsMixin:
    # -- applying edits -------------------------------------------------------------------------------------------
    def set_curve(self, curve: Curve, label: str) -> bool:
        """Make ``curve`` the selected slot's curve as one undo step."""
        slot = self.slot()
        if slot is None or slot.curve is None:
            return False
        if curve == slot.curve:
            return True
        slot.history.push(label, slot.curve)
        slot.curve = curve
        slot.name = curve.name
        self.message("")
        self._set_modified()
        self.refresh()
        return True

    def edit(self, label: str, operation, *args, **kwargs) -> bool:
        """Run an editing operation on the selected curve; a CurveError is shown and nothing changes."""
        curve = self.curve()
        if curve is None:
            return False
        try:
            new = operation(curve, *args, **kwargs)
        except CurveError as exc:
            self.message(f"{label}: {exc.message if exc.field in ('fix_points', 'master_length') else exc}")
            return False
        return self.set_curve(new, label)

    def undo(self) -> None:
        slot = self.slot()
        if slot and slot.curve and slot.history.can_undo:
            slot.curve = slot.history.undo(slot.curve)
            slot.name = slot.curve.name
            self._set_modified()
            self.refresh()

    def redo(self) -> None:
        slot = self.slot()
        if slot and slot.curve and slot.history.can_redo:
            slot.curve = slot.history.redo(slot.curve)
            slot.name = slot.curve.name
            self._set_modified()
            self.refresh()

    def snap_all(self) -> None:
        self.edit("Snap on Grid", editing.snap_all)

    # -- drawing ----------------------------------------------------------------------------------------------------
    def overlay(self) -> Overlay:
        o = self.options
        ov = Overlay(**{k: o[k] for k in ("velocity", "velocity_limit", "acceleration", "acceleration_limit", "jerk",
                                          "slave_stop", "start_stop", "engage", "disengage", "master_marker",
                                          "slave_marker", "correction")})
        ov.selected_pair = self.pair_table.selected_pair()
        curve = self.curve()
        if curve is not None:
            limits = slave_limits(curve, self.parameters)
            ov.velocity_limit_value, ov.acceleration_limit_value = limits.velocity, limits.acceleration
            p = self.parameters
            ov.master_marker_at = marker_detection(curve.master_marker_pos, parameter(p, "33-17"), curve.master_length)
            ov.master_tolerance = parameter(p, "33-21")
            # the slave marker is a slave position; reduced over the slave length when the curve has one
            s_len = abs(curve.slave_length)
            distance = parameter(p, "33-18")
            ov.slave_marker_at = (marker_detection(curve.slave_marker_pos, distance, s_len) if s_len
                                  else curve.slave_marker_pos - distance)
            ov.slave_tolerance = parameter(p, "33-22")
        return ov

    def _redraw(self, *, zoom: bool = False) -> None:
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

    def _options_changed(self) -> None:
        self._redraw()

    def zoom_reset(self) -> None:
        """Zoom Reset: the whole curve; restores both zoom and pan [DG L3569, L3626]."""
        self.diagram.zoom_reset()

    def zoom(self, factor: float) -> None:
        self.options.boxes["auto_scale"].setChecked(False)
        self.diagram.zoom(factor)

    # -- mouse ---------------------------------------------------------------------------------------------------------
    def _hovered(self, index: int) -> None:
        self.diagram.set_hover(index)
        self.fix_table.highlight(index)

    def _dragged(self, index: int, master: float, slave: float, finished: bool) -> None:
        """Drag a fix point: the table row follows, the curve and Curve Info too with Continuous Recalc, else on
        release; Snap on Grid makes it jump to grid lines; one undo step per drag [DG L3642-3650]."""
        slot = self.slot()
        if slot is None or slot.curve is None:
            return
        if self._drag_start is None:
            self._drag_start = slot.curve
        start = self._drag_start
        try:  # the array stores longs: a dragged point lands on whole units (issue 16)
            moved = editing.move_point(start, index, round(master), round(slave),
                                       snap_on_grid=self.options["snap_on_grid"], clamp=True)
        except CurveError as exc:
            moved = slot.curve
            self.message(f"Move point: {exc.message}")
        if finished:
            self._drag_start = None
            slot.curve = start
            self._follow = self._drag_overlay = None  # the release shows the final curve everywhere
            if moved == start:  # back where it started: no undo step; show the curve as it is again
                self._redraw()
                self.fix_table.model.update_row(index, start)
            else:
                self.set_curve(moved, "Move point")
            return
        p = moved.fix_points[index]
        if self.options["continuous_recalc"]:
            shown, slot.curve = slot.curve, moved
            if _same_drag_state(shown, moved, index):
                return  # the mouse moved within the same position (or the move was refused): nothing changes
            # a drag's curve is asked about only now: built once, without hashing its points into the shared
            # cache, taking the segment kinds over from the shown curve (only point ``index`` moved)
            profile(moved, cache=False, moved_from=(profile(shown), index))
            lengths = (moved.master_length, moved.slave_length)  # what the overlay depends on besides the options
            if self._drag_overlay is None or self._drag_overlay[0] != lengths:
                self._drag_overlay = (lengths, self.overlay())  # options cannot change mid-drag
            self.diagram.show_curve(moved, self._drag_overlay[1], dragging=True)
        else:
            self.diagram.move_marker(index, p.master, p.slave)
        self._drag_follow(moved, index, info=self.options["continuous_recalc"])

    def _drag_follow(self, curve: Curve, row: int, info: bool) -> None:
        """The dragged point's table row and, with Continuous Recalc, Curve Info follow a drag [DG L3644-3646],
        at up to 1 / FOLLOW_INTERVAL updates per second (the diagram follows every move; the last state of a
        pause follows by timer).  Curve Info is computed only while its card is shown (``show_follow`` catches
        up when it is brought to the front); the release shows the final curve everywhere."""
        self._follow = (curve, row, info)
        wait = self._follow_next - time.monotonic()
        if wait <= 0:
            self.show_follow()
        elif not self._follow_timer.isActive():
            self._follow_timer.start(max(1, math.ceil(wait * 1000)))

    def show_follow(self) -> None:
        """Show a drag's latest state in the table row and Curve Info (see _drag_follow)."""
        if self._follow is None:
            return
        curve, row, info = self._follow
        self.fix_table.model.update_row(row, curve)
        if info and self.cards.currentWidget() is self.curve_info and curve is self.curve():
            self.curve_info.show_info(curve, curve_info(curve), slave_limits(curve, self.parameters))
            self._follow = None
        elif not info:
            self._follow = None
        self._follow_next = time.monotonic() + FOLLOW_INTERVAL

    def _double_clicked(self, master: float, slave: float) -> None:
        self.edit("Add point", editing.add_points, [(master, round(slave))],
                  snap_on_grid=self.options["snap_on_grid"])

    def _context_menu(self, index: int, master: float, slave: float, screen_pos) -> None:
        """Popup on a fix point (change type, Delete, Snap on Grid) or on empty space (Insert on Curve / Insert
        Here) [DG L3656-3682]."""
        if self.curve() is None:
            return
        menu = QMenu(self)
        snap = self.options["snap_on_grid"]
        if index >= 0:
            current = self.curve().fix_points[index].type
            laws = QMenu("Motion law (VDI 2143)", menu)  # beyond the manual: decision C10
            for code, name in editing.TYPE_NAMES.items():
                action = (laws if code in LAW_TYPES else menu).addAction(name)
                action.setCheckable(True)
                action.setChecked(code == current)
                action.triggered.connect(lambda *_, t=code: self.edit("Change type", editing.change_type,
                                                                            index, t))
            menu.addMenu(laws)
            menu.addSeparator()
            menu.addAction("Delete").triggered.connect(lambda: self.edit("Delete point", editing.delete_point, index))
            menu.addAction("Snap on Grid").triggered.connect(lambda: self.edit("Snap point", editing.snap_point,
                                                                               index))
        else:
            menu.addAction("Insert on Curve").triggered.connect(
                lambda: self.edit("Insert on Curve", editing.insert_on_curve, master, snap_on_grid=snap))
            menu.addAction("Insert Here").triggered.connect(
                lambda: self.edit("Insert Here", editing.add_points, [(master, round(slave))], snap_on_grid=snap))
        self.context_menu = menu
        menu.popup(screen_pos)

    # -- tables -------------------------------------------------------------------------------------------------------
    def _fix_point_edited(self, row: int, field: str, value) -> None:
        curve = self.curve()
        if curve is None or not 0 <= row < len(curve.fix_points):
            return
        if field == "type":
            self.edit("Change type", editing.change_type, row, str(value))
            return
        try:
            number = parse_number(str(value))
        except ValueError:
            self.message(f"Fix point {row + 1}: {value!r} is not a number")
            self.refresh()
            return
        p = curve.fix_points[row]
        master, slave = (number, p.slave) if field == "master" else (p.master, number)
        if not self.edit("Edit point", editing.typed(editing.move_point), row, master, slave,
                         snap_on_grid=self.options["snap_on_grid"]):
            self.refresh()

    def _open(self, dialog) -> None:
        """Dialogs are opened non-blocking (window-modal); ``self.dialog`` is the open one."""
        self.dialog = dialog
        dialog.finished.connect(lambda _r: setattr(self, "dialog", None))
        dialog.open()

    def add_points_dialog(self) -> None:
        from motiontool.cameditor.ui.dialogs import PairsDialog

        dialog = PairsDialog(self, "Add Fix points", "master", "slave")
        dialog.accepted.connect(lambda: self.edit("Add points", editing.typed(editing.add_points), dialog.pairs,
                                                  snap_on_grid=self.options["snap_on_grid"]))
        self._open(dialog)

    def add_pairs_dialog(self) -> None:
        from motiontool.cameditor.ui.dialogs import PairsDialog

        dialog = PairsDialog(self, "Add Start Stop points", "start", "stop")
        dialog.accepted.connect(lambda: self.edit("Add pairs", editing.typed(editing.add_pairs),
                                                  self._snapped_pairs(dialog.pairs)))
        self._open(dialog)

    def _snapped_pairs(self, pairs: list[tuple[float, float]]) -> list[tuple[float, float]]:
        curve = self.curve()
        if curve is None or not self.options["snap_on_grid"]:
            return pairs
        return [(editing.grid_snap(curve, a), editing.grid_snap(curve, b)) for a, b in pairs]

    def edit_pair_dialog(self, k: int) -> None:
        from motiontool.cameditor.ui.dialogs import PairDialog

        curve = self.curve()
        if curve is None or not 0 < k < len(curve.start_stop_pairs):
            return
        pair = curve.start_stop_pairs[k]
        dialog = PairDialog(self, k, pair.start, pair.stop)
        dialog.accepted.connect(lambda: self.edit("Edit pair", editing.typed(editing.set_pair), k,
                                                  *self._snapped_pairs([(dialog.start.value(),
                                                                         dialog.stop.value())])[0]))
        self._open(dialog)

    # -- cards --------------------------------------------------------------------------------------------------------
    def _curve_field_edited(self, field: str, text: str) -> None:
        try:
            if field in _TEXT_FIELDS:
                value = text.strip()
            elif field in _INT_FIELDS:
                value = CurveType(int(text))
            else:
                value = parse_number(text)
        except ValueError:
            self.message(f"{field.replace('_', ' ')}: {text!r} is not a number")
            self.refresh()
            return
        if field == "name" and any(s is not self.slot() and s.name == value for s in self.slots):
            self.message(f"Name of Curve: an array named {value!r} exists already")
            self.refresh()
            return
        if not self.edit("Curve Data", editing.replace, **{field: value}):
            self.refresh()

    def set_length_dialog(self) -> None:
        from motiontool.cameditor.ui.dialogs import SetLengthDialog

        curve = self.curve()
        dialog = SetLengthDialog(self, curve.master_length, curve.intervals, curve.interpolation)
        dialog.accepted.connect(lambda: self.edit("Set length", editing.set_length, dialog.master_length.value(),
                                                  dialog.intervals.value(), dialog.interpolation.isChecked()))
        self._open(dialog)

    def set_gradients_dialog(self) -> None:
        from motiontool.cameditor.ui.dialogs import GradientDialog

        curve = self.curve()
        dialog = GradientDialog(self, curve.start_gradient, curve.end_gradient)
        dialog.accepted.connect(lambda: self.set_gradients(dialog.start.value(), dialog.end.value()))
        self._open(dialog)

    def set_gradients(self, start: float, end: float) -> bool:
        """The editor "will warn the user if the start and end gradients do not match" [DG L3725]."""
        if not self.edit("Set gradients", editing.replace, start_gradient=start, end_gradient=end):
            return False
        if start != end:
            self.message(f"Start gradient {start:g} and end gradient {end:g} differ: the slave velocity jumps when "
                         "the curve restarts", error=False)
        return True

    def _parameter_edited(self, number: str, text: str) -> None:
        try:
            value = database().validate(number, parse_number(text))
        except (ValueError, ParameterError) as exc:
            self.message(f"Parameter {database().get(number).label}: {exc}")
            self.refresh()
            return
        self.parameters[number] = value
        self.message("")
        self._set_modified()
        self.refresh()
