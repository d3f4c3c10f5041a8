"""The SM-Applications module running a DPL program on an APC drive: the task scheduler (docs/decisions.md A60).

* **Initial** runs first; the POS tasks start in the sample after it ends.
* **Pos0** and **Pos1** run to completion inside every POS sample, before and after the APC kernel (the drive
  calls them: `drive.pos0`, `drive.pos1`). A POS task that does not finish within MAX_POS_STATEMENTS is an
  overrun, a run-time error.
* **Background** (and Initial until it ends) runs as a time slice between POS samples: up to SLICE_STATEMENTS,
  and at most one pass of a loop — a jump back to an earlier line ends the slice — so an endless background loop
  (``top: … goto top:``) runs once per POS period. Background runs once unless it loops, like SyPT's task.

The drive is any object with the ApcDrive API (docs/apc.md): `tick()`, `pos0`/`pos1`, `task`, `params`,
`call_dpl`, `reinit()`. One runtime drives one drive; a CTSync line ticks its drives together and calls
`slice()` of each runtime between samples.
"""

from __future__ import annotations

from collections.abc import Callable

from motiontool.dpl.codegen import CodeGen, DplRuntimeError, Memory, TaskCode
from motiontool.dpl.driver import CheckResult

SLICE_STATEMENTS = 1000
MAX_POS_STATEMENTS = 100_000


class DplRuntime:
    def __init__(self, drive, checked: CheckResult):
        if checked.program is None:
            raise ValueError("the program has errors: check it first")
        self.drive = drive
        self.checked = checked
        symbols = checked.symbols
        assert symbols is not None  # check_source gives the symbols with every program it returns
        self.memory = Memory({name: 0 for name in symbols.variables},
                             {**{name: [0] * size for name, size in symbols.arrays.items()},
                              **{name: list(values) for name, values in symbols.consts.items()}})
        gen = CodeGen(checked.program, symbols, drive, self.memory)
        self.code = {name: gen.task(name) for name in ("Initial", "Background", "Pos0", "Pos1")}
        self.state = "idle"          # idle | initial | running | stopped | error
        self.error: DplRuntimeError | None = None
        self.listeners: list[Callable[[str, object], None]] = []   # ("state", state) / ("error", error)
        self._pc = {"Initial": 0, "Background": 0}
        self.line: int | None = None   # the statement last executed (for the IDE's status)

    # --- control ---------------------------------------------------------------------------------------------
    def start(self) -> None:
        """Start the program from its Initial task with all variables 0 (a module reset)."""
        for name in self.memory.variables:
            self.memory.variables[name] = 0
        symbols = self.checked.symbols
        assert symbols is not None  # __init__ took only a checked program
        for name, size in symbols.arrays.items():
            self.memory.arrays[name][:] = [0] * size
        self._pc = {"Initial": 0, "Background": 0}
        self.error = None
        self._set_state("initial" if self.code["Initial"] else "running")
        if self.state == "running":
            self._start_pos_tasks()

    def stop(self) -> None:
        """[Esc]: the tasks stop; the APC keeps the references it was given (the drive is not switched off)."""
        self._remove_pos_tasks()
        if self.state in ("initial", "running"):
            self._set_state("stopped")

    @property
    def running(self) -> bool:
        return self.state in ("initial", "running")

    def advance(self, samples: int = 1) -> None:
        """`samples` POS periods: a time slice of Initial or Background, then the drive's sample."""
        for _ in range(samples):
            self.slice()
            self.drive.tick()

    def slice(self) -> None:
        """The time between two POS samples: Initial until it ends, then Background."""
        try:
            if self.state == "initial":
                if self._run_slice("Initial"):
                    self._set_state("running")
                    self._start_pos_tasks()
            elif self.state == "running" and self.code["Background"] is not None:
                self._run_slice("Background")
        except DplRuntimeError as exc:
            self._fail(exc)

    # --- tasks -----------------------------------------------------------------------------------------------
    def _run_slice(self, name: str) -> bool:
        """Run task `name` for one slice from where it stopped; True when it has ended."""
        code = self.code[name]
        assert code is not None  # slice() runs only the tasks the program has
        ops, backward, n = code.ops, code.backward, len(code.ops)
        pc = self._pc[name]
        previous, self.drive.task = self.drive.task, name.lower()
        try:
            for _ in range(SLICE_STATEMENTS):
                if pc >= n:
                    break
                target = ops[pc]()
                if target is None:
                    pc += 1
                else:
                    jumped_back = backward[pc]
                    pc = target
                    if jumped_back:  # one pass of a loop per slice
                        break
        finally:
            self.drive.task = previous
            self._pc[name] = pc
        if pc < n:
            self.line = code.locs[pc].line
        return pc >= n

    def _pos_task(self, code: TaskCode) -> Callable[[], None]:
        ops, n = code.ops, len(code.ops)

        def run() -> None:
            if self.state != "running":
                return
            pc, count = 0, 0
            try:
                while pc < n:
                    target = ops[pc]()
                    count += 1
                    if count > MAX_POS_STATEMENTS:
                        raise DplRuntimeError(f"the {code.name} task did not end within its POS period (task "
                                              f"overrun after {MAX_POS_STATEMENTS} statements)", code.locs[pc])
                    pc = pc + 1 if target is None else target
            except DplRuntimeError as exc:
                self._fail(exc)
        return run

    def _start_pos_tasks(self) -> None:
        for name, attribute in (("Pos0", "pos0"), ("Pos1", "pos1")):
            code = self.code[name]
            setattr(self.drive, attribute, self._pos_task(code) if code is not None else None)

    def _remove_pos_tasks(self) -> None:
        self.drive.pos0 = None
        self.drive.pos1 = None

    def _fail(self, error: DplRuntimeError) -> None:
        self.error = error
        self._remove_pos_tasks()
        self._set_state("error")
        for listener in list(self.listeners):
            listener("error", error)

    def _set_state(self, state: str) -> None:
        self.state = state
        for listener in list(self.listeners):
            listener("state", state)

    # --- the debugger's and the watch's view -----------------------------------------------------------------
    def read_variable(self, name: str) -> int:
        """A variable (``Count%``) or an array element (``InArray%[2]``) by name, any case."""
        text = name.strip()
        base, _, rest = text.partition("[")
        key = base.strip().upper()
        if rest:
            data = self.memory.arrays.get(key)
            if data is None:
                raise KeyError(f"no array '{base.strip()}'")
            index = int(rest.rstrip("]").strip(), 0)
            if not 0 <= index < len(data):
                raise KeyError(f"{text}: index outside 0 … {len(data) - 1}")
            return data[index]
        if key not in self.memory.variables:
            raise KeyError(f"no variable '{text}'")
        return self.memory.variables[key]
