"""The words the generators build APOSS text from, and the small helpers over ``r`` they share.

``r`` is a ``random.Random``-like object: only ``r.random()``, ``r.randint()`` and ``r.choice()`` are used, so
that tests/aposs/test_fuzz.py can drive the same generators with hypothesis-drawn bytes.
"""

from __future__ import annotations

from pathlib import Path

from motiontool.aposs.commands import command_table

REPO = Path(__file__).resolve().parents[2]
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

