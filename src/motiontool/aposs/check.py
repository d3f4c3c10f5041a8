"""Structural checks of an APOSS program (the parts that need the whole program): program layout, labels,
jump and GOSUB targets, BREAK placement, subprogram and function declarations. Name and type checks
happen while generating code (codegen.py), where the symbols are resolved."""

from __future__ import annotations

from dataclasses import dataclass, field

from motiontool.aposs import ast
from motiontool.language.diagnostics import DiagnosticSink, Location


@dataclass
class Unit:
    """A body of code that jumps stay inside: the main program, one subprogram or one function."""

    kind: str  # "main" | "subprogram" | "function"
    name: str
    body: list[ast.Stmt]
    labels: dict[str, Location] = field(default_factory=dict)


def units_of(program: ast.Program) -> list[Unit]:
    units = [Unit("main", "main program", program.statements)]
    units += [Unit("subprogram", f"SUBPROG {s.text}", s.body) for s in program.subprograms]
    units += [Unit("function", f"function {f.text}", f.body) for f in program.functions if f.body is not None]
    return units


def check_program(program: ast.Program, sink: DiagnosticSink) -> list[Unit]:
    units = units_of(program)
    _check_layout(program, sink)
    _check_labels(units, sink)
    _check_jumps(program, units, sink)
    _check_breaks(units, sink)
    _check_subprograms(program, sink)
    return units


def _check_layout(program: ast.Program, sink: DiagnosticSink) -> None:
    seen_other: ast.Node | None = None   # first statement that is neither DIM nor pragma
    seen_code_before_area = False
    area_seen = False
    for kind, item in program.order:
        if kind == "subarea":
            area_seen = True
            continue
        if kind == "func":
            seen_other = seen_other or item
            continue
        if isinstance(item, ast.Dim):
            if seen_other is not None:
                sink.error(f"DIM must come before all other statements (DG 6439); the first statement is "
                           f"at {seen_other.loc}", item.loc)
        elif isinstance(item, ast.Pragma):
            if seen_other is not None:
                sink.error("#pragma must stand directly after the DIM statement (DG 6090)", item.loc)
        else:
            seen_other = seen_other or item
            if not isinstance(item, (ast.VarDecl, ast.Label)):
                if area_seen and seen_code_before_area:
                    sink.warning("program code after ENDPROG runs after the code before SUBMAINPROG; "
                                 "keep the main program in one place", item.loc)
                    seen_code_before_area = False  # say it once
                elif not area_seen:
                    seen_code_before_area = True


def _check_labels(units: list[Unit], sink: DiagnosticSink) -> None:
    everywhere: dict[str, Location] = {}
    for unit in units:
        for stmt in ast.walk(unit.body):
            if isinstance(stmt, ast.Label):
                if stmt.name in everywhere:
                    sink.error(f"label '{stmt.text}' is defined twice (first at {everywhere[stmt.name]})", stmt.loc)
                    continue
                everywhere[stmt.name] = stmt.loc
                unit.labels[stmt.name] = stmt.loc


def _check_jumps(program: ast.Program, units: list[Unit], sink: DiagnosticSink) -> None:
    subs = {s.name for s in program.subprograms}
    funcs = {f.name for f in program.functions}
    for unit in units:
        for stmt in ast.walk(unit.body):
            if isinstance(stmt, (ast.Goto, ast.Loop)):
                word = "GOTO" if isinstance(stmt, ast.Goto) else "LOOP"
                if stmt.label in unit.labels:
                    continue
                other = next((u for u in units if stmt.label in u.labels), None)
                if other is not None:
                    sink.error(f"{word} {stmt.text} would jump from the {unit.name} into the {other.name}; jumps "
                               "must stay inside one program part (error 152 on the controller)", stmt.loc)
                else:
                    sink.error(f"label '{stmt.text}' is not defined", stmt.loc)
            elif isinstance(stmt, (ast.Gosub, ast.OnInterrupt)):
                name = stmt.name if isinstance(stmt, ast.Gosub) else stmt.handler
                text = stmt.text if isinstance(stmt, ast.Gosub) else stmt.handler_text
                if name is None or name in subs:
                    continue
                hint = f"; '{text}' is a function, call it as {text}()" if name in funcs else ""
                sink.error(f"GOSUB target '{text}' is not a SUBPROG in the SUBMAINPROG area{hint}", stmt.loc)


def _check_breaks(units: list[Unit], sink: DiagnosticSink) -> None:
    def visit(body: list[ast.Stmt], breakable: bool) -> None:
        for stmt in body:
            if isinstance(stmt, ast.Break) and not breakable:
                sink.error("BREAK outside SWITCH, WHILE or REPEAT", stmt.loc)
            inner = breakable or isinstance(stmt, (ast.While, ast.Repeat, ast.Switch))
            for block in ast.child_blocks(stmt):
                visit(block, inner)

    for unit in units:
        visit(unit.body, False)


def _check_subprograms(program: ast.Program, sink: DiagnosticSink) -> None:
    seen: dict[str, Location] = {}
    for sub in program.subprograms:
        if sub.name in seen:
            sink.error(f"SUBPROG '{sub.text}' is defined twice (first at {seen[sub.name]})", sub.loc)
        seen.setdefault(sub.name, sub.loc)
    defined: dict[str, ast.Function] = {}
    declared: dict[str, ast.Function] = {}
    for func in program.functions:
        first = declared.get(func.name)
        if first is not None and _signature(first) != _signature(func):
            sink.error(f"function '{func.text}' does not match its declaration at {first.loc}", func.loc)
        declared.setdefault(func.name, func)
        if func.body is not None:
            if func.name in defined:
                sink.error(f"function '{func.text}' is defined twice (first at {defined[func.name].loc})", func.loc)
            defined[func.name] = func
        if func.name in seen:
            sink.error(f"'{func.text}' names both a function and a SUBPROG", func.loc)
    for name, func in declared.items():
        if name not in defined:
            sink.error(f"function '{func.text}' is declared but never defined", func.loc)


def _signature(func: ast.Function) -> tuple:
    return func.type, tuple((p.type, p.is_array) for p in func.params)
