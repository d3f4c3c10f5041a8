"""The operations of the link protocol, declared once (docs/link-protocol.md, issue 27 item 1).

`ControllerOperations` is what a controller side answers: one `op_<name>` method per operation, its parameters
being the request's arguments (JSON values) and its first docstring line what the answer holds. Everything else
follows it: the dispatch check `OPERATIONS`, the typed client (comms/client.py: one method per operation, same
arguments), the table in docs/link-protocol.md (`operation_table`), and the services that implement it
(controller/service.py for the MCO 305, controller/apc_service.py and dpl/host.py for the APC).
tests/comms/test_operations.py keeps all of them in step. The wire format is not touched: a request is still
`{op, args, id}`.
"""

from __future__ import annotations

import inspect
import json
from typing import Any, Protocol

Json = Any     # a JSON value: the arguments and answers of the protocol


class ControllerOperations(Protocol):
    # --- the controller ---------------------------------------------------------------------------------------
    def op_identify(self) -> dict:
        """product, firmware, protocol version, name; the APC adds kind and pos_period_us, a virtual drive node,
        clock, drive and boot"""

    def op_set_name(self, name: str) -> None:
        """Parameters → Name: at most 8 upper-case characters"""

    def op_status(self) -> dict:
        """time_ms, program_state (idle/running/break/ended/error), program, error, line, apos, cpos, axend"""

    def op_read_parameter(self, key: str | int) -> int:
        """the raw value (e.g. RAMPMIN in ms); key "32-60", 3260 or "KPROP"; "4-13" is the FC 300's own"""

    def op_write_parameter(self, key: str | int, value: int) -> None:
        """writes the raw value; refused outside the parameter's range"""

    # --- arrays -------------------------------------------------------------------------------------------------
    def op_list_arrays(self) -> list:
        """[{index, name, size}] in DIM order"""

    def op_read_array(self, index: int) -> list:
        """the values of the array at 0-based DIM position index"""

    def op_write_array(self, index: int, values: list) -> None:
        """writes values from the array's first element"""

    def op_restore_arrays(self, arrays: list) -> None:
        """arrays [{name, values}] in DIM order replace the array memory (Restore from file, `run --config`)"""

    # --- programs -----------------------------------------------------------------------------------------------
    def op_download(self, image: str, number: int | None = None, name: str = "", source: dict | None = None,
                    stack_size: int | None = None) -> None:
        """image: base64 of the program image; number None = temporary; source {file: text}, the program first
        (Include Sourcecode); stack_size (Settings → Compiler)"""

    def op_list_programs(self) -> list:
        """[{number, name, autostart, source, stored_at}]"""

    def op_upload_source(self, number: int) -> dict:
        """{files, main, stored_at} of a program stored with its source"""

    def op_upload_program(self, number: int) -> str:
        """the program image (base64), for Download's Verify"""

    def op_delete_program(self, number: int) -> None:
        """deletes a stored program"""

    def op_set_autostart(self, number: int | None) -> None:
        """the Autostart mark on program number (None = off)"""

    def op_power_on(self) -> None:
        """switches a simulated controller off and on (Autostart runs)"""

    def op_start(self, number: int | None = None, step: bool = False, inputs: list | tuple = ()) -> None:
        """starts a program (None = the temporary one); step: stop before statement 1 (Prepare Singlestep);
        inputs [[N, V, T]]: input N to V T ms after the start (Test-inputs)"""

    def op_break(self) -> None:
        """[Esc]"""

    def op_continue(self) -> None:
        """Continue after a break"""

    # --- inputs (simulated controllers); the APC's are named: DIGIN0, REF_MARKER, FB_MARKER (apc_service.apc_input) ---
    def op_set_input(self, number: int | str, value: int) -> None:
        """digital 0/1, analog 53/54 (INAD -1000…1000); simulated controllers only"""

    def op_schedule_input(self, number: int | str, value: int, time_ms: int) -> None:
        """input number to value at controller time time_ms; simulated controllers only"""

    # --- signals and the scope ------------------------------------------------------------------------------------
    def op_stream(self, signals: list, interval_ms: int = 1) -> None:
        """starts `samples` events of signals every interval_ms ([] stops)"""

    def op_read_signals(self, signals: list) -> list:
        """one poll: the signals' present values"""

    def op_list_signals(self) -> list:
        """[{name, group, text}]: the signals stream, read_signals and the recordings take (the scope's browser)"""

    def op_list_recordings(self) -> list:
        """TESTSETP recordings: [{index, name, samples, indices, running}]"""

    def op_upload_recording(self, index: int) -> dict:
        """{name, interval_ms, start_ms, indices, names, samples, first_ms}; first_ms = time of the first kept set"""

    def op_start_recording(self, signals: list, interval_ms: int = 1, destination: str = "DYNMEM",
                           cyclic: bool = False, count: int = 0) -> dict:
        """Single Shot: starts a recording owned by the link (destination "DYNMEM" or a user array; count 0 =
        fill); answers its status"""

    def op_recording_status(self) -> dict | None:
        """{running, samples, limit, taken, interval_ms} or null"""

    def op_stop_recording(self) -> dict:
        """{name, interval_ms, start_ms, signals, time_ms, samples, taken}; the recording is then forgotten"""

    # --- errors, memory, reset ------------------------------------------------------------------------------------
    def op_error_history(self) -> list:
        """oldest first: [{time_ms, number, text, line, detail}]"""

    def op_clear_error(self) -> None:
        """ERRCLR"""

    def op_clear_error_history(self) -> None:
        """Error History → Clear"""

    def op_save_memory(self, what: str) -> None:
        """Memory ▸: what = ram (Save RAM), user, arrays, app (all application data), option"""

    def op_delete_eprom(self) -> None:
        """Memory ▸ Delete EPROM: the factory settings at the next power on"""

    def op_reset(self, what: str) -> None:
        """Controller → Reset: what = parameters (global + axis defaults), user (19-xx), arrays, all (also the
        stored programs)"""

    def op_advance(self, ms: int) -> None:
        """virtual time (the synchronous embedded link, a virtual drive with `--clock virtual`)"""

    # --- the debugger (debug builds) --------------------------------------------------------------------------------
    def op_set_breakpoints(self, lines: list) -> None:
        """source lines of the main file, at most 10"""

    def op_step(self) -> None:
        """runs to the next statement and stops there"""

    def op_read_variables(self, names: list) -> list:
        """[value] of "name" or "array[i]" each"""

    def op_write_variable(self, name: str, value: int | float) -> None:
        """sets a variable or an array element"""


