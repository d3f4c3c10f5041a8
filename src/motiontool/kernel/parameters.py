"""The controller's live parameter values (19-xx, 32-xx, 33-xx, 34-xx) as the program sees them.

Values are the raw integers GET/SET use: a parameter with conversion index -3 (RAMPMIN 1.000 s) reads 1000.
SET changes of 32/33-xx hold only while the program runs (CR 3896-3899, DG 7647): the controller takes a
snapshot at program start and restores it at the end unless SAVE AXPARS/GLBPARS stored them.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from motiontool.kernel.errors import ControllerError
from motiontool.paramdb import Parameter, ParameterDatabase, ParameterError, database


def raw_value(parameter: Parameter, value: int | float) -> int:
    """Display value → raw integer (RAMPMIN 1.000 s → 1000 with conversion index -3)."""
    return parameter.to_raw(value)


PRGPAR_INDEX = 3380


def is_user_parameter(index: int) -> bool:
    return index // 100 == 19


def is_global_parameter(index: int) -> bool:
    """33-5x … 33-9x: I/O configuration, the global parameters and the MCO port settings (decision K50)."""
    return index // 100 == 33 and index % 100 >= 50


def is_axis_parameter(index: int) -> bool:
    """32-xx and 33-0x … 33-4x; the global parameters are 33-5x … 33-9x (I/O configuration, global, MCO port; DG
    2808 "the functions of the inputs and outputs and the standard parameters … in 33-5* and 33-8*", decision K47)."""
    return index // 100 == 32 or (index // 100 == 33 and index % 100 < 50)


class ParameterStore:
    def __init__(self, db: ParameterDatabase | None = None):
        self.db = db or database()
        self.values: dict[int, int] = {p.index: raw_value(p, p.default) for p in self.db}
        self.saved: dict[int, int] = dict(self.values)   # what survives a program end (EPROM)
        self.readouts: dict[int, Callable[[], int]] = {}  # 34-xx are computed by the controller
        self.on_change: Callable[[int, int, str], None] | None = None  # (index, value, source)

    def parameter(self, key: int | str) -> Parameter:
        try:
            return self.db.get(key)
        except ParameterError:
            raise ControllerError(112, f"parameter {key}") from None

    def get(self, key: int | str) -> int:
        p = self.parameter(key)
        read = self.readouts.get(p.index)
        return read() if read else self.values[p.index]

    def set(self, key: int | str, value: int, source: str = "program") -> None:
        """SET from the program ("program") or a write through a link ("link", which fires ON PARAM)."""
        p = self.parameter(key)
        if p.read_only or p.index // 100 == 34:
            raise ControllerError(112, f"{p.label} is read-only")
        # DG 7782-7795: the controller does not check ranges for SET; a link write is validated.
        if source != "program":
            try:
                p.validate(value if not p.conversion_index else value * 10 ** p.conversion_index)
            except ParameterError as exc:
                raise ControllerError(183, str(exc)) from None
        self.values[p.index] = int(value)
        # A write from the IDE/LCP is the controller's value, not a program's SET. 33-80 PRGPAR is set by a
        # program for the time after its end (DG 2768-2772: "if Activated Program Number is not reset, then
        # the current program will be executed repeatedly"), so it does not revert either (K22).
        if source != "program" or p.index == PRGPAR_INDEX:
            self.saved[p.index] = int(value)
        if self.on_change:
            self.on_change(p.index, int(value), source)

    def __getitem__(self, name: str) -> int:
        """Fast access by code name inside the kernel: params["KPROP"]."""
        return self.values[self.db.get(name).index]

    def save(self, which: Callable[[int], bool] | Iterable[int]) -> None:
        """SAVE AXPARS / GLBPARS / USRPARS: keep the current values of the parameters `which` selects past the
        program — a predicate on the parameter index, or parameter groups such as (19, 32, 33)."""
        if callable(which):
            chosen = [index for index in self.values if which(index)]
        else:
            groups = frozenset(which)
            chosen = [index for index in self.values if index // 100 in groups]
        for index in chosen:
            self.saved[index] = self.values[index]

    def restore(self) -> None:
        """Program end: SET values that were not saved go back."""
        for index, value in self.saved.items():
            if index // 100 in (32, 33):
                self.values[index] = value
