"""Fuzz the APOSS compiler with generated programs: no input may raise, every input only gives diagnostics.

Run from the repository root:

    .venv/bin/python benchmarks/fuzz_compiler.py [--cases 100000] [--seed 305] [--jobs N]

Prints ``name: value unit`` lines (``fuzz_cases``, ``fuzz_rate``, ``fuzz_crashes`` …). Exit status 1 if any input
raised an exception or broke a property; then each distinct crash site goes to stderr with its count, a shrunk
reproducer and the last frames of the traceback. The cases are split into units of CHUNK cases with their own
seeds, so the cases (and the findings) do not depend on --jobs.

The generators are plain functions of a ``random.Random``-like object ``r`` (only ``r.random()``,
``r.randint()`` and ``r.choice()`` are used). This script drives them with ``random.Random``;
``tests/aposs/test_fuzz.py`` drives the very same functions with hypothesis-drawn bytes, which shrink.

Generators (share of the benchmark's cases in GENERATORS):
  token_stream     text from a vocabulary of keywords, command names, identifiers, numbers (decimal, hex, octal,
                   doubles, characters), strings, operators, preprocessor lines, comments, junk characters and
                   newlines;
  mutated_example  an example program of tests/aposs/manual with 1-4 random edits (lines deleted, duplicated,
                   swapped, moved or borrowed; characters deleted or inserted; tokens replaced, deleted, duplicated
                   or swapped; the text truncated);
  semantic_soup    a grammar-generated program with wrong names, types, arities, constants and definitions
                   sprinkled in; most stay parseable, so they reach the checks and the code generator;
  valid_program    a grammar-generated program that must compile without errors (every fourth also as a debug
                   build);
  deep_nesting     very deep or very long constructs (parentheses, unary chains, blocks, macros, lines).

Properties (check_compile): compile_source returns; every diagnostic has a known severity, formats, and - when it
is in the input file - 1 <= line <= lines + 1 and col >= 1; with no error there is an image and
ProgramImage.from_bytes(image.to_bytes()) == image, with an error there is none.
"""

from __future__ import annotations

import argparse
import os
import random
import re
import sys
import time
import traceback
import zlib
from collections import Counter
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from motiontool.aposs.commands import command_table
from motiontool.aposs.driver import CompileResult, compile_source
from motiontool.aposs.image import ProgramImage

REPO = Path(__file__).resolve().parents[1]
EXAMPLES_DIR = REPO / "tests" / "aposs" / "manual"
# The name the generated text is compiled under: `#include "D12_hello.m"` then finds a real file next to it.
INPUT_PATH = str(EXAMPLES_DIR / "fuzz_input.m")
EXAMPLES = {p.name: p.read_text(encoding="utf-8") for p in sorted(EXAMPLES_DIR.glob("*.m"))}
EXAMPLE_NAMES = sorted(EXAMPLES)

TABLE = command_table()
COMMAND_NAMES = TABLE.names()
EXTRA_WORDS = ["INT", "ERROR", "PERIOD", "PARAM", "COMBIT", "STATBIT", "KEYPRESSED", "CANMSG", "CANINPUT",
               "DELETE", "SETOUT", "TOIN", "ALL", "X", "x", "long", "double", "return", "mod", "rnd", "exp", "not",
               "and", "or", "pi", "defined", "__LINE__", "__FILE__", "__DATE__", "__TIME__", "KPROP", "VELMAX",
               "POSERR", "SYNCPOSOFFS", "ARRAYS", "AXPARS", "CURVEPOS", "b1", "w2", "sb", "uw", "i3", "MOTOR",
               "ON", "OFF", "SAVE", "GOSUB", "THEN", "DO", "X59/3", "x56/1", "X59/", "DYNMEM"]
IDENTIFIERS = ["a", "b", "c", "i", "cnt", "arr", "buf", "main", "sub1", "sub2", "f", "g", "SQUARE", "VALUE", "_t",
               "v1", "A", "next_in", "test", "field", "myarray", "x1", "res", "tmp", "M", "F"]
EDGE_NUMBERS = ["0", "00", "08", "09", "0x", "0X1f", "0x0", "0xFFFFFFFF", "0x7FFFFFFF", "0x80000000", "0x100000000",
                "2147483647", "2147483648", "4294967295", "4294967296", "99999999999999999999", "1e400", "1.0e308",
                "1e-400", "0.0", "1.", ".5", "1.5e", "1e", "0777", "0100", "0.5", "1_000", "12abc", "0b101", "1e3",
                "-0.0", "1.7976931348623157e308", "5e-324", "'A'", "' '", "'''", "'AB'", "''"]
OPERATORS = ["+", "-", "*", "%", "^", "&", "|", "~", "<", ">", "=", "(", ")", "[", "]", "{", "}", ",", ";", ":",
             ".", "!", "<<", ">>", "==", "!=", "<=", ">=", "++", "--", "(long)", "(double)", "[]", "()", "(", ")",
             "=", ",", "(", ")"]
JUNK = ["@", "$", "?", "`", "\\", "#", "\u2013", "\u2014", "\u201c", "\u201d", "\u2018", "\u2019", "\u00a0", "\x00",
        "\t", "\r", "\f", "\v", "\u00e4", "\u20ac", "\U0001f600", "\ufeff", "\u2028", "\x85", "\x1c"]
STRINGS = ['"hello"', '""', '"a, b; c"', '"unterminated', '"\u00fcn\u00efcode \u20ac"', '"x = "', '"/* not a comment"',
           '"// nor this"', '"VALUE"', '"\\"', "'A'", "'x'", "'AB'", "''", '"tab\there"']
COMMENTS = ["// comment", "/* c */", "/* multi\nline\ncomment */", "/*", "*/", "/* a /* b */", "//", "/**/",
            "/* unterminated\n", "// \\", "/* multi\n /* nested */"]
INCLUDE_NAMES = ['"D12_hello.m"', '"F_D22_preprocessor.m"', '"C07_enctg_absolute_position.m"', "<README.md>",
                 '"nonexistent.m"', "D12_hello.m", '"../examples/D12_hello.m"', '"fuzz_input.m"', "<>", '""', "",
                 '"D12_hello.m', "<D12_hello.m>", '"."', '".."']
PARAM_NAMES = ["KPROP", "KDER", "VELMAX", "POSERR", "SYNCPOSOFFS", "ENCODER", "PRGPAR", "HOME_VEL"]
SYSVARS_LONG = [c.name for c in TABLE if c.kind == "sysvar" and c.returns == "long"]
MATH_DOUBLE = ["sqrt", "sin", "cos", "tan", "atan", "grad", "rad", "round", "fabs"]


# --- small helpers over r --------------------------------------------------------------------------------------
def chance(r, p: float) -> bool:
    return r.random() < p


def weighted(r, options: list[tuple[int, object]]):
    """One of the options, chosen with the given integer weights."""
    total = sum(w for w, _ in options)
    k = r.randint(1, total)
    for w, value in options:
        k -= w
        if k <= 0:
            return value
    raise AssertionError("unreachable")


def recase(r, word: str) -> str:
    """APOSS keywords and names are case-insensitive: write them in a random case."""
    k = r.randint(0, 5)
    if k == 0:
        return word.lower()
    if k == 1:
        return word.title()
    if k == 2:
        return "".join(c.lower() if r.randint(0, 1) else c.upper() for c in word)
    return word


# --- generator 1: random token streams ---------------------------------------------------------------------------
def number(r) -> str:
    k = r.randint(0, 9)
    if k == 0:
        return r.choice(EDGE_NUMBERS)
    if k <= 3:
        return str(r.randint(0, 1000))
    if k == 4:
        return str(r.randint(0, 1 << 33))
    if k == 5:
        return r.choice(["0x", "0X"]) + format(r.randint(0, 1 << 33), r.choice(["x", "X"]))
    if k == 6:
        return "0" + format(r.randint(0, 4096), "o")
    if k == 7:
        return f"{r.randint(0, 1000)}.{r.randint(0, 999)}"
    if k == 8:
        return f"{r.randint(0, 9)}.{r.randint(0, 9)}{r.choice('eE')}{r.choice(['', '+', '-'])}{r.randint(0, 400)}"
    return "'" + chr(r.randint(32, 126)) + "'"


def identifier(r) -> str:
    if chance(r, 0.7):
        return r.choice(IDENTIFIERS)
    first = r.choice("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_")
    rest = "".join(r.choice("abcdefghijklmnopqrstuvwxyz_0123456789") for _ in range(r.randint(0, 8)))
    return first + rest


