"""The cross reference file `<program>.ad$` that Syntax Check writes beside the program (DG 2483, 5588; the
untitled program's is `temp.ad$`, DG 6268). Our own versioned text format, docs/formats/ad.md: the program's
variables, arrays, subprograms and functions with their slots and entry points, the statement table
(offset → file:line:col) and the compiler's messages. It is written even when the program has errors, with
the messages only, so the file always says what the last check found."""

from __future__ import annotations

from pathlib import Path

from motiontool.aposs.driver import CompileResult
from motiontool.fileio import atomic_write_text

FORMAT = "# motiontool cross reference, format 1"


def xref_path(program: Path | None, fallback_dir: Path) -> Path:
    """`<name>.ad$` beside a saved program, else `temp.ad$` in `fallback_dir`."""
    if program is None:
        return Path(fallback_dir) / "temp.ad$"
    return Path(program).with_suffix(".ad$")


def xref_text(result: CompileResult, source: str) -> str:
    lines = [FORMAT, f"source {source}"]
    image = result.image
    if image is not None:
        lines.append(f"program {image.name} debug={int(image.debug)} instructions={len(image)}")
        lines += [f"file {n} {name}" for n, name in enumerate(image.files)]
        lines += [f"variable {slot} {v.name} {v.type}" for slot, v in enumerate(image.globals)
                  if not v.name.startswith("$")]
        lines += [f"array {slot} {v.name} {v.type} {'x'.join(map(str, v.dims))}"
                  for slot, v in enumerate(image.arrays)]
        lines += [f"dim {slot} {v.name} {'x'.join(map(str, v.dims))}" for slot, v in enumerate(image.dims)]
        lines += [f"subprogram {s.entry} {s.name}" for s in image.subprograms]
        lines += [f"function {f.entry} {f.name} {f.type}" for f in image.functions]
        lines += [f"line {e.pc} {e.file} {e.line} {e.col}" for e in image.lines]
    lines += [f"{d.severity} {d.loc}: {d.message}" for d in result.diagnostics]
    lines.append(f"end {len(result.errors)} error(s) {len(result.diagnostics) - len(result.errors)} warning(s)")
    return "\n".join(lines) + "\n"


def write_xref(path: Path, result: CompileResult, source: str) -> None:
    atomic_write_text(path, xref_text(result, source))
