"""No import circles (issue 27 item 7). Module-level imports form no cycle at all, nor do imports inside functions
(KNOWN lists none; it may only shrink). A cycle makes the order in
which modules load part of their meaning (registration by import order) and hides which way a package depends."""

from __future__ import annotations

import ast
import functools
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"

# circles through imports inside functions, still to break (docs/architecture.md): none
KNOWN: set[frozenset[str]] = set()


@functools.cache
def modules() -> dict[str, Path]:
    found = {}
    for path in SRC.rglob("*.py"):
        parts = path.relative_to(SRC).with_suffix("").parts
        found[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return found


@functools.cache
def _parsed(path: Path) -> ast.Module:
    return ast.parse(path.read_text(encoding="utf-8"))


def _targets(mods: dict[str, Path], name: str, node: ast.Import | ast.ImportFrom) -> list[str]:
    if isinstance(node, ast.Import):
        wanted = [alias.name for alias in node.names]
    else:
        base = node.module or ""
        if node.level:
            package = name.split(".") if mods[name].name == "__init__.py" else name.split(".")[:-1]
            base = ".".join(package[:len(package) - node.level + 1] + ([node.module] if node.module else []))
        wanted = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in mods else base for alias in node.names]
    found = []
    for target in wanted:
        while target and target not in mods:
            target = target.rpartition(".")[0]
        if target.startswith("motiontool") and target != name:
            found.append(target)
    return found


def _module_level(tree: ast.Module) -> list[ast.stmt]:
    """Statements that run when the module loads (not under `if TYPE_CHECKING`)."""
    out: list[ast.stmt] = []
    for node in tree.body:
        if isinstance(node, ast.If):
            if "TYPE_CHECKING" not in ast.unparse(node.test):
                out += node.body + node.orelse
        elif isinstance(node, ast.Try):
            out += node.body + [s for handler in node.handlers for s in handler.body] + node.orelse
        else:
            out.append(node)
    return out


def graph(everywhere: bool) -> dict[str, set[str]]:
    mods = modules()
    edges: dict[str, set[str]] = {name: set() for name in mods}
    for name, path in mods.items():
        tree = _parsed(path)
        typing_only = {id(n) for node in tree.body if isinstance(node, ast.If)
                       and "TYPE_CHECKING" in ast.unparse(node.test) for n in ast.walk(node)}
        nodes = ast.walk(tree) if everywhere else _module_level(tree)
        for node in nodes:
            if isinstance(node, ast.Import | ast.ImportFrom) and id(node) not in typing_only:
                edges[name].update(_targets(mods, name, node))
    return edges


def cycles(edges: dict[str, set[str]]) -> list[frozenset[str]]:
    """The strongly connected components of more than one module (Tarjan, iteratively)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[frozenset[str]] = []
    counter = 0
    for root in edges:
        if root in index:
            continue
        work = [(root, iter(sorted(edges[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(edges[child]))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = set()
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.add(member)
                    if member == node:
                        break
                if len(component) > 1:
                    found.append(frozenset(component))
    return found


def test_module_level_imports_form_no_cycle():
    assert cycles(graph(everywhere=False)) == []


def test_imports_inside_functions_form_no_new_cycle():
    found = set(cycles(graph(everywhere=True)))
    new = [sorted(c) for c in found if c not in KNOWN]
    assert not new, f"a new import circle (break it, do not hide it in a function): {new}"
    assert not KNOWN - found, f"broken, remove from KNOWN: {[sorted(c) for c in KNOWN - found]}"


def test_the_cycle_finder_finds_a_cycle():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [frozenset({"a", "b", "c"})]