def keyword(r) -> str:
    word = r.choice(COMMAND_NAMES) if chance(r, 0.75) else r.choice(EXTRA_WORDS)
    return recase(r, word)


def small_tokens(r, n: int) -> str:
    """A few tokens joined by blanks (bodies of #define and #if lines)."""
    return " ".join(weighted(r, [(3, identifier), (3, number), (3, lambda r: r.choice(OPERATORS)),
                                 (2, keyword), (1, lambda r: r.choice(STRINGS))])(r) for _ in range(n))


def directive(r) -> str:
    """A preprocessor line (it must start a line, so it comes with its newlines)."""
    name = r.choice(["A", "B", "F", "SQUARE", "VALUE", "M", "a", "POSA", "__LINE__", "X1", "1A"])
    k = r.randint(0, 17)
    if k == 0:
        text = f"define {name} {small_tokens(r, r.randint(0, 4))}"
    elif k == 1:
        params = ",".join(r.choice(["x", "y", "z", "x", "", "1", "x y"]) for _ in range(r.randint(0, 3)))
        text = f"define {name}({params}) {small_tokens(r, r.randint(0, 5))}"
    elif k == 2:
        text = f"undef {r.choice([name, '', '1', name + ' junk'])}"
    elif k in (3, 4):
        text = f"if {small_tokens(r, r.randint(0, 4))}"
    elif k == 5:
        text = f"{r.choice(['ifdef', 'ifndef'])} {r.choice([name, '', name + ' x', '(' + name + ')'])}"
    elif k == 6:
        text = f"elif {small_tokens(r, r.randint(0, 3))}"
    elif k in (7, 8):
        text = r.choice(["else", "endif", "endif", "else junk"])
    elif k == 9:
        text = f"include {r.choice(INCLUDE_NAMES)}"
    elif k == 10:
        text = f"pragma {r.choice(['NOIMPLICIT', 'IMPLICIT', 'noimplicit', 'ONCE', ''])}"
    elif k == 11:
        text = r.choice(["DEBUG", "DEBUG on", "INCLUDE", "Define A 1", "IF 1", "", "  ", "error", "line 5", "1"])
    elif k == 12:
        text = f"if defined({name}) {r.choice(['', '&&', 'AND', '||'])} {small_tokens(r, r.randint(0, 2))}"
    elif k == 13:
        text = f"define {name} \\\n {small_tokens(r, r.randint(0, 3))}"
    elif k == 14:
        text = f"if defined {r.choice([name, '', '('])}"
    elif k == 15:
        text = f"define {name}({r.choice(['x', 'x,y', ''])} {small_tokens(r, 2)}"
    elif k == 16:
        text = f"if __LINE__ {r.choice(['>', '==', '%', 'mod'])} {r.choice(['0', '1', '0.0', 'x'])}"
    else:
        body = r.choice(["/* c */", "/* multi", "// c", '"str"'])
        text = f"define {name} {body} {small_tokens(r, 2)}"
    lead = r.choice(["", "", " ", "\t"])
    return f"\n{lead}#{text}\n"


TOKEN_KINDS = [
    (25, keyword), (15, identifier), (12, number), (20, lambda r: r.choice(OPERATORS)),
    (4, lambda r: r.choice(STRINGS)), (8, lambda r: "\n"), (3, lambda r: r.choice(COMMENTS)), (5, directive),
    (1, lambda r: r.choice(JUNK)), (1, lambda r: "\\\n"),
]
SEPARATORS = [(12, " "), (3, ""), (3, "\n"), (1, "\t"), (1, "\n\n"), (1, " \\\n"), (1, "\r\n")]


def token_stream(r) -> str:
    """Text built from APOSS tokens in random order (often line-shaped: keyword first, newline after)."""
    parts: list[str] = []
    for _ in range(r.randint(0, 60)):
        if chance(r, 0.15):  # start something statement-like
            parts.append("\n" + keyword(r) + " ")
        parts.append(weighted(r, TOKEN_KINDS)(r))
        parts.append(weighted(r, SEPARATORS))
    return "".join(parts)


# --- generator 2: mutated example programs -----------------------------------------------------------------------
_TOKEN_RE = re.compile(r'"[^"\n]*"|0[xX][0-9A-Fa-f]+|\d+\.\d+|\w+|//|/\*|\*/|<<|>>|==|!=|<=|>=|\+\+|--|\S')


def any_token(r) -> str:
    return weighted(r, [(4, keyword), (3, identifier), (3, number), (4, lambda r: r.choice(OPERATORS)),
                        (1, lambda r: r.choice(STRINGS)), (1, lambda r: r.choice(JUNK)),
                        (1, lambda r: r.choice(COMMENTS)), (1, lambda r: "\n"), (1, lambda r: "")])(r)


def mutate(r, text: str, donors: list[str] | None = None) -> str:
    """Apply 1-4 random edits to a program's text: lines deleted, duplicated, swapped, moved or taken from another
    program; characters deleted or inserted; a token replaced, deleted or duplicated; the text truncated."""
    for _ in range(r.randint(1, 4)):
        lines = text.split("\n")
        i, j = r.randint(0, len(lines) - 1), r.randint(0, len(lines) - 1)
        op = r.randint(0, 11)
        if op == 0:
            del lines[i]
        elif op == 1:
            lines.insert(i, lines[i])
        elif op == 2:
            lines[i], lines[j] = lines[j], lines[i]
        elif op == 3:
            lines.insert(j, lines.pop(i))
        elif op == 4 and donors:
            donor = r.choice(donors).split("\n")
            lines.insert(i, donor[r.randint(0, len(donor) - 1)])
        elif op in (5, 6):
            pos = r.randint(0, len(text))
            text = text[:pos] + text[pos + r.randint(1, 6):]
            continue
        elif op == 7:
            pos = r.randint(0, len(text))
            text = text[:pos] + any_token(r) + text[pos:]
            continue
        elif op in (8, 9, 10):
            line = lines[i]
            spans = [m.span() for m in _TOKEN_RE.finditer(line)]
            if spans:
                a, b = r.choice(spans)
                k = r.randint(0, 3)
                new = line[a:b] + " " + line[a:b] if k == 0 else "" if k == 1 else any_token(r)
                if k == 2 and len(spans) > 1:  # swap with another token of the same line
                    c, d = r.choice(spans)
                    if (c, d) != (a, b):
                        (a, b), (c, d) = sorted([(a, b), (c, d)])
                        lines[i] = line[:a] + line[c:d] + line[b:c] + line[a:b] + line[d:]
                        text = "\n".join(lines)
                        continue
                lines[i] = line[:a] + new + line[b:]
        elif op == 11:
            text = text[:r.randint(0, len(text))]
            continue
        text = "\n".join(lines)
    return text


def mutated_example(r) -> str:
    name = r.choice(EXAMPLE_NAMES)
    return mutate(r, EXAMPLES[name], [EXAMPLES[r.choice(EXAMPLE_NAMES)]])


# --- generators 3 and 4: grammar-generated programs ----------------------------------------------------------------
class _Scope:
    """Names visible to a statement: the globals plus, inside a function, its parameters and locals."""

    def __init__(self, unit: str, longs: list[str], doubles: list[str], arrays: list[str], funcs: list,
                 sub_index: int = -1, breakable: bool = False, labels: list[str] | None = None,
                 func=None):
        self.unit, self.longs, self.doubles, self.arrays, self.funcs = unit, longs, doubles, arrays, funcs
        self.sub_index, self.breakable, self.labels, self.func = sub_index, breakable, labels, func

    def inner(self, breakable: bool | None = None) -> _Scope:
        scope = _Scope(self.unit, self.longs, self.doubles, self.arrays, self.funcs, self.sub_index,
                       self.breakable if breakable is None else breakable, None, self.func)
        return scope


