"""Controller array memory: the DIM arrays, shared by all programs and identified by position (DG 6449)."""

from __future__ import annotations

from motiontool.kernel.errors import ControllerError
from motiontool.kernel.vm import ArrayRef

MAX_ARRAY_ELEMENTS = 1_000_000  # simulator's array memory (elements); error 175 beyond it


class ArrayMemory:
    def __init__(self) -> None:
        self.arrays: list[ArrayRef] = []

    def dim(self, index: int, name: str, dims: list[int]) -> ArrayRef:
        """The index-th DIM of a program: the stored array at that position, or a new one appended.

        C:1024-1041: a program may DIM a prefix of the stored arrays; sizes must match (176); new arrays
        are appended at the end (170 if the program skips positions).
        """
        size = dims[0] * (dims[1] if len(dims) > 1 else 1)
        if index < len(self.arrays):
            stored = self.arrays[index]
            if len(stored) != size:
                raise ControllerError(176, f"DIM {name}[{size}] but array {index + 1} in the controller has "
                                           f"{len(stored)} elements")
            stored.name = name
            stored.dims = list(dims)
            return stored
        if index > len(self.arrays):
            raise ControllerError(170, f"DIM {name} is array {index + 1}, the controller has {len(self.arrays)}")
        if sum(len(a) for a in self.arrays) + size > MAX_ARRAY_ELEMENTS:
            raise ControllerError(175, f"no memory for {name}[{size}]")
        array = ArrayRef(name, size, list(dims))
        self.arrays.append(array)
        return array

    def delete(self) -> None:
        """DELETE ARRAYS / Controller → Reset → Arrays. CR 1003-1005: "If DELETE ARRAYS is carried out after a DIM
        assignment in the program, it is then no longer possible to access the array elements": a DIM array the
        program holds keeps no element, so every index is outside it (171, decision K119)."""
        for array in self.arrays:
            array.data = []
        self.arrays.clear()
