"""The rule that keeps the IDE's questions injectable (issue 27 item 5, "dialogs through one injected prompts
object"): a module of `motiontool/ui` asks its user through the window's prompts (`w.prompts`, session/prompts.py),
never by opening a QMessageBox, QInputDialog or QFileDialog itself; only ui/prompts.py (QtPrompts) opens them.
So a test or a headless caller answers every question with a ScriptedPrompts, and no command hides a dialog a
script cannot answer. The About box (QMessageBox.about) tells, it does not ask, and is not checked.

Read from the source (ast), without importing Qt.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
UI = SRC / "motiontool" / "ui"
ASKING = {"QMessageBox": ("question", "warning", "critical", "information"), "QInputDialog": ("get",),
          "QFileDialog": ("get",)}
# Each exception says why; an entry that no longer asks fails the test, so the list only shrinks.
EXCEPTIONS = {
    "motiontool/ui/prompts.py": "QtPrompts: the one place that opens the dialogs",
    # the editor widget's own commands (Go to Line, Repeat, Print, Find in Files' folder) work in an editor
    # that has no window yet; they move when the editor is given the window's prompts (issue 27 item 5)
    "motiontool/ui/editor/editing.py": "Go to Line, Repeat",
    "motiontool/ui/editor/printing.py": "Print's failure",
    "motiontool/ui/editor/find_dialog.py": "Find in Files' folder (QFileDialog.getExistingDirectory)",
}


def offences(source: str, label: str) -> list[str]:
    """The calls in `source` that open a question themselves: `QMessageBox.warning(...)`, `QMessageBox(...)`
    (a box built by hand), `QInputDialog.getText(...)`, `QFileDialog.getSaveFileName(...)` and the like."""
    found = []
    for node in sorted((n for n in ast.walk(ast.parse(source)) if isinstance(n, ast.Call)), key=lambda n: n.lineno):
        func = node.func
        if isinstance(func, ast.Name) and func.id == "QMessageBox":
            found.append(f"{label}:{node.lineno}: QMessageBox(...): ask through w.prompts")
        elif isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name) and func.value.id in ASKING \
                and func.attr.startswith(ASKING[func.value.id]):
            found.append(f"{label}:{node.lineno}: {func.value.id}.{func.attr}: ask through w.prompts")
    return found


def test_ui_modules_ask_through_the_windows_prompts():
    files = sorted(UI.rglob("*.py"))
    assert len(files) > 30
    found = {str(p.relative_to(SRC)): offences(p.read_text(encoding="utf-8"), str(p.relative_to(SRC)))
             for p in files}
    unexcused = [o for label, hits in found.items() if label not in EXCEPTIONS for o in hits]
    assert not unexcused, "these open a dialog themselves:\n" + "\n".join(unexcused)
    stale = [label for label in EXCEPTIONS if not found.get(label)]
    assert not stale, f"no longer asking by themselves, drop them from EXCEPTIONS: {stale}"


def test_the_rule_catches_each_way_of_opening_a_dialog():
    source = '''
def f(w, self):
    QMessageBox.question(w, "Reset", "Continue?")
    QMessageBox.warning(w, "Open", "no")
    box = QMessageBox(QMessageBox.Icon.Warning, "Download all", "?", QMessageBox.StandardButton.Cancel, self)
    QInputDialog.getInt(self, "Save as", "Program number (0-90):", 0, 0, 90)
    QFileDialog.getSaveFileName(w, "Save to file", "controller.zbc", "")
    QMessageBox.about(w, "About motiontool", "tells")
    w.prompts.confirm("Reset", "Continue?")
    box.setDefaultButton(QMessageBox.StandardButton.Cancel)
'''
    hits = offences(source, "x.py")
    assert [h.split(": ")[1] for h in hits] == [
        "QMessageBox.question", "QMessageBox.warning", "QMessageBox(...)", "QInputDialog.getInt",
        "QFileDialog.getSaveFileName"], hits
