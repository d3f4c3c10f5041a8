"""Export adds the chosen format's extension to a name typed without one (issue 23 item 9), typed into Qt's own
file dialog as a user does."""

from motiontool.controller.embedded import EmbeddedLink
from motiontool.scope.ui import ScopeWindow
from tests.modal import answering
from tests.scope.ui.test_scope_window import POSA, click, run_for, start_program
from tests.ui.test_save_names import type_name


def test_export_adds_the_format_extension(qtbot, tmp_path):
    link = EmbeddedLink()
    w = ScopeWindow(link, "free_run", ask=False)
    qtbot.addWidget(w)
    w.show()
    w.add_signal_curve("APOS", group="Test Group (Free Run)")
    click(qtbot, w, w.start_action)
    start_program(link, POSA)
    run_for(w, link, 500)
    click(qtbot, w, w.stop_action)
    with answering(qtbot, type_name(qtbot, str(tmp_path / "posa_run"))):
        w.export_action.trigger()
    text = (tmp_path / "posa_run.csv").read_text(encoding="utf-8")
    assert "APOS" in text.splitlines()[0] and len(text.splitlines()) > 10
    assert not (tmp_path / "posa_run").exists()
