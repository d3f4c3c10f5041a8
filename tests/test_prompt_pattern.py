"""The rule that keeps the IDE's questions injectable (issue 27 item 5, "dialogs through one injected prompts
object"): a Qt module - the APOSS window's (`ui/`, the program editor in `ui/editor/`) and the tool windows'
(`scope/ui/`, `cameditor/ui/`, `arrayeditor/ui/`) - asks its user through its window's prompts (`w.prompts`,
session/prompts.py; a tool window's are its APOSS window's, over itself), never by opening a QMessageBox,
QInputDialog or QFileDialog itself; only qtjobs/prompts.py (QtPrompts) opens them. So a test or a headless caller
answers every question with a ScriptedPrompts, and no command hides a dialog a script cannot answer. The About box
(QMessageBox.about) tells, it does not ask, and is not checked; nor are the colour pickers (QColorDialog), which
choose a value inside a dialog.

Read from the source (ast), without importing Qt.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "motiontool"
QT_PACKAGES = ("ui", "qtjobs", "scope/ui", "cameditor/ui", "arrayeditor/ui")   # the models import no Qt at all
ASKING = {"QMessageBox": ("question", "warning", "critical", "information"), "QInputDialog": ("get",),
          "QFileDialog": ("get",)}
# Each exception says why; an entry that no longer asks fails the test, so the list only shrinks.
EXCEPTIONS = {
    "motiontool/qtjobs/prompts.py": "QtPrompts: the one place that opens the dialogs",
}


def offences(source: str, label: str) -> list[str]:
    """The calls in `source` that open a question themselves: `QMessageBox.warning(...)`, `QMessageBox(...)` or
    `QFileDialog(...)` (a dialog built by hand), `ask_save_name(...)` (QtPrompts.save_name's dialog),
    `QInputDialog.getText(...)`, `QFileDialog.getSaveFileName(...)` and the like."""
    found = []
    for node in sorted((n for n in ast.walk(ast.parse(source)) if isinstance(n, ast.Call)), key=lambda n: n.lineno):
        func = node.func
        if isinstance(func, ast.Name) and func.id in ("QMessageBox", "QFileDialog", "QInputDialog", "ask_save_name"):
            found.append(f"{label}:{node.lineno}: {func.id}(...): ask through w.prompts")
        elif isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name) and func.value.id in ASKING \
                and func.attr.startswith(ASKING[func.value.id]):
            found.append(f"{label}:{node.lineno}: {func.value.id}.{func.attr}: ask through w.prompts")
    return found


def test_qt_modules_ask_through_the_windows_prompts():
    files = sorted({p for package in QT_PACKAGES for p in (PACKAGE / package).rglob("*.py")})
    assert len(files) > 80
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
    QFileDialog.getExistingDirectory(self, "Folder", "")
    QInputDialog.getItem(window, "TESTSETP", "Recording to upload:", labels, 0, False)
    dialog = QFileDialog(w, "Save oscilloscope", "", "Oscilloscope files (*.zbo)")
    ask_save_name(w, "Save as", "program.m", "")
    QMessageBox.about(w, "About motiontool", "tells")
    w.prompts.confirm("Reset", "Continue?")
    box.setDefaultButton(QMessageBox.StandardButton.Cancel)
'''
    hits = offences(source, "x.py")
    assert [h.split(": ")[1] for h in hits] == [
        "QMessageBox.question", "QMessageBox.warning", "QMessageBox(...)", "QInputDialog.getInt",
        "QFileDialog.getSaveFileName", "QFileDialog.getExistingDirectory", "QInputDialog.getItem", "QFileDialog(...)",
        "ask_save_name(...)"], hits