class ProgramGenerator:
    """Generates APOSS programs from the grammar of spec §3-§6.

    With loose=False every program must compile without errors (DIM first, pragma after it, declarations before
    use, functions declared before their calls, GOSUB only to later subprograms, BREAK only in loops and SWITCH,
    distinct CASE values, constants that fold without error). With loose=True a share of the choices is replaced
    by something wrong: unknown or misused names, wrong types and arities, bad constants, misplaced statements.
    """

    STATEMENTS = ["assign", "assign", "assign_double", "element", "bitset", "incdec", "print", "command",
                  "command", "gosub", "if", "if", "while", "repeat", "switch", "call", "copy", "label", "pseudo",
                  "ifdef", "exit"]

    def __init__(self, r, loose: bool = False, size: int = 1):
        self.r = r
        self.loose = loose
        self.size = size
        self.counter = 0
        self.chaos_rate = 0.08 if loose else 0.0
        # Loose programs mostly stay parseable, so that the checks and the code generator see them; some also get
        # parse errors and token-level edits.
        self.syntax_chaos = loose and chance(r, 0.3)

    def chaos(self) -> bool:
        return self.loose and chance(self.r, self.chaos_rate)

    def fresh(self, prefix: str) -> str:
        self.counter += 1
        return f"{prefix}{self.counter}"

    def kw(self, word: str) -> str:
        return recase(self.r, word)

    # --- the program ------------------------------------------------------------------------------------------
    def program(self) -> str:
        r = self.r
        out: list[str] = ["// generated by benchmarks/fuzz_compiler.py"]
        self.macros: list[tuple[str, int]] = []
        for _ in range(r.randint(0, 2)):
            name, value = self.fresh("M_K"), r.randint(1, 9)
            self.macros.append((name, value))
            out.append(f"#define {name} {value}")
        self.fmacro = self.fresh("M_SQ") if chance(r, 0.5) else None
        if self.fmacro:
            out.append(f"#define {self.fmacro}(x) ((x)*(x))")
        self.dims: dict[str, list[int]] = {}
        dim_decls = []
        for _ in range(r.randint(0, 3)):
            name = self.fresh("d_")
            if chance(r, 0.25):
                self.dims[name] = [r.randint(1, 5), r.randint(1, 5)]
                dim_decls.append(f"{name}[{self.dims[name][0]}][{self.dims[name][1]}]")
            else:
                size = r.randint(1, 50)
                self.dims[name] = [size]
                text = str(size)
                if self.macros and chance(r, 0.3):
                    text = self.macros[0][0]
                    self.dims[name] = [self.macros[0][1]]
                dim_decls.append(f"{name}[{text}]")
        if dim_decls:
            out.append(f"{self.kw('DIM')} " + ", ".join(dim_decls))
        self.noimplicit = chance(r, 0.3)
        if self.noimplicit:
            out.append("#pragma NOIMPLICIT")
        self.longs = [self.fresh("v_") for _ in range(r.randint(1, 4))]
        self.doubles = [self.fresh("x_") for _ in range(r.randint(0, 3))]
        self.garrays = {self.fresh("g_"): r.randint(1, 20) for _ in range(r.randint(0, 2))}
        decl = list(self.longs) + [f"{n}[{s}]" for n, s in self.garrays.items()]
        out.append(f"{self.kw('long')} " + ", ".join(decl))
        if self.doubles:
            out.append(f"{self.kw('double')} " + ", ".join(self.doubles))
        if not self.noimplicit:  # implicit LONG variables, created by their first assignment
            self.longs += [self.fresh("n_") for _ in range(r.randint(0, 2))]
        self.subs = [self.fresh("sub_") for _ in range(r.randint(0, 3))]
        # Functions: early ones are defined before the main code, late ones are declared there (prototype) and
        # defined after it; a body calls only functions with a smaller index.
        self.funcs: list[tuple[str, str, list[tuple[str, str, bool]], bool]] = []
        for _ in range(r.randint(0, 3)):
            params = [(r.choice(["long", "long", "double", "long[]"]), self.fresh("p_"), False)
                      for _ in range(r.randint(0, 3))]
            params = [(t.rstrip("[]"), n, t.endswith("[]")) for t, n, _ in params]
            self.funcs.append((self.fresh("fn_"), r.choice(["long", "double"]), params, chance(r, 0.5)))
        for name, type_, params, late in self.funcs:
            if late:
                shown = ", ".join(f"{t}{'[]' if a else ''} {self.fresh('q_')}" for t, _, a in params)
                out.append(f"{self.kw(type_)} {name}({shown}) ;")
        for k, f in enumerate(self.funcs):
            if not f[3]:
                out += self.function(k)
        self.arrays = list(self.dims) + list(self.garrays)
        main = _Scope("main", self.longs, self.doubles, self.arrays, self.funcs, labels=[])
        body: list[str] = []
        for _ in range(r.randint(0, 2) if self.subs else 0):
            body += self.interrupt(main)
        for _ in range(r.randint(1, 6 * self.size)):
            body += self.statement(main, depth=0)
        area = self.subprogram_area()
        if chance(r, 0.2):  # layout 2 of DG 6132: the subprogram area before the main code
            out += area + body
        else:
            out += body + area
        for k, f in enumerate(self.funcs):
            if f[3]:
                out += self.function(k)
        if self.loose and chance(r, 0.3):
            out += self.chaos_part()
        if self.syntax_chaos and chance(r, 0.5):
            out = self.chaos_lines(out)
        return "\n".join(self.decorate(out)) + r.choice(["\n", "", "\n\n"])

    def decorate(self, lines: list[str]) -> list[str]:
        """Indentation, trailing comments and continuation lines, which must not change the program."""
        r = self.r
        result = []
        for line in lines:
            plain = line and not line.lstrip().startswith(("#", "//")) and '"' not in line and "//" not in line
            if plain and chance(r, 0.05):
                line += r.choice(["  // note", " /* note */", "\t// x = 1"])
            if plain and " " in line.strip() and chance(r, 0.03) and "//" not in line and "/*" not in line:
                spaces = [m.start() for m in re.finditer(" ", line.strip())]
                cut = r.choice(spaces) + len(line) - len(line.lstrip())
                line = line[:cut] + " \\\n" + line[cut + 1:]
            if not line.lstrip().startswith("#") and chance(r, 0.3):
                line = r.choice(["  ", "\t", "    "]) + line
            result.append(line)
        return result

    def chaos_lines(self, lines: list[str]) -> list[str]:
        """Loose mode: a few token-level edits of the finished program."""
        r = self.r
        text = mutate(r, "\n".join(lines))
        return text.split("\n")

    # --- functions and subprograms -------------------------------------------------------------------------------
    def function(self, k: int) -> list[str]:
        r = self.r
        name, type_, params, _ = self.funcs[k]
        header = ", ".join(f"{self.kw(t)}{'[]' if a else ''} {n}" for t, n, a in params)
        lines = [f"{self.kw(type_)} {name}({header})", "{"] if chance(r, 0.5) else [f"{type_} {name} ({header})",
                                                                                      "", "{"]
        locals_long = [self.fresh("l_") for _ in range(r.randint(0, 2))]
        locals_double = [self.fresh("y_") for _ in range(r.randint(0, 1))]
        local_arrays = [self.fresh("la_") for _ in range(r.randint(0, 1))]
        if locals_long or local_arrays:
            lines.append("long " + ", ".join(locals_long + [f"{a}[{r.randint(1, 9)}]" for a in local_arrays]))
        if locals_double:
            lines.append("double " + ", ".join(locals_double))
        longs = self.longs + locals_long + [n for t, n, a in params if t == "long" and not a]
        if self.noimplicit or chance(r, 0.5):
            longs = [n for n in longs if not n.startswith("n_")]
        doubles = self.doubles + locals_double + [n for t, n, a in params if t == "double"]
        arrays = list(self.dims) + list(self.garrays) + local_arrays + [n for _, n, a in params if a]
        scope = _Scope("func", longs, doubles, arrays, self.funcs[:k], labels=[], func=(name, type_))
        for _ in range(r.randint(0, 4)):
            lines += self.statement(scope, depth=1)
        if chance(r, 0.85):
            lines.append(f"{self.kw('return')}({self.value(scope, type_, 2)})")
        lines.append("}")
        return lines

    def subprogram_area(self) -> list[str]:
        if not self.subs:
            return []
        r = self.r
        lines = [self.kw("SUBMAINPROG")]
        for k, name in enumerate(self.subs):
            lines.append(f"{self.kw('SUBPROG')} {name}")
            scope = _Scope("sub", self.longs, self.doubles, self.arrays, self.funcs, sub_index=k, labels=[])
            for _ in range(r.randint(0, 4)):
                lines += self.statement(scope, depth=1)
            lines.append(self.kw("RETURN"))
        lines.append(self.kw("ENDPROG"))
        return lines

    def interrupt(self, scope: _Scope) -> list[str]:
        r = self.r
        sub = r.choice(self.subs)
        g = self.kw("GOSUB")
        forms = [f"ON ERROR {g} {sub}", f"ON INT {r.choice(['1', '-2', '8', '(-3)'])} {g} {sub}",
                 f"ON PERIOD {r.randint(20, 1000)} {g} {sub}", f"ON TIME {r.randint(1, 5000)} {g} {sub}",
                 f"ON {r.choice(['', '+', '-'])}{r.choice(['APOS', 'IPOS', 'MAPOS', 'MCPOS', 'MIPOS'])} "
                 f"{r.randint(0, 100000)} {g} {sub}",
                 f"ON {r.choice(['+', '-'])}APOS {r.randint(0, 9999)} SETOUT {r.choice(['1', '-2'])}",
                 f"ON MAPOS {r.randint(0, 9999)} SETOUT 1 TOIN {r.choice(['2', '-1'])}",
                 f"ON DELETE {r.randint(0, 9999)} {g} {sub}", f"ON STATBIT {r.randint(1, 31)} {g} {sub}",
                 f"ON COMBIT {r.choice(['3', '-4'])} {g} {sub}",
                 f"ON PARAM {r.choice(['3267', '0x01606000'])} {g} {sub}",
                 f"ON KEYPRESSED {g} {sub}", f"ON CANMSG {g} {sub}", f"ON CANINPUT 0 {g} {sub}",
                 f"{self.kw('DISABLE')} {r.choice(['ALL', 'INT', 'PERIOD', 'APOS'])}",
                 f"{self.kw('ENABLE')} {r.choice(['ALL', 'INT', 'TIME', 'MIPOS'])}"]
        line = r.choice(forms)
        return [" ".join(self.kw(w) if w.isupper() and w.isalpha() else w for w in line.split(" "))]

    # --- statements ------------------------------------------------------------------------------------------------
    def statement(self, scope: _Scope, depth: int) -> list[str]:
        r = self.r
        if self.chaos():
            return [self.chaos_statement(scope)]
        kinds = list(self.STATEMENTS)
        if depth >= 3:
            kinds = [k for k in kinds if k not in ("if", "while", "repeat", "switch", "ifdef")]
        if scope.breakable:
            kinds.append("break")
        if scope.func is not None:
            kinds.append("return")
        kind = r.choice(kinds)
        method = getattr(self, "s_" + kind)
        return method(scope, depth)

    def body(self, scope: _Scope, depth: int, low: int = 0, high: int = 3) -> list[str]:
        lines: list[str] = []
        for _ in range(self.r.randint(low, high)):
            lines += self.statement(scope, depth)
        return lines

    def s_assign(self, scope, depth):
        if not scope.longs:
            return self.s_print(scope, depth)
        return [f"{self.r.choice(scope.longs)} = {self.lexpr(scope, 3)}"]

    def s_assign_double(self, scope, depth):
        if not scope.doubles:
            return self.s_assign(scope, depth)
        return [f"{self.r.choice(scope.doubles)} = {self.dexpr(scope, 3)}"]

    def s_element(self, scope, depth):
        target = self.element(scope)
        if target is None:
            return self.s_assign(scope, depth)
        return [f"{target} = {self.lexpr(scope, 2)}"]

    def s_bitset(self, scope, depth):
        target = self.r.choice(scope.longs) if scope.longs else self.element(scope)
        if target is None:
            return self.s_assign(scope, depth)
        return [f"{target}{self.selector()} = {self.lexpr(scope, 1)}"]

    def s_incdec(self, scope, depth):
        names = scope.longs + scope.doubles
        target = self.r.choice(names) if names and chance(self.r, 0.7) else self.element(scope)
        if target is None:
            return self.s_print(scope, depth)
        return [f"{target}{self.r.choice(['++', '--'])}"]

    def s_print(self, scope, depth):
        r = self.r
        items = []
        for _ in range(r.randint(0, 4)):
            k = r.randint(0, 5)
            if k <= 1:
                items.append(r.choice(['"text"', '"x = "', '""', '" a, b; c "', '"tab\there"']))
            elif k == 2:
                items.append(f"{self.kw('chr')}({r.choice(['65', '13', self.lexpr(scope, 1)])})")
            elif k == 3:
                items.append(self.dexpr(scope, 2))
            else:
                items.append(self.lexpr(scope, 2))
        head = self.kw("PRINT")
        if chance(r, 0.1):
            head = f"{self.kw('PRINTDEV')} {r.randint(0, 9)}" + ("," if items and chance(r, 0.5) else "")
        end = ";" if items and chance(r, 0.2) else ""
        return [f"{head} {', '.join(items)}{end}".rstrip()]

    def s_command(self, scope, depth):
        text = self.command(scope, statement=True)
        return [text] if text else self.s_assign(scope, depth)

    def s_gosub(self, scope, depth):
        targets = self.subs[scope.sub_index + 1:] if scope.unit != "func" else []
        if not targets:
            return self.s_assign(scope, depth)
        return [f"{self.kw('GOSUB')} {self.r.choice(targets)}"]

    def s_if(self, scope, depth):
        r = self.r
        inner = scope.inner()
        lines = [f"{self.kw('IF')} {self.cond(scope)} {self.kw('THEN')}"]
        if chance(r, 0.15) and scope.longs:  # C:2427: IF cond THEN statement / ENDIF
            lines[0] += f" {r.choice(scope.longs)} = {self.lexpr(scope, 1)}"
        lines += self.body(inner, depth + 1)
        for _ in range(r.randint(0, 2)):
            lines.append(f"{self.kw('ELSEIF')} {self.cond(scope)} {self.kw('THEN')}")
            lines += self.body(inner, depth + 1)
        if chance(r, 0.5):
            lines.append(self.kw("ELSE"))
            lines += self.body(inner, depth + 1)
        lines.append(self.kw("ENDIF"))
        return lines

    def s_while(self, scope, depth):
        return ([f"{self.kw('WHILE')} {self.cond(scope)} {self.kw('DO')}"] + self.body(scope.inner(True), depth + 1)
                + [self.kw("ENDWHILE")])

    def s_repeat(self, scope, depth):
        return ([self.kw("REPEAT")] + self.body(scope.inner(True), depth + 1)
                + [f"{self.kw('UNTIL')} {self.cond(scope)}"])

    def s_switch(self, scope, depth):
        r = self.r
        inner = scope.inner(True)
        value = self.lexpr(scope, 2)
        lines = [f"{self.kw('SWITCH')} {value if chance(r, 0.5) else '(' + value + ')'}"]
        values = sorted({r.randint(-5, 20) for _ in range(r.randint(1, 4))})
        for v in values:
            label = str(v)
            for name, mv in self.macros:
                if mv == v and chance(r, 0.5):
                    label = name
            if chance(r, 0.2) and scope.longs:
                lines.append(f"{self.kw('CASE')} {label}: {r.choice(scope.longs)} = {v}")
            else:
                lines.append(f"{self.kw('CASE')} {label}:")
            lines += self.body(inner, depth + 1, 0, 2)
            if chance(r, 0.7):
                lines.append(self.kw("BREAK"))
        if chance(r, 0.5):
            lines.append(f"{self.kw('DEFAULT')}:")
            lines += self.body(inner, depth + 1, 0, 2)
        lines.append(self.kw("ENDSWITCH"))
        return lines

    def s_call(self, scope, depth):
        text = self.call(scope)
        return [text] if text else self.s_assign(scope, depth)

    def s_copy(self, scope, depth):
        one_d = [a for a in scope.arrays if len(self.dims.get(a, [1])) == 1]
        if len(one_d) < 1:
            return self.s_assign(scope, depth)
        return [f"{self.r.choice(one_d)}[] = {self.r.choice(one_d)}[]"]

    def s_label(self, scope, depth):
        """label: … LOOP n label, or label: … GOTO label inside an IF (labels only at a unit's top level)."""
        r = self.r
        if depth > 1 or scope.labels is None or scope.unit == "func":
            return self.s_assign(scope, depth)
        label = self.fresh("lbl_")
        lines = [f"{label}:"] + self.body(scope, depth, 0, 2)
        if chance(r, 0.5):
            lines.append(f"{self.kw('LOOP')} {r.choice(['3', '0', self.leaf_long(scope)])} {label}")
        else:
            lines += [f"{self.kw('IF')} {self.cond(scope)} {self.kw('THEN')}", f"{self.kw('GOTO')} {label}",
                      self.kw("ENDIF")]
        return lines

    def s_pseudo(self, scope, depth):
        r = self.r
        name = r.choice(["SYSVAR", "PCD", "PDO"])
        index = r.choice(["1", "4096", "0x01220101", self.leaf_long(scope)])
        sel = self.selector() if chance(r, 0.2) else ""
        return [f"{self.kw(name)}[{index}]{sel} = {self.lexpr(scope, 1)}"]

    def s_ifdef(self, scope, depth):
        """Conditional compilation around statements: the dropped branch may hold anything."""
        r = self.r
        inner = scope.inner()
        inner.labels = None
        junk = r.choice(["This is never compiled.", "ENDIF )(", "#notadirective", "x = = 1"])
        form = r.randint(0, 2)
        if form == 0 and self.macros:
            name, value = r.choice(self.macros)
            head, taken = f"#if {name} > {value - 1}", True
        elif form == 1:
            head, taken = r.choice([("#ifdef M_UNDEFINED", False), ("#ifndef M_UNDEFINED", True)])
        else:
            head, taken = r.choice([("#if 0", False), ("#if 1", True), ("#if defined(M_UNDEFINED)", False)])
        good = self.body(inner, depth + 1, 1, 2)
        if chance(r, 0.5):
            return [head] + (good if taken else [junk]) + ["#endif"]
        return [head] + (good if taken else [junk]) + ["#else"] + ([junk] if taken else good) + ["#endif"]

    def s_exit(self, scope, depth):
        return [self.kw("EXIT")] if chance(self.r, 0.3) else self.s_assign(scope, depth)

    def s_break(self, scope, depth):
        return [self.kw("BREAK")]

    def s_return(self, scope, depth):
        return [f"{self.kw('return')}({self.value(scope, scope.func[1], 2)})"]

    # --- commands --------------------------------------------------------------------------------------------------
    def command(self, scope: _Scope, statement: bool) -> str | None:
        """A command from the table with arguments that fit its argument specs."""
        r = self.r
        candidates = [c for c in TABLE if c.kind == "command" and c.name not in ("PRINT", "PRINTDEV")
                      and (c.statement if statement else (not c.statement and c.returns != "none"))]
        cmd = r.choice(candidates)
        args: list[str] = []
        kinds: list[str] = []
        for spec in cmd.args:
            count = 1
            if spec.optional and chance(r, 0.5):
                count = 0
            if spec.repeat:
                count = max(count, 1) + r.randint(0, 2)
            for _ in range(count):
                arg = self.argument(scope, spec)
                if arg is None:
                    return None
                args.append(arg)
                kinds.append(spec.kind)
        # A bare name followed by '(' would read as a function call: put such names in parentheses.
        for k in reversed(range(len(args) - 1)):
            if kinds[k] == "expr" and re.fullmatch(r"[A-Za-z_]\w*", args[k]) and args[k + 1].startswith("("):
                args[k] = f"({args[k]})"
        sep = ", " if any(s.repeat for s in cmd.args) and chance(r, 0.5) else " "
        # The legacy axis designator x(1) (C:826 DEFCORIGIN X(1)), on commands without arguments.
        axis = f" {self.kw('x')}(1)" if chance(r, 0.1) and not cmd.args else ""
        text = " ".join(self.kw(w) for w in cmd.words) + axis + (" " + sep.join(args) if args else "")
        return text if statement else f"({text})"

    def argument(self, scope: _Scope, spec) -> str | None:
        r = self.r
        if spec.kind == "word":
            return self.kw(r.choice(spec.words))
        if spec.kind == "string":
            return r.choice(['"text"', '"Par 1"', '""'])
        if spec.kind == "array":
            arrays = [a for a in scope.arrays if len(self.dims.get(a, [1])) == 1]
            return r.choice(arrays) if arrays else None
        if spec.kind == "var":
            if scope.longs and chance(r, 0.8):
                return r.choice(scope.longs)
            return self.element(scope, one_d=True)
        if spec.kind == "param":
            return r.choice(PARAM_NAMES + [str(r.randint(1900, 1999))])
        k = r.randint(0, 3)
        if k == 0:
            return str(r.randint(0, 2000))
        if k == 1:
            return f"({self.lexpr(scope, 2)})"
        if k == 2:
            return f"(-{r.randint(1, 100)})"
        return self.leaf_long(scope)

    def call(self, scope: _Scope) -> str | None:
        if not scope.funcs:
            return None
        name, type_, params, _ = self.r.choice(scope.funcs)
        args = []
        for t, _, is_array in params:
            if is_array:
                arrays = [a for a in scope.arrays if len(self.dims.get(a, [1])) == 1]
                if not arrays:
                    return None
                args.append(self.r.choice(arrays))
            else:
                args.append(self.value(scope, t, 1))
        return f"{name}({', '.join(args)})"

    # --- expressions -------------------------------------------------------------------------------------------------
    def value(self, scope: _Scope, type_: str, depth: int) -> str:
        return self.dexpr(scope, depth) if type_ == "double" else self.lexpr(scope, depth)

    def selector(self) -> str:
        r = self.r
        kind = r.choice(["", "", "i", "b", "w", "l", "ub", "sb", "uw", "sw"])
        high = {"": 32, "i": 32, "b": 4, "ub": 4, "sb": 4, "w": 2, "uw": 2, "sw": 2, "l": 1}[kind]
        return f".{kind}{r.choice(['', ' '] if kind else [''])}{r.randint(1, high)}"

    def element(self, scope: _Scope, one_d: bool = False) -> str | None:
        r = self.r
        arrays = [a for a in scope.arrays if not one_d or len(self.dims.get(a, [1])) == 1]
        if not arrays:
            return None
        name = r.choice(arrays)
        dims = self.dims.get(name) or [self.garrays.get(name, 1)]
        return name + "".join(f"[{self.index(scope, n)}]" for n in dims)

    def index(self, scope: _Scope, n: int) -> str:
        if chance(self.r, 0.6):
            return str(self.r.randint(1, n))
        return self.lexpr(scope, 1)

    def leaf_long(self, scope: _Scope) -> str:
        r = self.r
        k = r.randint(0, 12)
        if k <= 2 or not scope.longs and k <= 5:
            return r.choice([str(r.randint(0, 1000)), str(r.randint(0, 100000)), hex(r.randint(0, 0xFFFF)),
                             "'A'", "0x7FFFFFFF", "0", "1", "017"])
        if k <= 5:
            return r.choice(scope.longs)
        if k == 6:
            element = self.element(scope)
            return element or "1"
        if k == 7:
            return self.kw(r.choice(SYSVARS_LONG))
        if k == 8 and self.macros:
            return r.choice(self.macros)[0]
        if k == 9:
            return self.command(scope, statement=False) or "2"
        if k == 10:
            return f"{self.kw(r.choice(['IN', 'INB', 'INAD']))} {r.randint(1, 8)}"
        if k == 11:
            return f"{self.kw('GET')} {r.choice(PARAM_NAMES + ['1901'])}"
        return self.kw(r.choice(["ON", "OFF"]))

    def lexpr(self, scope: _Scope, depth: int) -> str:
        """A LONG expression (constants stay small, divisors are non-zero literals)."""
        r = self.r
        if self.chaos():
            return self.chaos_value(scope)
        if depth <= 0 or chance(r, 0.3):
            return self.leaf_long(scope)
        k = r.randint(0, 15)
        a = self.lexpr(scope, depth - 1)
        if k <= 4:
            op = r.choice(["+", "-", "*", "&", "|", "^", "<<", ">>", "==", "!=", "<", "<=", ">", ">=", "AND", "OR",
                           "mod", "rnd", "%"])
            if op in ("mod", "rnd", "%"):
                return f"({a} {self.kw(op)} {r.randint(1, 9)})"
            return f"({a} {self.kw(op)} {self.lexpr(scope, depth - 1)})"
        if k == 5:
            return f"{r.choice(['-', '~', self.kw('NOT') + ' '])}({a})"
        if k == 6:
            return f"{self.kw('abs')}({a})"
        if k == 7:
            return f"((long) ({self.dexpr(scope, depth - 1)}))"
        if k == 8:  # '.' binds like '*': (a * b.3) is ((a * b).3), so the selection gets parentheses
            base = f"({a})" if chance(r, 0.5) or not scope.longs else r.choice(scope.longs)
            return f"({base}{self.selector()})"
        if k == 9:
            return f"({self.dexpr(scope, depth - 1)} {r.choice(['<', '>=', '==', '!='])} {self.dexpr(scope, 0)})"
        if k == 10:
            calls = [f for f in scope.funcs if f[1] == "long"]
            if calls:
                name, _, params, _ = r.choice(calls)
                text = self.call(_Scope(scope.unit, scope.longs, scope.doubles, scope.arrays,
                                        [f for f in scope.funcs if f[0] == name]))
                if text:
                    return text
            return a
        if k == 11 and self.fmacro:
            return f"{self.fmacro}({a})"
        if k == 12 and scope.longs:
            return f"{r.choice(scope.longs)}{r.choice(['++', '--'])}"
        if k == 13:
            return f"{self.kw('SYSVAR')}[{a}]"
        if k == 14:  # DOUBLE operands of the logical operators
            return f"({self.dexpr(scope, depth - 1)} {self.kw(r.choice(['AND', 'OR']))} {a})"
        if k == 15:
            return f"({self.kw('NOT')} {self.dexpr(scope, depth - 1)})"
        return a

    def dexpr(self, scope: _Scope, depth: int) -> str:
        """A DOUBLE expression: small finite constants, so constant folding never overflows."""
        r = self.r
        if self.chaos():
            return self.chaos_value(scope)
        if depth <= 0 or chance(r, 0.3):
            k = r.randint(0, 5)
            if k <= 1 or not scope.doubles and k <= 3:
                return r.choice(["1.5", "0.0", "2.0", "100.25", "0.001", "15.0", "3.0e2", "1e-3"])
            if k <= 3:
                return r.choice(scope.doubles)
            if k == 4:
                return self.kw("PI")
            return f"((double) {self.leaf_long(scope)})"
        k = r.randint(0, 9)
        a = self.dexpr(scope, depth - 1)
        if k <= 3:
            op = r.choice(["+", "-", "*", "%"])
            b = r.choice(["2.0", "0.5", "3", "7.25"]) if op == "%" else self.value(scope, r.choice(["long", "double"]),
                                                                                   depth - 1)
            return f"({a} {op} {b})"
        if k == 4:
            fn = r.choice(MATH_DOUBLE)
            return f"{self.kw(fn)}({a})" if fn != "sqrt" else f"{self.kw('sqrt')}({self.kw('fabs')}({a}))"
        if k == 5:
            return f"{self.kw('ln')}({self.kw('fabs')}({a}) + 1.0)"
        if k == 6:
            return f"{self.kw(r.choice(['asin', 'acos']))}({self.kw('sin')}({a}))"
        if k == 7:
            base = r.choice(scope.doubles + ["2.0", "1.5"])
            return f"({base} {self.kw('exp')} {r.choice(['2.0', '0.5', '3', '1.0'])})"
        if k == 8:
            return f"-({a})"
        calls = [f for f in scope.funcs if f[1] == "double"]
        if calls:
            name = r.choice(calls)[0]
            text = self.call(_Scope(scope.unit, scope.longs, scope.doubles, scope.arrays,
                                    [f for f in scope.funcs if f[0] == name]))
            if text:
                return text
        return a

    def cond(self, scope: _Scope) -> str:
        r = self.r
        k = r.randint(0, 4)
        if k == 0:
            return f"({self.lexpr(scope, 2)})"
        if k == 1:
            return f"{self.kw('IN')} {r.randint(1, 8)}"
        if k == 2:
            return f"({self.lexpr(scope, 1)} {r.choice(['<', '==', '>=', '!='])} {self.lexpr(scope, 1)})"
        if k == 3:
            return f"(({self.kw('AXEND')} & 2) {self.kw(r.choice(['AND', 'OR']))} NOT ({self.lexpr(scope, 1)}))"
        return f"({self.dexpr(scope, 1)} > {self.dexpr(scope, 0)})"

    # --- loose mode: wrong things ------------------------------------------------------------------------------------
    # Values and statements that parse but are wrong (they reach the checks and the code generator) ...
    CHAOS_VALUES = [
        "{undef}", "{array}", "{long}[1]", "{dim}[1][2]", "{func}", "{sub}", "nofunc(1)", "{func}(1, 2, 3, 4)",
        '"text"', "chr(65)", "{double}.3", "{long}.b5", "{long}.40", "{long}.0", "5.b9", "(1.5 << 2)",
        "({double} mod 2)", "~{double}", "(1 % 0)", "(5 mod 0)", "(1 rnd 0)", "(2.0 % 0.0)", "sqrt(-1.0)", "ln(0.0)",
        "acos(2.0)", "(0.0 exp -1.0)", "((-8.0) exp 0.5)", "(1e308 * 10.0)", "(1e308 + 1e308)", "ON", "(GET NOTAPARAM)",
        "(10 exp 400)", "(2.0 exp 1024.0)", "grad(1e308)", "(1e308 * 1e308 * 0.0)", "({long} % 0)", "(7 % (3 - 3))",
        "-(-2147483648)", "(2147483647 + 1)", "(0x80000000 % -1)", "((-2147483647 - 1) % -1)", "abs(-2147483648)",
        "(1 << -1)", "(1 >> 64)", "(1 << 99999)", "({long} exp {long})", "NOT 1.5", "((double) 1) . 3", "x(1)",
        "{long}(1)", "round(-0.5)", "(1 == 1 == 1)", "'A' + 'B'", "{long}.sb 0", "{long}.b ({long})", "{long}.uw -1",
        "(1.5).b1", "(long)(double)(long) 1.5e300", "(SDOSTATE 1 {long})", "(ENCTGREAD {long})", "{math}(1e308 * 10.0)",
        "{math}(-(1e308 * 10.0))", "{math}((1e308 * 10.0) - (1e308 * 10.0))", "{math}(1e308)", "{math}(-1e308)",
        "{math}(5e-324)", "{math}({double})", "(long) {math}(1e308 * 1e308)", "{math}(1.7976931348623157e308 * 2)",
        "{func}({long})", "{func}({array})", "{func}({double}, {double})", "{long}.{long}", "{long}.({long} + 1)",
        "{array}[0]", "{array}[-1]", "{dim}[1]", "(SDOSTATE 1 {dim}[1][1])", "({double} AND {double})", "NOT {double}",
        "((1e308 * 10.0) == 0.0)", "(long) (1e308 * 10.0)", "{double} exp 0.5", "__LINE__", "__FILE__", "(x(1) + 1)",
        "PI", "(long) PI", "(CPOSDIFF x(2) 5)", "(APOSDIFF X({long}) {long})",
    ]
    # ... and ones that stop the parser.
    CHAOS_VALUES_SYNTAX = [
        "1e400", "round(1e400)", "((long) 1e400)", "0x100000000", "99999999999", "tan(PI / 2)", "(IN)", "(POSA 1)",
        "(MOTOR ON)", "SYSVAR", "PCD[1][2]", "(1)++", "{long}++ ++", "(GET)", "(long)", "(double)", "{func}({array}[])",
        "{array}[]", "(({long}))[1]", "SQRT(1, 2)", "ABS()", "PI(1)", "({long} = 1)", "(IN 1 2)", "(APOS 1)", "(INKEY)",
        "(CANIN 1 2 3 4 5)", "(ENCPOSOFFS 5)", "(ENCTGREAD 5)", "(IN X59/3)", "(IN x56/)", "X59/3",
    ]
    CHAOS_STATEMENTS = [
        "GOSUB nosub", "GOTO nolabel", "LOOP {long} nolabel", "BREAK", "EXIT", "DIM late[5]", "#pragma IMPLICIT",
        "#pragma NOIMPLICIT", "long {long}", "double {long}", "long {func}", "long {sub}", "{func} = 1",
        "{long}[] = {long}[]", "{array}[] = {double}[]", "PCD[1].3 = 1", "SYSVAR[1].b2 = 4", "ON INT 1 GOSUB nosub",
        "ON DELETE 5 SETOUT 1", "ON -APOS 5 SETOUT 1 TOIN 2", "ON + IPOS 1 GOSUB {sub}", "ON TIME 1 GOSUB {func}",
        "DEFCORIGIN X({long})", "DEFCORIGIN X(2)", "{long}:", "{sub}:", "lbl_dup:", "lbl_dup:",
        "long f_bad(long a, long a) ;", "double {func}() ;", "long {func}(long[] z) ;", "long proto_only() ;",
        "{func}()", "SET NOTAPARAM 1", "OUT {array} 1", "SDOSTATE 1 {long}.3", "ENCTGREAD {long}", "SETCURVE {long}",
        "PRINT {array}", "PRINT {func}", "{long}++", "{double}--", "{array}++", "SYSVAR[1]++", "INKEY 0",
        "DELETE ARRAYS", "x = 1", "{long} = {func}", "{long} = {sub}", '{double} = "s"', "{long} = {long}[1]",
        "{double}[1] = 0", "label_only:", "GOTO label_only", "ON INT 0 GOSUB {sub}", "ON PERIOD 5 GOSUB {sub}",
        "ON COMBIT 40 GOSUB {sub}", "ON STATBIT 0 GOSUB {sub}", "ON CANINPUT 1 GOSUB {sub}", "ON TIME -1 GOSUB {sub}",
        "ON PERIOD {double} GOSUB {sub}", "ON APOS {double} GOSUB {sub}", "ON DELETE +APOS SETOUT 1",
        "ON DELETE -MAPOS GOSUB {sub}", "SDOSTATE 1 {dim}[1][1]", "ENCPOSOFFS {dim}[1][2]",
        "CANIN 1 2 3 {long} {array}[1]", "OUT X59/3 1", "OUT x59/1 {long}", "{long} = IN X59/3", "TESTSETDEST DYNMEM",
        "TESTSETDEST {array}", "LOOP -1 label_only", "LOOP {double} label_only", "SWITCH {double}\nCASE 1:\nENDSWITCH",
        "SWITCH 1\nCASE {long}:\nENDSWITCH", "SWITCH 1\nCASE 1:\nCASE 1:\nENDSWITCH", "SWITCH 1\nCASE 1.5:\nENDSWITCH",
        "IF 1 THEN ENDIF", "{long}.{long} = 1", "{long}.b({long}) = 2", "{dim}[1][1].3 = 1", "PDO[1].w2 = {double}",
        "DIM huge[2000][2000]", "POSA (1e308 * 10.0)", "DELAY {double}", "PRINT chr({double}), chr(1e308 * 10.0)",
        'PRINTDEV {double} "x"', "NOWAIT ON", "WAITI 1", "WAITI 1 OFF", "SET PID KPROP {double}",
        "SET KPROP (1e308 * 10.0)", 'LINKGPAR 1900 "" 0 100 0',
    ]
    CHAOS_STATEMENTS_SYNTAX = [
        "RETURN", "return({long})", "long POSA", "APOS = 1", "POSA = 3", "PI = 3", "(v) = 1", "1 = 2", "{long}.3.2 = 1",
        "{func}(1).3 = 2", "ON FOO 1 GOSUB {sub}", "ON APOS GOSUB {sub}", "ON ERROR", "ON INT GOSUB {sub}",
        "SWITCH {double}", "SWITCH 1", "CASE 1:", "DEFAULT:", "ENDSWITCH", "ENDIF", "ELSE", "ENDWHILE", "UNTIL 1",
        "POSA x(2) 100", "POSA:", "THEN", "SUBPROG {sub}", "ENDPROG", "SUBMAINPROG", "{{", "}}", "{func}", "{long}",
        "{undef}", "MOTOR", "SAVE", "SET PID FOO 1", "SET PID KPROP", "SET 1900", "SET", "NOWAIT MAYBE", "NOWAIT",
        "WAITI 1 ON OFF", "OUT 1", "OUT 1 2 3", 'POSA "text"', "LINKGPAR 1900 5 0 100 0", "CANIN 1 2 3 4 5",
        "CANIN 1 2 3 {long} {func}(1)", "ENCPOSOFFS 5", "TESTSETINDEX", "CANINI 1,2,,3", "PRINT ,", "PRINT 1;;",
        "PRINT CHR()", "PRINTDEV", "{long} = {long} =", "IF 1 THEN", "WHILE 1 DO", "REPEAT",
        "IF {long} THEN GOTO nolabel", "{long} = INKEY", "DISABLE ERROR", "ENABLE", "DELETE", "MOTOR ON OFF",
        "POSA CURVEPOS 1", "X(1) = 2", "{long} = (long)", "{long}.b = 1", "{dim}[1] = {dim}[1][1][1]", "POSA X59/3",
        "SWITCH 1\nDEFAULT:\nDEFAULT:\nENDSWITCH", "IF 1 THEN\nELSE\nELSE\nENDIF",
        "IF 1 THEN\nELSE\nELSEIF 1 THEN\nENDIF", "IF 1 THEN\nELSE IF 1 THEN\nENDIF", "SWITCH\nENDSWITCH",
        "WHILE DO\nENDWHILE", "REPEAT\nUNTIL", "LOOP", "long x[0]", "long x[1][2][3]", "long x = 1", "DIM y",
        "SUBMAINPROG\nENDPROG",
    ]
    # Program-level mistakes: duplicate definitions, mismatching prototypes, misplaced parts.
    CHAOS_PARTS = [
        "long {func}(double z)\n{{\nreturn(1)\n}}", "long {func}()\n{{\n}}", "double {func}(long[] a) ;",
        "long fresh_fn(long a, long a)\n{{\nreturn(a)\n}}", "long {sub}()\n{{\n}}",
        "SUBMAINPROG\nSUBPROG {sub}\nRETURN\nENDPROG", "long late_decl\nlate_decl = 1",
        "long rec(long n)\n{{\nreturn(rec(n - 1))\n}}", "long noreturn()\n{{\n{long} = 1\n}}",
        "long used_before()\n{{\nreturn(later_fn(1))\n}}\nlong later_fn(long q)\n{{\nreturn(q)\n}}",
    ]

    def chaos_fill(self, template: str, scope: _Scope) -> str:
        r = self.r
        fields = {
            "undef": r.choice(["undeclared", "zz", "n_99", "Zq_1"]),
            "array": r.choice(scope.arrays or ["noarray"]),
            "dim": r.choice(list(self.dims) or ["nodim"]),
            "long": r.choice(scope.longs or ["nolong"]),
            "double": r.choice(scope.doubles or ["nodouble"]),
            "func": r.choice([f[0] for f in self.funcs] or ["nofunc"]),
            "sub": r.choice(self.subs or ["nosub"]),
            "math": r.choice(MATH_DOUBLE + ["asin", "acos", "ln", "abs", "exp", "chr"]),
        }
        return template.format(**fields)

    def chaos_value(self, scope: _Scope) -> str:
        syntax = self.syntax_chaos and chance(self.r, 0.3)
        return self.chaos_fill(self.r.choice(self.CHAOS_VALUES_SYNTAX if syntax else self.CHAOS_VALUES), scope)

    def chaos_statement(self, scope: _Scope) -> str:
        r = self.r
        k = r.randint(0, 5)
        if k == 0 and self.syntax_chaos:  # a command with arguments of any kind
            cmd = r.choice(TABLE.names())
            args = " ".join(r.choice([self.lexpr(scope, 1), self.chaos_value(scope), any_token(r), '"t"'])
                            for _ in range(r.randint(0, 4)))
            return f"{cmd} {args}"
        if k == 1 and scope.longs:
            return f"{r.choice(scope.longs)} = {self.chaos_value(scope)}"
        if k == 2:
            return f"PRINT {self.chaos_value(scope)}"
        if self.syntax_chaos and chance(r, 0.3):
            return self.chaos_fill(r.choice(self.CHAOS_STATEMENTS_SYNTAX), scope)
        return self.chaos_fill(r.choice(self.CHAOS_STATEMENTS), scope)

    def chaos_part(self) -> list[str]:
        scope = _Scope("main", self.longs, self.doubles, list(self.dims) + list(self.garrays), self.funcs)
        return self.chaos_fill(self.r.choice(self.CHAOS_PARTS), scope).split("\n")


