"""The Array Editor's list: every controller array element and parameter as a row with a pending value, the
controller's value and the template's name, limits and default (ide-spec 5.1-5.30).  Qt-free; the controller
is reached only through a comms Link.

Item identities (docs/formats/zba.md): User = application parameter 19-n, Index n (0..89); Global, Axis 1 and
Proc 1 = the parameter number without its dash as Index (3260 is 32-60 KPROP); Array k = DIM array k (0-based),
Index = element (1-based, as in APOSS).  Parameter values are display values (RAMPMIN 1.000 s), as in the
parameter database.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass, replace

from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError
from motiontool.formats.zba import Record, ZbaFile
from motiontool.paramdb import Parameter, database

READ_ONLY_KINDS = ("Proc", "System")


def parameter_record(p: Parameter) -> Record:
    """The row definition of a parameter from the parameter database."""
    number = int(p.number.replace("-", ""))
    if p.number.startswith("19-"):
        kind, array, index = "User", None, number - 1900
    elif p.number.startswith("34-"):
        kind, array, index = "Proc", 1, number
    elif p.number.startswith(("33-8", "33-9")):
        kind, array, index = "Global", None, number
    else:
        kind, array, index = "Axis", 1, number
    return Record(kind, array, index, p.name or "", None,
                  None if kind == "User" else p.default, p.minimum, p.maximum, f"{p.number} {p.description}",
                  not p.read_only)


def array_of(record: Record) -> int:
    """The array number k of an Array record (parse_zba requires it for that kind, add_array gives it)."""
    assert record.kind == "Array" and record.array is not None, record
    return record.array


def parameter_of(record: Record) -> Parameter | None:
    db = database()
    if record.kind == "User" and 0 <= record.index <= 99:
        key = f"19-{record.index:02d}"
    elif record.kind in ("Global", "Axis", "Proc") and 1000 <= record.index <= 9999:
        key = f"{record.index // 100:02d}-{record.index % 100:02d}"
    else:
        return None
    return db.get(key) if key in db else None


@dataclass
class ControllerValues:
    """What Read from controller asked the link: its arrays, the parameter rows offered and the values read."""

    arrays: list
    records: list[Record]
    live: dict[tuple, int | float]


def fetch_controller(link: Link, parameters: bool = True) -> ControllerValues:
    """Every array and parameter value of the controller; link requests only, so it may run on a thread."""
    live: dict[tuple, int | float] = {}
    arrays = link.list_arrays()
    for info in arrays:
        for i, value in enumerate(link.read_array(info.index), start=1):
            live[("Array", info.index, i)] = value
    records = []
    for p in database():
        if not parameters and not p.number.startswith("19-"):
            continue  # "Array Editor parameter support" off: arrays and user parameters only (DG L4082)
        record = parameter_record(p)
        records.append(record)
        with contextlib.suppress(LinkError):  # a parameter this controller lacks stays blank
            live[record.key] = p.from_raw(link.read_parameter(p.number))
    return ControllerValues(arrays, records, live)


@dataclass
class Row:
    record: Record
    controller: int | float | None = None   # the live value; None = blank (offline or not on the controller)
    pending: int | float | None = None      # the user's value; None = blank (nothing will be written)
    exists: bool = True                     # the item exists on the controller (else green, read-only)

    @property
    def heading(self) -> bool:
        return self.record.kind == "Group"

    @property
    def writable(self) -> bool:
        return not self.heading and self.record.rw and self.exists and self.record.kind not in READ_ONLY_KINDS

    @property
    def differs(self) -> bool:
        """Shown red: the pending value is not what the controller has (ide-spec 5.12)."""
        return self.pending is not None and self.pending != self.controller

    @property
    def problem(self) -> str | None:
        return None if self.pending is None else self.record.check(self.pending)

    def selection_names(self) -> tuple[str, ...]:
        """The Array Selection Box entries that show this row (ide-spec 5.16, 5.35)."""
        r = self.record
        if r.kind == "Group":
            code = r.array if r.array is not None else -1
            if code >= 0:
                return (str(code),)
            return {-1: ("*",), -2: ("User",), -3: ("Global",), -4: ("System",)}.get(
                code, (f"Axis {-code - 100}",) if -200 < code <= -101 else
                (f"Temp {-code - 200}",) if -300 < code <= -201 else (f"Proc {-code - 300}",))
        if r.kind == "Array":
            return (str(r.array),)
        if r.kind in ("Axis", "Temp", "Proc"):
            return (f"{r.kind} {r.array}",)
        return (r.kind,)


class ArrayList:
    """All rows plus the operations of the editor's toolbar."""

    def __init__(self) -> None:
        self.rows: list[Row] = []
        self.template: ZbaFile | None = None   # "with file" mode when set (ide-spec 5.28/5.29)
        self.read_time = ""
        self.structure_changed = False         # arrays added/deleted: Write replaces the array memory

    # --- what to show ----------------------------------------------------------------------------------
    def selections(self) -> list[str]:
        names = ["All"]
        for row in self.rows:
            for name in row.selection_names():
                if name != "*" and name not in names:
                    names.append(name)
        return names

    def visible(self, selection: str = "All") -> list[int]:
        return [i for i, row in enumerate(self.rows)
                if selection == "All" or selection in row.selection_names() or "*" in row.selection_names()]

    # --- controller ------------------------------------------------------------------------------------
    def read_controller(self, link: Link, parameters: bool = True, now: str = "") -> None:
        """Read every array and parameter. Without a template the rows are the controller's items; with one,
        the template's rows get the controller's values and items missing on the controller turn green."""
        self.take_controller(fetch_controller(link, parameters), now)

    def take_controller(self, read: ControllerValues, now: str = "") -> None:
        """The rows of what fetch_controller read (the GUI thread's half of Read from controller)."""
        arrays, live = read.arrays, read.live
        if self.template is None:
            rows = [Row(r) for r in read.records]
            rows += [Row(Record("Array", info.index, i, info.name if i == 1 else ""))
                     for info in arrays for i in range(1, info.size + 1)]
            self.rows = rows
        for row in self.rows:
            if row.heading:
                continue
            row.exists = row.record.key in live
            row.controller = live.get(row.record.key)
        self.read_time = now
        self.structure_changed = False

    def write_controller(self, link: Link) -> list[str]:
        """Write every non-blank pending value of all arrays (shown or not); blank values leave the
        controller's value alone (ide-spec 5.19). Returns the problems (the rest is written)."""
        problems = []
        for row in self.rows:
            if row.pending is not None and row.problem:
                problems.append(f"{self.label(row)}: {row.problem}")
        if problems:
            return problems  # nothing is written while a value is invalid
        arrays: dict[int, list[Row]] = {}
        for row in self.rows:
            if row.record.kind == "Array":
                arrays.setdefault(array_of(row.record), []).append(row)
        if self.structure_changed:
            link.restore_arrays([
                (rows[0].record.name or f"array{k}",
                 [int(r.pending if r.pending is not None else (r.controller or 0)) for r in rows])
                for k, rows in sorted(arrays.items())])
        else:
            for k, rows in sorted(arrays.items()):
                if any(r.pending is not None and r.writable for r in rows):
                    values = link.read_array(k)
                    for r in rows:
                        if r.pending is not None and r.writable and 1 <= r.record.index <= len(values):
                            values[r.record.index - 1] = int(r.pending)
                    link.write_array(k, values)
        for row in self.rows:
            if row.pending is None or row.record.kind == "Array" or not row.writable:
                continue
            p = parameter_of(row.record)
            if p is None:
                continue
            try:
                link.write_parameter(p.number, p.to_raw(row.pending))
            except LinkError as exc:
                problems.append(f"{self.label(row)}: {exc}")
        return problems

    # --- editing ---------------------------------------------------------------------------------------
    @staticmethod
    def label(row: Row) -> str:
        r = row.record
        where = f"Array {r.array}[{r.index}]" if r.kind == "Array" else (
            f"{r.kind} {r.index}" if r.array is None else f"{r.kind} {r.array} {r.index}")
        return f"{where} {r.name}".strip()

    def set_value(self, i: int, value: int | float | None) -> None:
        row = self.rows[i]
        if not row.writable:
            raise ValueError(f"{self.label(row)} is read-only")
        self.rows[i].pending = value

    def set_to_default(self, indices) -> None:
        for i in indices:
            row = self.rows[i]
            if row.writable and row.record.default is not None:
                row.pending = row.record.default

    def set_to_controller(self, indices) -> None:
        for i in indices:
            row = self.rows[i]
            if row.writable and row.controller is not None:
                row.pending = row.controller

    def add_array(self, size: int, name: str = "") -> int:
        """Expert mode: a new array after the last one, created on the controller at Write (ide-spec 5.27)."""
        if size < 1:
            raise ValueError("an array needs at least one element")
        k = 1 + max((array_of(r.record) for r in self.rows if r.record.kind == "Array"), default=-1)
        self.rows += [Row(Record("Array", k, i, name if i == 1 else ""), None, 0, True) for i in range(1, size + 1)]
        self.structure_changed = True
        return k

    def delete_array(self, k: int) -> None:
        """Expert mode: remove array k; the following arrays move down (no gaps, ide-spec 5.27)."""
        rows = []
        for row in self.rows:
            r = row.record
            if r.kind == "Array" and r.array == k:
                continue
            if r.kind == "Array" and array_of(r) > k:
                row = replace(row, record=replace(r, array=array_of(r) - 1))
            rows.append(row)
        self.rows = rows
        self.structure_changed = True

    # --- templates -------------------------------------------------------------------------------------
    def load_template(self, zba: ZbaFile) -> None:
        """Browse a .zba: only its items are shown; values come from the file until a controller is read."""
        self.template = zba
        self.rows = [Row(r, None, r.value, True) for r in zba.records]
        self.read_time = zba.date

    def to_zba(self) -> ZbaFile:
        """Save File: the list with the pending values (the Controller column is never stored)."""
        records = [r.record if r.heading else replace(r.record, value=r.pending) for r in self.rows]
        return ZbaFile(self.read_time, list(self.template.widths) if self.template else [], records)
