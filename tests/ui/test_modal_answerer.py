"""The modal-dialog answerer the GUI tests rely on (tests/modal.py): it must tell a dialog that stays open from
a series of dialogs that each closed."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QMessageBox

from tests.modal import answering, button_reply

OK = QMessageBox.StandardButton.Ok


def test_many_dialogs_one_after_another_are_each_answered_once(qtbot):
    """Each box is freed before the next is made, so CPython hands the next wrapper the same id(): a count kept
    by id() reported "stayed open after 3 replies" for the fourth box although every box had closed."""
    results = []
    with answering(qtbot, fallback=button_reply(OK)) as answerer:
        for k in range(8):
            box = QMessageBox(QMessageBox.Icon.Information, "Box", f"box {k}", OK)
            results.append(box.exec())
            del box
    assert results == [OK] * 8
    assert len(answerer.seen) == 8


class Stubborn(QMessageBox):
    """A dialog that OK does not close (Cancel does)."""

    def done(self, result: int) -> None:
        if result == QMessageBox.StandardButton.Cancel:
            super().done(result)


def test_a_dialog_that_stays_open_is_reported_and_closed(qtbot):
    box = Stubborn(QMessageBox.Icon.Information, "Stubborn", "press OK", OK | QMessageBox.StandardButton.Cancel)
    with pytest.raises(AssertionError, match="'Stubborn' stayed open after 3 replies"), \
            answering(qtbot, fallback=button_reply(OK)):
        box.open()
        qtbot.waitUntil(lambda: not box.isVisible(), timeout=5000)  # closed by the answerer's Cancel
