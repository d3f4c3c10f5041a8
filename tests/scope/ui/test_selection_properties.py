"""Curve Properties → Source → Byte/bit selection (ide-spec 6.43) in the oscilloscope window, embedded link."""

import pytest

from motiontool.controller.embedded import EmbeddedLink
from motiontool.scope.ui import ScopeWindow, open_scope_file
from motiontool.scope.ui.dialogs import WHOLE_VALUE, AddCurveDialog, PropertiesDialog

GROUP = "Test Group (Free Run)"


@pytest.fixture
def window(qtbot):
    link = EmbeddedLink()
    w = ScopeWindow(link, "free_run", ask=False)
    qtbot.addWidget(w)
    w.show()
    return w, link


def record(w, link, ms=200):
    w.run.start()
    for _ in range(ms // 50):
        link.advance(50)
        w.run.tick()
    w.run.stop()


def test_changing_the_selection_renames_clears_and_records_the_new_field(window, tmp_path):
    w, link = window
    w.add_signal_curve("INPUTS", group=GROUP)
    w.add_signal_curve("INPUTS.b1", group=GROUP)
    w.scope.curve("1: INPUTS").axis.share = "1: INPUTS.b1"
    link.call("set_input", number=2, value=1)
    link.call("set_input", number=9, value=1)
    record(w, link)
    assert set(w.scope.curve("1: INPUTS.b1").raw()[1]) == {2}
    dialog = PropertiesDialog(w.scope.curve("1: INPUTS.b1"), [c.name for c in w.scope.curves], w)
    assert dialog.select.currentText() == "b1" and dialog.select.isEnabled()
    dialog.select.setCurrentText("9")
    dialog.accept()
    assert w.edit_properties("1: INPUTS.b1", dialog=dialog)
    curve = w.scope.curve("1: INPUTS.9")        # the suffix follows the selection, so does the shared axis
    assert curve.source.select == "9" and len(curve.buffer) == 0
    assert w.scope.curve("1: INPUTS").axis.share == "1: INPUTS.9"
    assert w.list.item_for("1: INPUTS.9") is not None
    record(w, link)
    assert set(curve.raw()[1]) == {1}
    w.save_to(tmp_path / "sel.zbo")
    opened = open_scope_file(tmp_path / "sel.zbo")
    assert opened.scope.curve("1: INPUTS.9").source.select == "9"
    opened.close()
    whole = PropertiesDialog(w.scope.curve("1: INPUTS.9"), [c.name for c in w.scope.curves], w)
    whole.select.setCurrentText(WHOLE_VALUE)
    whole.accept()
    w.edit_properties("1: INPUTS.9", dialog=whole)
    assert w.scope.curve("1: INPUTS (2)").source.select is None   # "1: INPUTS" exists: made unique


def test_a_renamed_curve_keeps_its_name_and_a_bad_selection_is_refused(window, monkeypatch):
    from PySide6.QtWidgets import QMessageBox

    w, _ = window
    w.add_signal_curve("INPUTS", group=GROUP, name="Inputs word")
    dialog = PropertiesDialog(w.scope.curve("Inputs word"), [c.name for c in w.scope.curves], w)
    dialog.select.setCurrentText("w2")
    dialog.accept()
    w.edit_properties("Inputs word", dialog=dialog)
    # a user name without the suffix gets it appended once it records a part of the value
    assert w.scope.curve("Inputs word.w2").source.select == "w2"
    warnings = []
    monkeypatch.setattr(QMessageBox, "warning", lambda *a: warnings.append(a[2]))
    bad = PropertiesDialog(w.scope.curve("Inputs word.w2"), [c.name for c in w.scope.curves], w)
    bad.select.setCurrentText("b5")
    bad.accept()
    assert bad.result() != PropertiesDialog.Accepted and "b1…b4" in warnings[0]
    assert w.scope.curve("Inputs word.w2").source.select == "w2"


def test_add_curve_dialog_takes_the_aposs_suffix(window):
    w, _ = window
    dlg = AddCurveDialog([GROUP], [], w)
    dlg.signal.setText("4104.sw1")
    dlg.method.setCurrentText(GROUP)
    w.add_curve_dialog(dlg=dlg)
    curve = w.scope.curve("1: REG_STAT [4104].sw1")
    assert curve.source.signal == "4104" and curve.source.select == "sw1"


def test_derived_and_testsetp_curves_have_no_selection(window):
    from motiontool.scope.derived import DerivedSpec

    w, _ = window
    w.add_signal_curve("APOS", group=GROUP)
    w.add_derived_curve(DerivedSpec("delta", "1: APOS"), "d")
    dialog = PropertiesDialog(w.scope.curve("d"), [c.name for c in w.scope.curves], w)
    assert not dialog.select.isEnabled() and dialog.select.currentText() == WHOLE_VALUE
