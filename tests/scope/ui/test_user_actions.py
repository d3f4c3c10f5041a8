"""The oscilloscope as a user drives it from the IDE: toolbar buttons, menu entries and keys, with the modal
dialogs answered (issue 16, defects 2a). Before the fix Add curve raised "'bool' object has no attribute
'kind'" (triggered(bool) arrived as the optional dialog) and Save wrote every curve's "data": null."""

import json

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QToolButton

from motiontool.scope.ui import ScopeWindow
from motiontool.scope.ui.dialogs import AddCurveDialog
from tests.modal import answering, file_reply, ok_reply

MOVING = "VEL 50\nACC 100\nDEC 100\nmain:\nPOSA 50000\nPOSA 0\nGOTO main\n"
GROUP = "Test Group (Free Run)"


def click(qtbot, window, action):
    button = next(b for b in window.findChildren(QToolButton) if b.defaultAction() is action)
    qtbot.mouseClick(button, Qt.MouseButton.LeftButton)


def activate(qtbot, widget):
    """Bring the window to the front (a user clicks into it) so its shortcuts reach it."""
    widget.activateWindow()
    qtbot.waitUntil(widget.isActiveWindow, timeout=2000)


def add_curve_reply(signal):
    def fill(dialog):
        dialog.signal.setText(signal)
        dialog.method.setCurrentText(GROUP)
    return ok_reply(fill, AddCurveDialog)


def open_scope_moving(window, qtbot):
    """F5 on a program that moves the axis back and forth, then Tools → Oscilloscope."""
    editor = window.new_file()
    editor.setPlainText(MOVING)
    qtbot.keyClick(editor, Qt.Key.Key_F5)
    qtbot.waitUntil(lambda: window.bridge.last_status is not None
                    and window.bridge.last_status.program_state == "running", timeout=5000)
    window.actions_by_text["Oscilloscope"].trigger()
    scope = window._scopes[-1]
    qtbot.waitExposed(scope)
    return scope


