"""The APC manual's DPL programs (seed 004 §6.4, §7.1-§7.6) as test fixtures, and the proof that each fixture is
the manual's text except for the OCR repairs its header lists.

A fixture starts with a comment block:

    // <title>
    // Source: seed 004 L5105-L5229[, L…-L…]
    // OCR repairs:
    //   L5146: <seed text> => <repaired text>   ~~ optional reason
    //   after L5165: + <inserted line>          ~~ optional reason
    //   L5120: - <deleted line>                  ~~ optional reason
    // Not repaired: … (free text, optional)

then a blank line and the program. `repairs()` diffs the seed's lines (page headers and footers, Markdown fences,
blank lines and indentation left out) against the program's lines; the test demands that the list in the header
is exactly that diff. Run this module with a fixture path to print the list for a new or changed fixture.
"""

from __future__ import annotations

import difflib
import re
import sys
from pathlib import Path

SEED = Path("/work/shared/seeds/004_16445ecb4420dbd7.txt")   # the vendor manual (OCR text), where at hand
PROGRAMS = Path(__file__).parent / "programs"
EXCERPT = PROGRAMS / "seed-004-lines.txt"                      # the seed's lines the fixtures come from
_FURNITURE = re.compile(r"^\s*(?:[ıIĺ|]\s+)?(?:Using Thi|Manual\s+Information|Manual\s+Info|```|Using This)")
_SOURCE = re.compile(r"L(\d+)-L(\d+)")
_ENTRY = re.compile(r"^//\s{3}(.*?)(?:\s+~~\s.*)?$")


def seed_lines() -> dict[int, str]:
    """Seed line number → text, from the excerpt kept with the fixtures."""
    lines = {}
    for row in EXCERPT.read_text(encoding="utf-8").split("\n"):
        if row and not row.startswith("#"):
            number, _, text = row.partition("\t")
            lines[int(number)] = text
    return lines


def seed_code(ranges: list[tuple[int, int]]) -> list[tuple[int, str]]:
    """(line number, text without indentation) of the seed lines in `ranges`, without page furniture."""
    lines = seed_lines()
    out = []
    for first, last in ranges:
        for n in range(first, last + 1):
            text = lines[n].strip()
            if text and not _FURNITURE.match(text):
                out.append((n, text))
    return out


def split(fixture: str) -> tuple[list[str], list[str]]:
    """(header comment lines, program lines) of a fixture's text."""
    lines = fixture.split("\n")
    blank = lines.index("")
    return lines[:blank], lines[blank + 1:]


def source_ranges(header: list[str]) -> list[tuple[int, int]]:
    line = next(h for h in header if h.startswith("// Source:"))
    return [(int(a), int(b)) for a, b in _SOURCE.findall(line)]


def listed_repairs(header: list[str]) -> list[str]:
    """The repair entries of the header, reasons removed."""
    start = next(i for i, h in enumerate(header) if h.startswith("// OCR repairs:"))
    out = []
    for h in header[start + 1:]:
        m = _ENTRY.match(h)
        if not m:
            break
        out.append(m.group(1).rstrip())
    return out


def repairs(ranges: list[tuple[int, int]], program: list[str]) -> list[str]:
    """Every difference between the seed's text and the program, one entry per changed run of lines."""
    seed = seed_code(ranges)
    old = [t for _, t in seed]
    new = [t.strip() for t in program if t.strip()]
    entries = []
    matcher = difflib.SequenceMatcher(a=old, b=new, autojunk=False)
    for tag, a1, a2, b1, b2 in matcher.get_opcodes():
        if tag == "equal":
            continue
        span = _span([n for n, _ in seed[a1:a2]], ranges)
        if tag == "insert":
            where = f"after L{seed[a1 - 1][0]}" if a1 else "before the first line"
            entries += [f"{where}: + {line}" for line in new[b1:b2]]
        elif tag == "delete":
            entries.append(f"{span}: - {' | '.join(old[a1:a2])}")
        else:
            entries.append(f"{span}: {' | '.join(old[a1:a2])} => {' | '.join(new[b1:b2])}")
    return entries


def _span(numbers: list[int], ranges: list[tuple[int, int]]) -> str:
    """"L5146", "L5146-L5150", or "L4793,L4810" when the lines come from different source ranges."""
    if len(numbers) == 1:
        return f"L{numbers[0]}"
    pieces = []
    for first, last in ranges:
        inside = [n for n in numbers if first <= n <= last]
        if inside:
            pieces.append(f"L{inside[0]}" if len(inside) == 1 else f"L{inside[0]}-L{inside[-1]}")
    return ",".join(pieces)


def fixture_paths() -> list[Path]:
    return sorted(PROGRAMS.glob("*.dpl"))


if __name__ == "__main__":  # print the repair list of a fixture (paste it into the header, add reasons)
    header, program = split(Path(sys.argv[1]).read_text(encoding="utf-8"))
    for entry in repairs(source_ranges(header), program):
        print(f"//   {entry}")
