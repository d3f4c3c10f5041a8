"""Tools → Array Editor against the embedded controller (ide-spec 5.5-5.30, DG L4074-4590)."""

from PySide6.QtCore import QItemSelectionModel, Qt

from motiontool.arrayeditor.ui.editor import COLUMNS, GREEN, RED_BG, VALUE
from motiontool.formats.zba import read_zba


def _open(window):
    assert window.development.connect_default()
    window.bridge.link.call("restore_arrays", arrays=[{"name": "speeds", "values": [10, 20, 30]}])
    window.actions_by_text["Array Editor"].trigger()
    return window._array_editor


def _row(editor, label):
    for r in range(editor.model.rowCount()):
        row = editor.model.row_at(r)
        if editor.data_list.label(row).startswith(label):
            return r, row
    raise AssertionError(label)


def test_opens_on_the_windows_controller_and_lists_arrays_and_parameters(window):
    """DG L4088-4109: from Tools → Array Editor, in Expert mode; "If the active window has a controller, its
    data loads automatically"; columns of DG L4147-4223."""
    editor = _open(window)
    model = editor.model
    assert [model.headerData(c, Qt.Orientation.Horizontal) for c in range(len(COLUMNS))] == list(COLUMNS)
    assert "Controller 1" in editor.windowTitle() and "Expert" in editor.windowTitle()
    r, row = _row(editor, "Array 0[2]")
    assert row.controller == 20 and model.data(model.index(r, VALUE + 1)) == "20"
    r, row = _row(editor, "Axis 1 3260 KPROP")
    assert row.controller == 30 and row.record.default == 30 and row.record.maximum == 100000
    r, row = _row(editor, "Proc 1 3450")  # process data are read-only: green
    assert model.data(model.index(r, 0), Qt.ItemDataRole.BackgroundRole).color().name() == GREEN
    for name in ("All", "User", "Axis 1", "Proc 1", "Global", "0"):
        assert editor.selection_box.findText(name) >= 0, name


def test_edit_values_then_write_to_controller(window, qtbot):
    """DG L4193-4253: the Value cell is edited; nothing is sent until Write to controller, which writes the
    non-blank values of all arrays; an invalid value is red with the reason as tooltip and blocks Write."""
    editor = _open(window)
    editor.selection_box.setCurrentText("0")
    assert editor.model.rowCount() == 3
    model = editor.model
    assert model.setData(model.index(1, VALUE), "25")
    assert window.bridge.link.read_array(0) == [10, 20, 30]  # not yet written
    editor.selection_box.setCurrentText("Axis 1")
    r, _row_kprop = _row(editor, "Axis 1 3260 KPROP")
    assert model.setData(model.index(r, VALUE), "200000")  # outside 0..100000
    assert model.data(model.index(r, VALUE), Qt.ItemDataRole.BackgroundRole).color().name() == RED_BG
    assert "maximum" in model.data(model.index(r, VALUE), Qt.ItemDataRole.ToolTipRole)
    editor._error = lambda text: setattr(editor, "last_error", text)
    assert not editor.write_controller()
    assert "KPROP" in editor.last_error
    assert model.setData(model.index(r, VALUE), "45")
    assert editor.write_controller()
    assert window.bridge.link.read_array(0) == [10, 25, 30]
    assert window.bridge.link.read_parameter("KPROP") == 45


def test_set_to_default_and_to_controller(window):
    editor = _open(window)
    editor.selection_box.setCurrentText("Axis 1")
    r, row = _row(editor, "Axis 1 3260 KPROP")
    # select through the selection model: QTableView.selectRow obeys the application's keyboard modifiers,
    # which key clicks with Ctrl/Shift in earlier tests leave set under the offscreen platform
    flags = QItemSelectionModel.SelectionFlag.ClearAndSelect | QItemSelectionModel.SelectionFlag.Rows
    editor.table.selectionModel().select(editor.model.index(r, 0), flags)
    editor.set_to_controller()
    assert row.pending == 30
    row.pending = 99
    editor.set_to_default()
    assert row.pending == 30


def test_add_and_delete_arrays_then_save_as_zba(window, tmp_path):
    """DG L4375-4420: Add Array appends after the last array and is created on Write; Delete Array removes
    it; Save As writes the list as a .zba (DG L4515-4523)."""
    editor = _open(window)
    k = editor.add_array(size=4)
    assert k == 1
    assert editor.write_controller()
    assert [a["size"] for a in window.bridge.link.call("list_arrays")] == [3, 4]
    assert editor.delete_array(k=0)
    assert editor.write_controller()
    assert [a["size"] for a in window.bridge.link.call("list_arrays")] == [4]
    path = tmp_path / "machine.zba"
    assert editor.save_as(path=path)
    zba = read_zba(path)
    assert any(r.kind == "Axis" and r.index == 3260 and r.name == "KPROP" for r in zba.records)
    assert "machine.zba" in editor.windowTitle()


def test_template_shows_only_its_items(window, tmp_path):
    """DG L4426-4464: with a file only its items are shown; items missing on the controller are green and
    disabled; a read-only flag makes the row green."""
    path = tmp_path / "t.zba"
    path.write_text('Group,-1,0,"Set-up",,,,,,0\n'
                    'Axis,1,3260,"Gain",40,30,0,500,"position gain",1\n'
                    'Array,0,2,"Second",,,0,100,"speed 2",1\n'
                    'Array,5,1,"Missing",,,,,"not on the controller",1\n'
                    'Array,0,3,"Locked",,,,,"read only",0\n')
    editor = _open(window)
    assert editor.open_file(path=path)
    rows = editor.data_list.rows
    assert [editor.data_list.label(r) for r in rows] == [
        "Group -1 0 Set-up", "Axis 1 3260 Gain", "Array 0[2] Second", "Array 5[1] Missing", "Array 0[3] Locked"]
    assert rows[1].controller == 30 and rows[1].pending == 40 and rows[1].differs
    assert rows[2].controller == 20
    assert not rows[3].exists and not rows[3].writable
    assert not rows[4].writable
