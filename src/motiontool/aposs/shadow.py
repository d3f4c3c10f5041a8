"""Names a program gives to its own variables and subprograms although they are command names (decision L14).

DG 6425 says a variable name "may not be identical to a command name", yet the manuals' own examples do it:
`STAT = CANIN …` (CR 429), `in = INB 0` (CR 1645), `ON CANINPUT 0 GOSUB break` (CR 2488), `long index` (DG 6639).
Where the grammar leaves no doubt the name is the program's: a declaration (`long`, `double`, `DIM`, a function
parameter), the target of an assignment at the start of a line when the command only gives a value or takes no
argument (`index = 1`, DG 6691; `VEL = 5` stays an error: it reads as a mistaken `VEL 5`), a subprogram's name.
Such a name then means the variable in the whole program, so the command of that name cannot be used in it; the
warning says so.
"""

from __future__ import annotations

from motiontool.aposs.commands import CommandTable
from motiontool.aposs.lexer import IDENT, NEWLINE, Token
from motiontool.language.diagnostics import Diagnostic

_VALUE_KINDS = ("command", "sysvar", "function")   # keywords (IF, BREAK …) never name a variable


def shadowed_commands(tokens: list[Token], commands: CommandTable) -> tuple[set[str], list[Diagnostic]]:
    """The command names the program uses as variable names (upper case), and one warning for each, where it
    first does so."""
    found: dict[str, Token] = {}

    def take(tok: Token) -> None:
        known = commands.get(tok.value)
        if known is not None and known.kind in _VALUE_KINDS and tok.value not in found:
            found[tok.value] = tok

    start = True      # at the start of a statement
    declaring = None  # "LONG"/"DOUBLE"/"DIM" while the statement declares names
    depth = 0         # () and [] nesting within the statement
    prev: Token | None = None
    for k, tok in enumerate(tokens):
        if tok.kind == NEWLINE:
            start, declaring, depth, prev = True, None, 0, None
            continue
        nxt = tokens[k + 1] if k + 1 < len(tokens) else tok
        if tok.is_op("(", "["):
            depth += 1
        elif tok.is_op(")", "]"):
            depth -= 1
        elif tok.kind == IDENT and prev is not None:
            after_type = prev.is_word("LONG", "DOUBLE") or (prev.is_op("]") and k >= 3
                                                            and tokens[k - 3].is_word("LONG"))
            listed = declaring and depth == 0 and (prev.is_op(",") or prev.is_word("DIM"))
            if (after_type and not nxt.is_op("(")) or listed:   # not a function's name
                take(tok)
        elif tok.kind == IDENT and start and nxt.is_op("="):
            known = commands.get(tok.value)
            if known is not None and (not known.statement or not known.args) and known.kind != "pseudoarray":
                take(tok)
        if start and tok.is_word("LONG", "DOUBLE", "DIM"):
            declaring = tok.value
        start = False
        prev = tok
    warnings = [Diagnostic("warning", f"'{tok.text}' is the name of the command {name}; this program uses it as "
                                      f"a variable, so {name} cannot be used as the command here (DG 6425)", tok.loc)
                for name, tok in found.items()]
    return set(found), warnings


def subprogram_name_warning(name: Token, kind: str) -> Diagnostic:
    what = "a keyword" if kind == "keyword" else "a command name"
    return Diagnostic("warning", f"'{name.text}' is {what} (DG 6425); it names a subprogram here, which GOSUB and "
                                 "SUBPROG keep apart from the command", name.loc)
