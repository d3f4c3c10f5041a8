"""The properties every compiled input must have (check_compile), and where a crash happened."""

from __future__ import annotations

import traceback
import zlib
from collections import Counter

from motiontool.aposs.driver import CompileResult, compile_source
from motiontool.aposs.image import ProgramImage

from .vocabulary import INPUT_PATH


class PropertyViolation(AssertionError):
    """compile_source returned, but its result breaks a property (a bug, like a crash)."""


def check_compile(text: str, path: str = INPUT_PATH, must_compile: bool = False) -> CompileResult:
    """Compile `text` and check the properties; exceptions of the compiler propagate, PropertyViolation if a
    property fails. With must_compile the text must compile without errors; every fourth such text (chosen by a
    checksum, so the choice is reproducible) is also compiled as a debug build."""
    if must_compile and zlib.crc32(text.encode("utf-8", "surrogatepass")) % 4 == 0:
        check_compile_once(text, path, must_compile=True, debug=True)
    return check_compile_once(text, path, must_compile)


def check_compile_once(text: str, path: str, must_compile: bool, debug: bool = False) -> CompileResult:
    result = compile_source(text, path, debug=debug)

    def fail(why: str) -> None:
        shown = "\n".join(d.format() for d in result.diagnostics)
        raise PropertyViolation(f"{why}\n--- diagnostics:\n{shown}")

    lines = text.count("\n") + 1
    for d in result.diagnostics:
        if d.severity not in ("error", "warning", "note"):
            fail(f"unknown severity {d.severity!r}")
        d.format()
        if d.loc.file == path and not (1 <= d.loc.line <= lines + 1 and d.loc.col >= 1):
            fail(f"diagnostic outside the source ({lines} lines): {d.loc.line}:{d.loc.col}: {d.message}")
    if result.ok:
        if result.image is None:
            fail("no error but no image")
        again = ProgramImage.from_bytes(result.image.to_bytes())
        if again != result.image:
            fail("ProgramImage.from_bytes(image.to_bytes()) != image")
    elif result.image is not None:
        fail("errors but an image")
    if must_compile and not result.ok:
        fail("a valid program did not compile")
    return result


def crash_site(exc: BaseException) -> tuple[str, str, str, str]:
    """Where a crash happened: (exception type, file inside the motiontool package, function, source line) of the
    innermost motiontool frame; for a RecursionError the frame that recurses (the most frequent one)."""
    frames = traceback.extract_tb(exc.__traceback__)
    ours = [f for f in frames if "/motiontool/" in f.filename.replace("\\", "/")] or frames
    frame = ours[-1]
    if isinstance(exc, RecursionError):
        counts = Counter((f.filename, f.name, f.line) for f in ours)
        top = counts.most_common(1)[0][0]
        frame = next(f for f in ours if (f.filename, f.name, f.line) == top)
    filename = frame.filename.replace("\\", "/")
    return type(exc).__name__, filename.split("/motiontool/")[-1], frame.name, (frame.line or "").strip()


def last_frames(exc: BaseException, count: int = 4) -> str:
    frames = traceback.extract_tb(exc.__traceback__)[-count:]
    text = "".join(traceback.format_list(frames))
    return text + f"{type(exc).__name__}: {str(exc)[:300]}"

