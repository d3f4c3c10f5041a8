"""The one rule that keeps a signal's argument out of a slot's options (docs/architecture.md, "Signals and
slots"; decision I7): in Qt code, the optional parameters of methods, nested functions and lambdas -- everything
that can be connected to a signal -- are keyword-only.

PySide6 calls a Python slot with as many of the signal's arguments as the slot has positional parameters. A
`triggered(bool)` connected to `save_dialog(self, with_data=True)` therefore arrived as `with_data=False`, and
`add_curve_dialog(self, dlg=None)` got `dlg=False` -- bugs that tests calling the methods directly never saw.
With options keyword-only (`def save_dialog(self, *, with_data=True)`), no signal can reach them: a slot that
wants a signal's argument takes it as a required positional parameter. Module-level functions are not slots
(menus reach them through lambdas) and are not checked; overrides of Qt and pyqtgraph methods keep the
signatures of the methods they override.
"""

from __future__ import annotations

import ast
import importlib
import inspect
from pathlib import Path

import pytest

pytestmark = pytest.mark.gui  # it imports the Qt packages it checks

SRC = Path(__file__).resolve().parents[1] / "src"
QT_PACKAGES = ("motiontool/ui", "motiontool/scope/ui", "motiontool/cameditor/ui", "motiontool/arrayeditor/ui")
FOREIGN = ("PySide6", "shiboken6", "pyqtgraph")


def _module(path: Path):
    name = ".".join(path.relative_to(SRC).with_suffix("").parts)
    return importlib.import_module(name.removesuffix(".__init__"))


def _overrides_foreign(module, class_name: str, method: str) -> bool:
    """True when `class_name.method` overrides a method of a Qt or pyqtgraph base class."""
    cls = getattr(module, class_name, None)
    if not inspect.isclass(cls):
        return False
    return any(base.__module__.split(".")[0] in FOREIGN and hasattr(base, method) for base in cls.__mro__[1:])


def _offences(source: str, label: str, module=None) -> list[str]:
    """The functions and lambdas of `source` with positional options; `module` (imported) tells overrides."""
    found = []

    def visit(node, owner: str | None) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.ClassDef):
                visit(child, child.name)
                continue
            if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda):
                args = child.args
                positional = args.posonlyargs + args.args
                name = getattr(child, "name", "lambda")
                exempt = (name.startswith("__") and name.endswith("__")) or isinstance(node, ast.Module) or (
                    owner is not None and module is not None and _overrides_foreign(module, owner, name))
                if args.defaults and not exempt:
                    options = [a.arg for a in positional[len(positional) - len(args.defaults):]]
                    found.append(f"{label}:{child.lineno}: {name}: make {', '.join(options)} keyword-only "
                                 "(put '*,' before)")
                visit(child, None)
                continue
            visit(child, owner)

    visit(ast.parse(source), None)
    return found


def test_optional_parameters_in_qt_code_are_keyword_only():
    files = [p for package in QT_PACKAGES for p in sorted((SRC / package).rglob("*.py"))]
    assert len(files) > 40
    offences = [o for path in files
                for o in _offences(path.read_text(encoding="utf-8"), str(path.relative_to(SRC)), _module(path))]
    assert not offences, "a signal's argument could land in these options:\n" + "\n".join(offences)


def test_the_rule_catches_the_scope_defect():
    """The shape that broke the oscilloscope's Save is reported, so is a lambda binding a loop value
    positionally; their keyword-only forms are not."""
    source = ("class W:\n    def save_dialog(self, with_data=True):\n        pass\n"
              "    def ok(self, *, with_data=True):\n        pass\n"
              "def build(w, later=None):\n    bad = lambda checked=False, s=w: s\n"
              "    return bad, lambda *_, s=w: s\n")
    assert [f.split(": ")[1] for f in _offences(source, "example.py")] == ["save_dialog", "lambda"]
