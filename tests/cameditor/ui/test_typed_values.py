"""A fraction typed into the CAM editor is refused where it is typed (decision C20), not at Save: the curve array
holds LONG values ("Long word (32 bit): -2^31 to +2^31-1", DG 6397; docs/formats/cam-array.md), and a slave of
2900.5 typed into the Fix Points table used to be taken and then refused by Save (issue 23 item 9)."""

from __future__ import annotations

from motiontool.formats.zbc import ConfigFile, read_config
from tests.camcurve.conftest import stamping_curve
from tests.cameditor.ui.helpers import add_fix_points, add_pairs, edit_cell
from tests.modal import answering, file_reply

SLAVE = 2  # Fix Points table columns: #, Master, Slave, Type


def _stamping(editor) -> None:
    config = ConfigFile(parameters={"33-10": 2048, "33-11": 55})
    config.add_curve(stamping_curve())
    editor.load_config(config, None)


def test_a_fractional_slave_is_refused_in_the_cell_and_a_whole_one_saves(qtbot, editor, tmp_path):
    _stamping(editor)
    before = editor.curve()
    edit_cell(qtbot, editor, 2, SLAVE, "2900.5")
    assert editor.curve() == before
    assert editor.message_line.text() == ("Edit point: point 3: slave 2900.5 is not a whole number (the controller "
                                          "stores the curve as longs): type 2900 or 2901")
    assert editor.fix_table.model.index(2, SLAVE).data() == f"{before.fix_points[2].slave:g}"  # the cell too
    edit_cell(qtbot, editor, 2, SLAVE, "2900")
    assert editor.curve().fix_points[2].slave == 2900
    path = tmp_path / "typed.zbc"
    with answering(qtbot, file_reply(path)):
        editor.actions_by_name["save"].trigger()
    assert read_config(path).curve("stamping").fix_points[2].slave == 2900


def test_the_add_dialogs_refuse_fractions_too(qtbot, editor):
    _stamping(editor)
    before = editor.curve()
    add_fix_points(editor, "1200, 10.25")
    assert editor.curve() == before and "slave 10.25 is not a whole number" in editor.message_line.text()
    add_pairs(editor, "1000.5 1500")
    assert editor.curve() == before and "pair 1: 1000.5 is not on the interpolation grid" in editor.message_line.text()
    add_fix_points(editor, "1200, 10")
    assert (1200, 10) in [(p.master, p.slave) for p in editor.curve().fix_points]