def valid_program(r) -> str:
    """A program that must compile without errors."""
    return ProgramGenerator(r, loose=False).program()


def semantic_soup(r) -> str:
    """A grammar-generated program with wrong things sprinkled in."""
    return ProgramGenerator(r, loose=True).program()


# --- generator 5: deep and long constructs -------------------------------------------------------------------------
def deep_nesting(r) -> str:
    n = r.choice([2, 10, 50, 100, 200, 400, 800, 1500, 3000])
    k = r.randint(0, 25)
    if k in (8, 11):  # these cost O(n^2) or 10 n lines: keep them quick
        n = min(n, 400)
    if k == 7:
        n = min(n, 1500)
    if k == 0:
        return "a = " + "(" * n + "1" + ")" * n
    if k == 1:
        return "a = " + "- " * n + "1"
    if k == 2:
        return "a = " + " + ".join(["1"] * n)
    if k == 3:
        return "b = 1\na = " + " + ".join(["b"] * n)
    if k == 4:
        return "IF 1 THEN\n" * n + "a = 1\n" + "ENDIF\n" * n
    if k == 5:
        return "WHILE a < 1 DO\n" * n + "a = a + 1\n" + "ENDWHILE\n" * n
    if k == 6:
        return "a = " + "NOT " * n + "1"
    if k == 7:
        return "#define F(x) (x)\na = " + "F(" * n + "1" + ")" * n
    if k == 8:
        return "#define M0 1\n" + "".join(f"#define M{i} (M{i - 1}+1)\n" for i in range(1, n)) + f"a = M{n - 1}"
    if k == 9:  # doubling macros: stopped by the expansion limits (decisions L22), whatever the depth
        m = min(n, 64)
        return "#define M0 b\n" + "".join(f"#define M{i} M{i - 1}+M{i - 1}\n" for i in range(1, m)) + \
            f"b = 1\na = M{m - 1}" + f"\nc = M{min(m, 12) - 1}" * r.randint(0, 60)
    if k == 10:
        return "#if 1\n" * n + "a = 1\n" + "#endif\n" * n
    if k == 11:
        return "a = 1\n" * (n * 10)
    if k == 12:
        return "long f(long x)\n{\nreturn(x + 1)\n}\na = " + "f(" * n + "1" + ")" * n
    if k == 13:
        return "DIM d[5]\na = " + "d[" * n + "1" + "]" * n
    if k == 14:
        return r.choice(["a = " + "9" * n, "a" * n + " = 1", 'PRINT "' + "x" * (n * 10) + '"', "a = 1." + "5" * n])
    if k == 15:
        return "b = 7\na = b" + ".1" * n
    if k == 16:
        return "double d\nd = " + "(long) (double) " * n + "1.5"
    if k == 17:
        return "double d\nd = 2.0" + " exp 1.0" * n
    if k == 18:
        return "REPEAT\n" * n + "a = 1\n" + "UNTIL 1\n" * n
    if k == 19:
        return "SWITCH 1\nCASE 1:\n" * n + "a = 1\n" + "ENDSWITCH\n" * n
    if k == 20:
        return "a = 1 " + "/* c */ " * n + "\n" + "// c\n" * n + "/*\n" * 1 + "\n" * n + "*/"
    if k == 21:  # function-like doubling nested in its own arguments
        return "#define D(x) x x\na = " + "D(" * min(n, 40) + "1" + ")" * min(n, 40)
    if k == 22:
        return "#if " + "(" * n + "1" + ")" * n + "\na = 1\n#endif"
    if k == 23:
        return r.choice(["#if " + "9" * (n * 3), "a = " + "9" * (n * 3), '#include "' + "n" * n + '.m"'])
    if k == 24:  # a chain of macros each using the next
        return "".join(f"#define C{i} C{i + 1}\n" for i in range(n)) + f"#define C{n} 1\na = C0"
    return "a = " + "abs(" * n + "-1" + ")" * n