def record(scope: ScopeWindow, qtbot, ms: int = 1500) -> None:
    """Start with the toolbar, let the program move, Stop with Shift+F9."""
    click(qtbot, scope, scope.start_action)
    qtbot.waitUntil(lambda: all(len(c.buffer) > 50 for c in scope.scope.curves), timeout=10000)
    qtbot.wait(ms // 3)
    activate(qtbot, scope)
    qtbot.keyClick(scope, Qt.Key.Key_F9, Qt.KeyboardModifier.ShiftModifier)
    assert not scope.run.running


def test_add_curve_button_then_free_run_records_apos_and_cpos_while_a_program_moves(window, qtbot):
    """DG 5424-5450, ide-spec S20: Add curve opens the dialog; the curves land in the Free Run group and record."""
    scope = open_scope_moving(window, qtbot)
    for signal in ("APOS", "CPOS"):
        with answering(qtbot, add_curve_reply(signal)):
            click(qtbot, scope, scope.add_action)
    assert [(c.name, c.source.group) for c in scope.scope.curves] == [("1: APOS", GROUP), ("1: CPOS", GROUP)]
    record(scope, qtbot)
    for curve in scope.scope.curves:
        t, y = curve.raw()
        assert t.size > 50 and y.max() - y.min() > 100, curve.name  # the axis moved while recording
    scope.close()


def test_save_by_toolbar_menu_and_ctrl_s_writes_the_data_and_it_reopens(window, qtbot, tmp_path):
    """DG 5349-5355, ide-spec S20 step 6: the saved .zbo holds the samples; File → Open shows them again."""
    scope = open_scope_moving(window, qtbot)
    for signal in ("APOS", "CPOS"):
        with answering(qtbot, add_curve_reply(signal)):
            click(qtbot, scope, scope.add_action)
    record(scope, qtbot)
    samples = {c.name: c.raw()[0].size for c in scope.scope.curves}
    file_menu = next(a.menu() for a in scope.menuBar().actions() if a.text() == "&File")
    save_entry = next(a for a in file_menu.actions() if a.text() == "Save")
    ways = {"toolbar": lambda: click(qtbot, scope, scope.save_action),
            "menu": save_entry.trigger,
            "ctrl_s": lambda: qtbot.keyClick(scope, Qt.Key.Key_S, Qt.KeyboardModifier.ControlModifier)}
    for way, fire in ways.items():
        path = tmp_path / f"{way}.zbo"
        activate(qtbot, scope)
        with answering(qtbot, file_reply(path)):
            fire()
        curves = json.loads(path.read_text())["curves"]
        assert all(c["data"] is not None for c in curves), way
        with answering(qtbot, file_reply(path)):
            click(qtbot, scope, scope.open_action)
        reopened = scope._opened
        assert {c.name: c.raw()[0].size for c in reopened.scope.curves} == samples, way
        assert reopened.link is None   # a file opens unbound (DG 5277-5285)
        reopened.close()
    scope.close()


def test_save_without_data_still_writes_a_template(window, qtbot, tmp_path):
    """File → Save without Data (DG 5349-5355) is the one way to write "data": null."""
    scope = open_scope_moving(window, qtbot)
    with answering(qtbot, add_curve_reply("APOS")):
        click(qtbot, scope, scope.add_action)
    record(scope, qtbot, ms=300)
    file_menu = next(a.menu() for a in scope.menuBar().actions() if a.text() == "&File")
    entry = next(a for a in file_menu.actions() if a.text() == "Save without Data")
    path = tmp_path / "template.zbo"
    with answering(qtbot, file_reply(path)):
        entry.trigger()
    assert [c["data"] for c in json.loads(path.read_text())["curves"]] == [None]
    scope.close()


# --- cursors and the mouse (issue 16, 2k) ------------------------------------------------------------------
def recorded_scope(qtbot):
    from motiontool.controller.embedded import EmbeddedLink
    from tests.scope.ui.test_scope_window import run_for

    link = EmbeddedLink()
    scope = ScopeWindow(link, "free_run", ask=False)
    qtbot.addWidget(scope)
    scope.show()
    qtbot.waitExposed(scope)
    scope.add_signal_curve("4119", group=GROUP)   # sys_clock: the value is the time
    click(qtbot, scope, scope.start_action)
    run_for(scope, link, 1000)
    click(qtbot, scope, scope.stop_action)
    return scope


def test_cursors_move_with_the_right_button_and_the_left_button_zooms_past_them(qtbot):
    """ide-spec 6.7-6.8, DG 4743-4787: cursors are moved by right-dragging; a right-drag elsewhere pans; a
    left-drag zooms a rectangle even when it starts on a cursor (it moved the cursor before)."""
    from tests.scope.ui.mouse import drag, to_pixel

    scope = recorded_scope(qtbot)
    click(qtbot, scope, scope.cursor_a)
    plot, view = scope.chart.plot, scope.chart.view
    a = scope.scope.cursors[0]
    (x0, x1), _ = view.viewRange()
    drag(qtbot, plot, to_pixel(plot, view, a, 0.5), to_pixel(plot, view, a + 0.2 * (x1 - x0), 0.3),
         Qt.MouseButton.LeftButton)
    assert scope.scope.cursors[0] == a                          # the left button leaves the cursor
    (z0, z1), _ = view.viewRange()
    assert z1 - z0 < 0.5 * (x1 - x0)                            # … and zooms
    scope.zoom_reset()
    (x0, x1), _ = view.viewRange()
    drag(qtbot, plot, to_pixel(plot, view, a, 0.5), to_pixel(plot, view, a + 0.1 * (x1 - x0), 0.5),
         Qt.MouseButton.RightButton)
    assert abs(scope.scope.cursors[0] - (a + 0.1 * (x1 - x0))) < 0.01 * (x1 - x0)   # the right button moves it
    assert view.viewRange()[0] == [x0, x1]                       # … and does not pan
    moved = scope.scope.cursors[0]
    drag(qtbot, plot, to_pixel(plot, view, x0 + 0.8 * (x1 - x0), 0.5), to_pixel(plot, view, x0 + 0.6 * (x1 - x0), 0.5),
         Qt.MouseButton.RightButton)
    (p0, p1), _ = view.viewRange()
    assert p0 > x0 + 0.1 * (x1 - x0) and scope.scope.cursors[0] == moved   # elsewhere the right button pans


# --- TESTSETP runs lie over each other (issue 16, 2l) --------------------------------------------------------
def test_a_second_testsetp_run_lands_over_the_first_not_far_beside_it(qtbot):
    """ide-spec S23: two runs of a TESTSETP program and their difference; the second run used to land at its
    controller time, so Zoom Reset showed two slivers far apart."""
    from motiontool.controller.embedded import EmbeddedLink
    from tests.scope.test_acquisition import TESTSETP, start

    link = EmbeddedLink()
    start(link, TESTSETP)
    link.advance(3000)
    scope = ScopeWindow(link, "testsetp", ask=False)   # opening the TESTSETP scope uploads the recording
    qtbot.addWidget(scope)
    scope.show()
    run_one = scope.scope.curves[0].raw()[0]
    link.advance(5000)
    start(link, TESTSETP)
    link.advance(3000)
    click(qtbot, scope, scope.load_action)
    assert len(scope.scope.curves) == 6
    run_two = scope.scope.curves[3].raw()[0]
    assert run_two[0] == run_one[0] and run_two[-1] == run_one[-1]
    (x0, x1), _ = scope.chart.view.viewRange()
    assert x1 - x0 < 1.1 * (run_one[-1] - run_one[0])   # the chart shows the runs, not the gap between them
