"""Program text as both compilers read it: bounded (never a device, decisions R4), UTF-8 with or without a BOM,
else Latin-1 (old APOSS files), CRLF and CR line ends as LF."""

from __future__ import annotations

from pathlib import Path

from motiontool.fileio import read_bytes


def source_text(data: bytes) -> str:
    """Program bytes as text: UTF-8 (a BOM dropped), else Latin-1, line ends normalised."""
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = data.decode("latin-1")
    return text.replace("\r\n", "\n").replace("\r", "\n")


def read_source(path: Path | str, limit: int, what: str) -> str:
    """Read a program file of at most `limit` bytes; `what` names it in the OSError beyond that."""
    return source_text(read_bytes(path, limit, what))