# name: (generator, share of the benchmark's cases in per mille)
GENERATORS = {
    "token_stream": (token_stream, 400),
    "mutated_example": (mutated_example, 345),
    "semantic_soup": (semantic_soup, 150),
    "valid_program": (valid_program, 100),
    "deep_nesting": (deep_nesting, 5),
}


# --- the properties --------------------------------------------------------------------------------------------------
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


# --- the benchmark ---------------------------------------------------------------------------------------------------
CHUNK = 500  # cases per work unit; each unit has its own seed, so the result does not depend on --jobs


def outcome(text: str, must_compile: bool) -> tuple | None:
    """None if all is well, else a key naming the failure: the crash site or the broken property."""
    try:
        check_compile(text, must_compile=must_compile)
    except PropertyViolation as exc:
        return ("property", str(exc).split("\n")[0].split(":")[0], "", "")
    except Exception as exc:  # noqa: BLE001 - every exception is a finding
        return crash_site(exc)
    return None


def describe_failure(text: str, must_compile: bool) -> str:
    """The broken property with the diagnostics, or the last frames of the traceback."""
    try:
        check_compile(text, must_compile=must_compile)
    except PropertyViolation as exc:
        return str(exc)
    except Exception as exc:  # noqa: BLE001
        return last_frames(exc)
    return "(no failure)"


