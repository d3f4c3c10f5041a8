"""Curve editing in the CAM-Editor window: undo/redo per curve, mouse editing in the diagram, table and card edits
[DG L3573-3577, L3636-3682, L3960-4070].  A part of CamEditor (window.py), ``editor.edits``: it owns a drag's state and
reaches the editor's widgets and curves through ``editor``."""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QMenu

from motiontool.camcurve.model import LAW_TYPES, Curve, CurveError, CurveType
from motiontool.camcurve.spline import curve_info, profile
from motiontool.cameditor import editing
from motiontool.cameditor.limits import slave_limits
from motiontool.paramdb import ParameterError, database

if TYPE_CHECKING:
    from motiontool.cameditor.ui.window import CamEditor

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


class CurveEdits:
    """Undo/redo and the edits made with the mouse, in the tables and on the cards, of one CamEditor."""

    def __init__(self, editor: CamEditor) -> None:
        self.editor = editor
        self.context_menu: QMenu | None = None   # the last popup on the diagram
        self._drag_start: Curve | None = None
        self._drag_overlay = None  # ((master length, slave length), Overlay) during a drag
        self._follow: tuple[Curve, int, bool] | None = None  # a drag's state the table / Curve Info lag behind
        self._follow_next = 0.0  # monotonic time of their next update
        self._follow_timer = QTimer(editor)   # the editor's child: it goes with the window
        self._follow_timer.setSingleShot(True)
        self._follow_timer.timeout.connect(self.show_follow)

    # -- applying edits -------------------------------------------------------------------------------------------
    def set_curve(self, curve: Curve, label: str) -> bool:
        """Make ``curve`` the selected slot's curve as one undo step."""
        slot = self.editor.slot()
        if slot is None or slot.curve is None:
            return False
        if curve == slot.curve:
            return True
        slot.history.push(label, slot.curve)
        slot.curve = curve
        slot.name = curve.name
        self.editor.message("")
        self.editor.set_modified()
        self.editor.refresh()
        return True

    def edit(self, label: str, operation, *args, **kwargs) -> bool:
        """Run an editing operation on the selected curve; a CurveError is shown and nothing changes."""
        curve = self.editor.curve()
        if curve is None:
            return False
        try:
            new = operation(curve, *args, **kwargs)
        except CurveError as exc:
            self.editor.message(f"{label}: {exc.message if exc.field in ('fix_points', 'master_length') else exc}")
            return False
        return self.set_curve(new, label)

    def undo(self) -> None:
        slot = self.editor.slot()
        if slot and slot.curve and slot.history.can_undo:
            slot.curve = slot.history.undo(slot.curve)
            slot.name = slot.curve.name
            self.editor.set_modified()
            self.editor.refresh()

    def redo(self) -> None:
        slot = self.editor.slot()
        if slot and slot.curve and slot.history.can_redo:
            slot.curve = slot.history.redo(slot.curve)
            slot.name = slot.curve.name
            self.editor.set_modified()
            self.editor.refresh()

    def snap_all(self) -> None:
        self.edit("Snap on Grid", editing.snap_all)

    # -- mouse ---------------------------------------------------------------------------------------------------------
    def hovered(self, index: int) -> None:
        self.editor.diagram.set_hover(index)
        self.editor.fix_table.highlight(index)

    def dragged(self, index: int, master: float, slave: float, finished: bool) -> None:
        """Drag a fix point: the table row follows, the curve and Curve Info too with Continuous Recalc, else on
        release; Snap on Grid makes it jump to grid lines; one undo step per drag [DG L3642-3650]."""
        slot = self.editor.slot()
        if slot is None or slot.curve is None:
            return
        if self._drag_start is None:
            self._drag_start = slot.curve
        start = self._drag_start
        try:  # the array stores longs: a dragged point lands on whole units (issue 16)
            moved = editing.move_point(start, index, round(master), round(slave),
                                       snap_on_grid=self.editor.options["snap_on_grid"], clamp=True)
        except CurveError as exc:
            moved = slot.curve
            self.editor.message(f"Move point: {exc.message}")
        if finished:
            self._drag_start = None
            slot.curve = start
            self._follow = self._drag_overlay = None  # the release shows the final curve everywhere
            if moved == start:  # back where it started: no undo step; show the curve as it is again
                self.editor.redraw()
                self.editor.fix_table.model.update_row(index, start)
            else:
                self.set_curve(moved, "Move point")
            return
        p = moved.fix_points[index]
        if self.editor.options["continuous_recalc"]:
            shown, slot.curve = slot.curve, moved
            if _same_drag_state(shown, moved, index):
                return  # the mouse moved within the same position (or the move was refused): nothing changes
            # a drag's curve is asked about only now: built once, without hashing its points into the shared
            # cache, taking the segment kinds over from the shown curve (only point ``index`` moved)
            profile(moved, cache=False, moved_from=(profile(shown), index))
            lengths = (moved.master_length, moved.slave_length)  # what the overlay depends on besides the options
            if self._drag_overlay is None or self._drag_overlay[0] != lengths:
                self._drag_overlay = (lengths, self.editor.overlay())  # options cannot change mid-drag
            self.editor.diagram.show_curve(moved, self._drag_overlay[1], dragging=True)
        else:
            self.editor.diagram.move_marker(index, p.master, p.slave)
        self._drag_follow(moved, index, info=self.editor.options["continuous_recalc"])

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
        self.editor.fix_table.model.update_row(row, curve)
        if info and self.editor.cards.currentWidget() is self.editor.curve_info and curve is self.editor.curve():
            self.editor.curve_info.show_info(curve, curve_info(curve), slave_limits(curve, self.editor.parameters))
            self._follow = None
        elif not info:
            self._follow = None
        self._follow_next = time.monotonic() + FOLLOW_INTERVAL

    def double_clicked(self, master: float, slave: float) -> None:
        self.edit("Add point", editing.add_points, [(master, round(slave))],
                  snap_on_grid=self.editor.options["snap_on_grid"])

    def menu_requested(self, index: int, master: float, slave: float, screen_pos) -> None:
        """Popup on a fix point (change type, Delete, Snap on Grid) or on empty space (Insert on Curve / Insert
        Here) [DG L3656-3682]."""
        if self.editor.curve() is None:
            return
        menu = QMenu(self.editor)
        snap = self.editor.options["snap_on_grid"]
        if index >= 0:
            current = self.editor.curve().fix_points[index].type
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
    def fix_point_edited(self, row: int, field: str, value) -> None:
        curve = self.editor.curve()
        if curve is None or not 0 <= row < len(curve.fix_points):
            return
        if field == "type":
            self.edit("Change type", editing.change_type, row, str(value))
            return
        try:
            number = parse_number(str(value))
        except ValueError:
            self.editor.message(f"Fix point {row + 1}: {value!r} is not a number")
            self.editor.refresh()
            return
        p = curve.fix_points[row]
        master, slave = (number, p.slave) if field == "master" else (p.master, number)
        if not self.edit("Edit point", editing.typed(editing.move_point), row, master, slave,
                         snap_on_grid=self.editor.options["snap_on_grid"]):
            self.editor.refresh()

    def add_points_dialog(self) -> None:
        from motiontool.cameditor.ui.dialogs import PairsDialog

        dialog = PairsDialog(self.editor, "Add Fix points", "master", "slave")
        dialog.accepted.connect(lambda: self.edit("Add points", editing.typed(editing.add_points), dialog.pairs,
                                                  snap_on_grid=self.editor.options["snap_on_grid"]))
        self.editor.show_dialog(dialog)

    def add_pairs_dialog(self) -> None:
        from motiontool.cameditor.ui.dialogs import PairsDialog

        dialog = PairsDialog(self.editor, "Add Start Stop points", "start", "stop")
        dialog.accepted.connect(lambda: self.edit("Add pairs", editing.typed(editing.add_pairs),
                                                  self._snapped_pairs(dialog.pairs)))
        self.editor.show_dialog(dialog)

    def _snapped_pairs(self, pairs: list[tuple[float, float]]) -> list[tuple[float, float]]:
        curve = self.editor.curve()
        if curve is None or not self.editor.options["snap_on_grid"]:
            return pairs
        return [(editing.grid_snap(curve, a), editing.grid_snap(curve, b)) for a, b in pairs]

    def edit_pair_dialog(self, k: int) -> None:
        from motiontool.cameditor.ui.dialogs import PairDialog

        curve = self.editor.curve()
        if curve is None or not 0 < k < len(curve.start_stop_pairs):
            return
        pair = curve.start_stop_pairs[k]
        dialog = PairDialog(self.editor, k, pair.start, pair.stop)
        dialog.accepted.connect(lambda: self.edit("Edit pair", editing.typed(editing.set_pair), k,
                                                  *self._snapped_pairs([(dialog.start.value(),
                                                                         dialog.stop.value())])[0]))
        self.editor.show_dialog(dialog)

    # -- cards --------------------------------------------------------------------------------------------------------
    def curve_field_edited(self, field: str, text: str) -> None:
        try:
            if field in _TEXT_FIELDS:
                value = text.strip()
            elif field in _INT_FIELDS:
                value = CurveType(int(text))
            else:
                value = parse_number(text)
        except ValueError:
            self.editor.message(f"{field.replace('_', ' ')}: {text!r} is not a number")
            self.editor.refresh()
            return
        if field == "name" and any(s is not self.editor.slot() and s.name == value for s in self.editor.slots):
            self.editor.message(f"Name of Curve: an array named {value!r} exists already")
            self.editor.refresh()
            return
        if not self.edit("Curve Data", editing.replace, **{field: value}):
            self.editor.refresh()

    def set_length_dialog(self) -> None:
        from motiontool.cameditor.ui.dialogs import SetLengthDialog

        curve = self.editor.curve()
        dialog = SetLengthDialog(self.editor, curve.master_length, curve.intervals, curve.interpolation)
        dialog.accepted.connect(lambda: self.edit("Set length", editing.set_length, dialog.master_length.value(),
                                                  dialog.intervals.value(), dialog.interpolation.isChecked()))
        self.editor.show_dialog(dialog)

    def set_gradients_dialog(self) -> None:
        from motiontool.cameditor.ui.dialogs import GradientDialog

        curve = self.editor.curve()
        dialog = GradientDialog(self.editor, curve.start_gradient, curve.end_gradient)
        dialog.accepted.connect(lambda: self.set_gradients(dialog.start.value(), dialog.end.value()))
        self.editor.show_dialog(dialog)

    def set_gradients(self, start: float, end: float) -> bool:
        """The editor "will warn the user if the start and end gradients do not match" [DG L3725]."""
        if not self.edit("Set gradients", editing.replace, start_gradient=start, end_gradient=end):
            return False
        if start != end:
            self.editor.message(f"Start gradient {start:g} and end gradient {end:g} differ: the slave velocity jumps "
                                "when the curve restarts", error=False)
        return True

    def parameter_edited(self, number: str, text: str) -> None:
        try:
            value = database().validate(number, parse_number(text))
        except (ValueError, ParameterError) as exc:
            self.editor.message(f"Parameter {database().get(number).label}: {exc}")
            self.editor.refresh()
            return
        self.editor.parameters[number] = value
        self.editor.message("")
        self.editor.set_modified()
        self.editor.refresh()
