"""A parameter's value in a PWE, as master and slave both read and write it (docs/protocols/fc.md "Parameters").

Word data types (Uint8/Uint16/Int8/Int16) travel as words (16 bits), the others as double words (32 bits); Int types
are two's complement. A word parameter whose value does not fit 16 bits (a program may SET any value, DG
7782-7795) travels as a double word.
"""

from __future__ import annotations

from motiontool.comms.fc.telegram import AK_VALUE_DWORD, AK_VALUE_WORD
from motiontool.paramdb import Parameter

WORD_TYPES = ("Uint8", "Uint16", "Int8", "Int16")


def to_pwe(p: Parameter, value: int) -> tuple[int, int]:
    """(AK of the answer, PWE) for a parameter's value: AK 1 (word) or AK 2 (double word)."""
    signed = p.data_type.startswith("Int")
    if p.data_type in WORD_TYPES and (-0x8000 <= value <= 0x7FFF if signed else 0 <= value <= 0xFFFF):
        return AK_VALUE_WORD, value & 0xFFFF
    return AK_VALUE_DWORD, value & 0xFFFFFFFF


def from_pwe(p: Parameter, pwe: int, *, word: bool) -> int:
    """A PWE as the parameter's value: a word holds 16 bits, a double word 32; Int types are two's complement."""
    bits = 16 if word else 32
    value = pwe & ((1 << bits) - 1)
    if p.data_type.startswith("Int") and value >> (bits - 1):
        value -= 1 << bits
    return value