def _declared() -> dict[str, inspect.Signature]:
    return {name.removeprefix("op_"): inspect.signature(method) for name, method in vars(ControllerOperations).items()
            if name.startswith("op_")}


SIGNATURES: dict[str, inspect.Signature] = _declared()
# operation → argument names: what a controller side accepts (the wire-only `events` is the drive's, F9)
OPERATIONS: dict[str, tuple[str, ...]] = {op: tuple(sig.parameters)[1:] for op, sig in SIGNATURES.items()}


def summary(op: str) -> str:
    """The answer of an operation, from its declaration (one line)."""
    doc = inspect.getdoc(getattr(ControllerOperations, "op_" + op))
    assert doc is not None, f"op_{op} is declared without the docstring that says its answer"
    return " ".join(doc.split())


def operation_table() -> list[str]:
    """The table of docs/link-protocol.md: op, arguments (with defaults), what it does or answers."""
    rows = ["| op | arguments | value |", "|---|---|---|"]
    for op, sig in SIGNATURES.items():
        args = ", ".join(name if p.default is inspect.Parameter.empty else f"{name}={_json(p.default)}"
                         for name, p in list(sig.parameters.items())[1:])
        rows.append(f"| {op} | {args} | {summary(op)} |")
    return rows


def _json(value: Json) -> str:
    return json.dumps(list(value) if isinstance(value, tuple) else value)


if __name__ == "__main__":    # python -m motiontool.comms.operations: the table for docs/link-protocol.md
    print("\n".join(operation_table()))
