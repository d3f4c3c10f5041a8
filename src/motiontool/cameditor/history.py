"""Per-curve undo/redo of the CAM editor, Qt-free [DG L3573-3577]: "a separate undo list is maintained for each
curve"; a batch (several points added at once, Snap on Grid) is one step.  Curves are immutable, so a step is
simply the curve before and after."""

from __future__ import annotations

from dataclasses import dataclass, field

from motiontool.camcurve.model import Curve

MAX_STEPS = 200  # generous; a step is one small immutable Curve


@dataclass
class History:
    undo_stack: list[tuple[str, Curve]] = field(default_factory=list)  # (label, curve before the step)
    redo_stack: list[tuple[str, Curve]] = field(default_factory=list)  # (label, curve after the step)

    def push(self, label: str, before: Curve) -> None:
        self.undo_stack.append((label, before))
        del self.undo_stack[:-MAX_STEPS]
        self.redo_stack.clear()

    @property
    def can_undo(self) -> bool:
        return bool(self.undo_stack)

    @property
    def can_redo(self) -> bool:
        return bool(self.redo_stack)

    def undo(self, current: Curve) -> Curve:
        label, before = self.undo_stack.pop()
        self.redo_stack.append((label, current))
        return before

    def redo(self, current: Curve) -> Curve:
        label, after = self.redo_stack.pop()
        self.undo_stack.append((label, current))
        return after

    def undo_label(self) -> str:
        return self.undo_stack[-1][0] if self.undo_stack else ""

    def redo_label(self) -> str:
        return self.redo_stack[-1][0] if self.redo_stack else ""
