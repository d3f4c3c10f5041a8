"""The link protocol's operations are declared once (comms/operations.py, issue 27 item 1); the typed client, the
controller sides and the table of docs/link-protocol.md must all follow that declaration."""

from __future__ import annotations

import inspect
import re
from pathlib import Path

import pytest

from motiontool.comms.client import METHOD_NAMES, ControllerClient
from motiontool.comms.operations import OPERATIONS, SIGNATURES, ControllerOperations, operation_table
from motiontool.controller.apc_service import PROGRAM_OPS, ApcService
from motiontool.controller.dpl_program import DplProgram
from motiontool.controller.embedded import EmbeddedLink
from motiontool.controller.service import ControllerService

ROOT = Path(__file__).resolve().parents[2]


def arguments(function) -> list[inspect.Parameter]:
    return [p for name, p in inspect.signature(function).parameters.items() if name != "self"]


def client_methods() -> set[str]:
    return {name for name, value in vars(ControllerClient).items() if callable(value) and not name.startswith("_")
            and name != "call"}


@pytest.mark.parametrize("op", sorted(OPERATIONS))
def test_the_client_has_one_method_per_operation_with_its_arguments(op):
    method = getattr(ControllerClient, METHOD_NAMES.get(op, op))
    assert [p.name for p in arguments(method)] == list(OPERATIONS[op])


def test_the_client_has_nothing_but_the_operations():
    assert client_methods() == {METHOD_NAMES.get(op, op) for op in OPERATIONS}


@pytest.mark.parametrize("op", sorted(OPERATIONS))
def test_the_mco_service_answers_every_operation_as_declared(op):
    implemented = arguments(getattr(ControllerService, "op_" + op))
    declared = arguments(getattr(ControllerOperations, "op_" + op))
    assert [(p.name, p.default) for p in implemented] == [(p.name, p.default) for p in declared]


def test_the_apc_side_answers_its_operations_as_declared():
    """The APC service answers some operations itself and hands the program ones to its DPL host; an
    implementation may leave out trailing optional arguments, which the client sends only when given."""
    answered = 0
    for op, names in OPERATIONS.items():
        owner = ApcService if hasattr(ApcService, "op_" + op) else DplProgram if op in PROGRAM_OPS else None
        if owner is None or not hasattr(owner, "op_" + op):
            continue
        answered += 1
        implemented = [p.name for p in arguments(getattr(owner, "op_" + op))]
        assert implemented == list(names[:len(implemented)]), op
        declared = dict(SIGNATURES[op].parameters)
        left_out = [name for name in names[len(implemented):] if declared[name].default is inspect.Parameter.empty]
        assert not left_out, f"{op}: the APC side needs {left_out}"
    assert answered >= 20


def test_the_documented_table_is_the_declared_one():
    text = (ROOT / "docs" / "link-protocol.md").read_text(encoding="utf-8")
    table = re.search(r"<!-- operations: generated -->\n(.*?)\n<!-- end of operations -->", text, re.S)
    assert table is not None
    assert table.group(1).split("\n") == operation_table(), "run python -m motiontool.comms.operations"


def test_typed_answers_on_the_simulated_controller():
    link = EmbeddedLink()
    identity = link.identify()
    assert identity.product.startswith("MCO 305") and identity.kind == "MCO"
    assert link.status().program_state == "idle"
    assert link.list_programs() == [] and link.error_history() == [] and link.recording_status() is None
    link.restore_arrays([("speeds", [1, 2, 3])])
    (info,) = link.list_arrays()
    assert (info.index, info.name, info.size) == (0, "speeds", 3)
    status = link.start_recording(["APOS"], interval_ms=2, count=10)
    assert status.running and status.limit == 10
    link.advance(30)
    shot = link.stop_recording()
    assert shot.signals == ["APOS"] and len(shot.samples) == 10 and shot.interval_ms == 2


@pytest.mark.parametrize("kind", ["MCO", "APC"])
def test_every_signal_the_controller_lists_can_be_read_and_streamed(kind):
    """The scope's signal browser offers what list_signals answers: each name must be one the controller reads."""
    if kind == "MCO":
        link = EmbeddedLink()
    else:
        from motiontool.controller.apc_service import embedded_apc_link

        link = embedded_apc_link()
    signals = link.list_signals()
    groups = {s.group for s in signals}
    assert len(signals) > 100 and all(s.name and s.text for s in signals)
    assert ({"Axis", "Process data (SYSVAR)", "Parameters"} if kind == "MCO" else {"APC read parameters"}) <= groups
    names = [s.name for s in signals]
    assert len(link.read_signals(names)) == len(names)
    link.stream(names[:20], interval_ms=1)
    link.stream([], interval_ms=1)


STRING_DOOR = re.compile(r"""\.call\(\s*["']""")


def string_door_calls() -> list[str]:
    """Where a module of src/motiontool outside comms/ (the client's own package) asks through `call("op", ...)`."""
    package = ROOT / "src" / "motiontool"
    found = []
    for path in sorted(package.rglob("*.py")):
        where = path.relative_to(package).as_posix()
        if where.startswith("comms/"):
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
            if STRING_DOOR.search(line):
                found.append(f"{where}:{number}")
    return found


def test_no_module_asks_through_the_string_door():
    """The typed client is how the IDE asks a controller (issue 27 item 1): a value can be followed from the
    dialog, the scope or the CLI to the operation that answers it."""
    assert string_door_calls() == []
