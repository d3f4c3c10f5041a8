"""Generators 1, 2 and 5: random token streams, mutated example programs, very deep or long constructs."""

from __future__ import annotations

import re

from .vocabulary import (
    COMMAND_NAMES,
    COMMENTS,
    EDGE_NUMBERS,
    EXAMPLE_NAMES,
    EXAMPLES,
    EXTRA_WORDS,
    IDENTIFIERS,
    INCLUDE_NAMES,
    JUNK,
    OPERATORS,
    STRINGS,
    chance,
    recase,
    weighted,
)


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
TOKEN_RE = re.compile(r'"[^"\n]*"|0[xX][0-9A-Fa-f]+|\d+\.\d+|\w+|//|/\*|\*/|<<|>>|==|!=|<=|>=|\+\+|--|\S')


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
            spans = [m.span() for m in TOKEN_RE.finditer(line)]
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