def run_unit(unit: tuple[str, int, int, int]) -> tuple[str, int, float, dict, dict]:
    """Run `count` cases of one generator from the seed (seed, name, index): (name, count, seconds, failure
    counts by key, first failing text by key)."""
    name, seed, index, count = unit
    generate, _ = GENERATORS[name]
    r = random.Random(f"{seed}:{name}:{index}")
    must = name == "valid_program"
    counts: dict[tuple, int] = {}
    first: dict[tuple, str] = {}
    start = time.perf_counter()
    for _ in range(count):
        text = generate(r)
        key = outcome(text, must)
        if key is not None:
            counts[key] = counts.get(key, 0) + 1
            first.setdefault(key, text)
    return name, count, time.perf_counter() - start, counts, first


def shrink(text: str, key: tuple, must_compile: bool, budget: float = 10.0) -> str:
    """A smaller text with the same failure key (time-boxed): repeatedly drop runs of lines, then of tokens, then
    of characters, runs halving in length down to 1, until nothing more can go."""
    deadline = time.perf_counter() + budget
    splitters = [(lambda t: t.split("\n"), "\n"), (lambda t: re.findall(r"\s+|" + _TOKEN_RE.pattern, t), ""),
                 (list, "")]
    progress = True
    while progress and time.perf_counter() < deadline:
        progress = False
        for split, joiner in splitters:
            parts = split(text)
            chunk = max(1, len(parts) // 2)
            while chunk >= 1 and time.perf_counter() < deadline:
                i = 0
                while i + chunk <= len(parts) and time.perf_counter() < deadline:
                    candidate = parts[:i] + parts[i + chunk:]
                    if candidate and outcome(joiner.join(candidate), must_compile) == key:
                        parts, progress = candidate, True
                    else:
                        i += 1 if chunk <= 2 else chunk
                chunk //= 2
            text = joiner.join(parts)
    return text


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cases", type=int, default=100_000, help="total number of generated programs")
    parser.add_argument("--seed", type=int, default=305)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="worker processes")
    args = parser.parse_args(argv)
    units = []
    for name, (_, share) in GENERATORS.items():
        cases = args.cases * share // 1000
        if name == "token_stream":  # the rounding remainder
            cases += args.cases - sum(args.cases * s // 1000 for _, s in GENERATORS.values())
        units += [(name, args.seed, i, min(CHUNK, cases - i * CHUNK)) for i in range((cases + CHUNK - 1) // CHUNK)]
    start = time.perf_counter()
    if args.jobs > 1:
        with ProcessPoolExecutor(args.jobs) as pool:
            results = list(pool.map(run_unit, units))
    else:
        results = [run_unit(u) for u in units]
    elapsed = time.perf_counter() - start
    done = sum(r[1] for r in results)
    counts: dict[tuple, int] = {}
    first: dict[tuple, tuple[str, str]] = {}
    for name, _, _, unit_counts, unit_first in results:
        for key, n in unit_counts.items():
            counts[key] = counts.get(key, 0) + n
            first.setdefault(key, (name, unit_first[key]))
    crashes = sum(n for k, n in counts.items() if k[0] != "property")
    print(f"fuzz_cases: {done} cases")
    print(f"fuzz_jobs: {args.jobs} count")
    print(f"fuzz_time: {elapsed:.1f} s")
    print(f"fuzz_rate: {done / elapsed:.0f} cases/s")
    for name in GENERATORS:
        n = sum(r[1] for r in results if r[0] == name)
        seconds = sum(r[2] for r in results if r[0] == name)
        print(f"fuzz_rate_{name}: {n / seconds if seconds else 0:.0f} cases/s per process ({n} cases)")
    print(f"fuzz_crashes: {crashes} count")
    print(f"fuzz_crash_sites: {sum(1 for k in counts if k[0] != 'property')} count")
    print(f"fuzz_property_failures: {sum(n for k, n in counts.items() if k[0] == 'property')} count")
    where = Path(INPUT_PATH).relative_to(REPO)
    for key, (name, text) in first.items():
        must = name == "valid_program"
        small = text if key[0] == "property" and must else shrink(text, key, must)
        print(f"\n=== {counts[key]} x {key[0]} {key[1]} {key[2]}: {key[3]}", file=sys.stderr)
        print(f"first from {name} ({len(text)} chars), shrunk to {len(small)} chars; reproduce with", file=sys.stderr)
        print(f"compile_source({small!r}, {str(where)!r})", file=sys.stderr)
        print(describe_failure(small, must), file=sys.stderr)
    return 1 if counts else 0


if __name__ == "__main__":
    sys.exit(main())
