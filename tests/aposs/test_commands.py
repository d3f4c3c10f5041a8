"""The APOSS command table resources/aposs/commands.toml and its loader motiontool.aposs.commands."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

from motiontool.aposs.commands import ArgSpec, Command, CommandTable, CommandTableError, command_table

TABLE_PATH = Path(__file__).resolve().parents[2] / "resources" / "aposs" / "commands.toml"

# Every command, statement, readout and interrupt form of spec section 7.1-7.15 (group tables D:6998-7432).
_ONE_WORD = """
DEFCORIGIN DEFMORIGIN DEFORIGIN ERRCLR HOME INDEX RSTORIGIN SAVEPROM SETMORIGIN SETORIGIN
CONTINUE DELAY DIM EXIT GOSUB GOTO IF THEN ELSEIF ELSE ENDIF LOOP NOWAIT REPEAT UNTIL SUBMAINPROG ENDPROG
SUBPROG RETURN SYSVAR VLTALARMSTAT VLTCONTROL VLTERRCLR WAITAX WAITI WAITNDX WAITP WAITT WHILE DO ENDWHILE
SWITCH CASE DEFAULT BREAK ENDSWITCH
IN INAD INB INKEY OUT OUTAN OUTB OUTDA
APOS APOSDIFF AVEL AXEND CPOS CPOSDIFF ENCPOSOFFS ENCTGREAD ENCTGWRITE ERRNO IPOS IPOSDIFF JERKFINVEL
JERKSTOPDIST MAPOS MAPOSDIFF MAVEL MENCPOSOFFS MENCTGREAD MENCTGWRITE MIPOS MIPOSDIFF PID PRINT PRINTDEV
STAT SYNCERR TESTSETDEST TESTSETINDEX TESTSETP TESTSETTIME TESTSETTYPE TESTSTART TESTSTOP TIME TRACKERR
_GETVEL DISABLE ENABLE
GET GETVLT GETVLTSUB LINKGPAR LINKPDO LINKSDO LINKSYSVAR SET SETVLT SETVLTSUB
COMOPTSEND COMOPTGET PCD CSTART CSTOP CVEL ACC DEC VEL POSA POSR
DEFSYNCORIGIN MOVESYNCORIGIN PULSACC PULSVEL SYNCM SYNCMARKERSTART SYNCP SYNCSTAT SYNCSTATCLR SYNCV
CURVEPOS DEFMCPOS SETCURVE SYNCC SYNCCMM SYNCCMS SYNCCSTART SYNCCSTOP
CANDEL CANIN CANOUT DEFCANIN DEFCANOUT INGLB INMSG MSGVAL OUTMSG USRSTAT CANINI SDOREAD SDOREADSEG
SDOREADSEGP SDOSTATE SDOWRITE PDO
ABS MOD RND EXP SQRT SIN COS TAN ACOS ASIN ATAN LN GRAD RAD PI FABS ROUND CHR AND OR NOT LONG DOUBLE ON OFF
INLONG SWAPMENC SETOUT TOIN
"""
SECTION_7 = _ONE_WORD.split() + [
    "DELETE ARRAYS", "MOTOR OFF", "MOTOR ON", "MOTOR STOP", "SAVE ARRAYS", "SAVE AXPARS", "SAVE GLBPARS",
    "SAVE USRPARS", "POSA CURVEPOS", "SET PID", "ON ERROR GOSUB", "ON INT", "ON APOS", "ON IPOS", "ON MAPOS",
    "ON MCPOS", "ON MIPOS", "ON PERIOD", "ON TIME", "ON COMBIT", "ON STATBIT", "ON PARAM", "ON KEYPRESSED",
    "ON CANMSG", "ON CANINPUT", "ON DELETE",
]


@pytest.fixture(scope="module")
def table() -> CommandTable:
    return command_table(TABLE_PATH)


def kinds(cmd: Command) -> list[str]:
    return [str(a) for a in cmd.args]


def test_the_packaged_table_loads_once_and_matches_the_file(table: CommandTable) -> None:
    assert command_table() is command_table()
    assert command_table().names() == table.names()


def test_counts(table: CommandTable) -> None:
    """Spec §7: ≈178 distinct commands/statements (incl. keywords, ON forms, pseudo-arrays) + ~20 functions.

    The plain commands and readouts alone are ≈135: the rest of the 178 are control keywords
    (IF, WHILE, GOSUB ...), the 16 ON forms and SYSVAR/PCD/PDO, which have their own kinds.
    """
    count = Counter(c.kind for c in table)
    assert count["command"] + count["sysvar"] >= 130
    assert sum(count[k] for k in ("command", "sysvar", "keyword", "interrupt", "pseudoarray")) >= 170
    assert count["function"] + count["operator"] + count["sysvar"] >= 20
    assert count["interrupt"] == 16
    assert {c.name for c in table if c.kind == "pseudoarray"} == {"SYSVAR", "PCD", "PDO"}


def test_section_7_is_covered(table: CommandTable) -> None:
    assert [name for name in SECTION_7 if name not in table] == []


def test_names_are_unique_upper_case_and_single_spaced(table: CommandTable) -> None:
    names = table.names()
    assert len({n.upper() for n in names}) == len(names) == len(table)
    assert all(n == " ".join(n.upper().split()) for n in names)


def test_help_is_one_short_paragraph(table: CommandTable) -> None:
    for cmd in table:
        assert "\n" not in cmd.help and 10 <= len(cmd.help) <= 600, cmd.name
        assert cmd.src.startswith(("D:", "C:")), cmd.name


def test_posa(table: CommandTable) -> None:
    """C:3447 "Syntax POSA p"; D:6184 "for position commands the program waits until the target position
    has been reached. Exception: If NOWAIT has been set to ON."
    """
    posa = table.get("posa")
    assert posa is not None and kinds(posa) == ["expr"] and posa.wait == "M" and posa.group == "ABS"
    assert posa.returns == "none" and posa.statement and 111 in posa.errors


def test_home_always_blocks(table: CommandTable) -> None:
    """C:1505 "The HOME command will also be carried out to the end in the NOWAIT ON mode"."""
    home = table.get("HOME")
    assert home is not None and home.wait == "B" and home.args == ()


def test_motor_words_and_longest_first(table: CommandTable) -> None:
    """D:7014/7015/7042 "MOTOR OFF", "MOTOR ON", "MOTOR STOP" are two-word commands."""
    motor = table.starting_with("motor")
    assert {c.name for c in motor} == {"MOTOR ON", "MOTOR OFF", "MOTOR STOP"}
    assert [len(c.words) for c in motor] == sorted((len(c.words) for c in motor), reverse=True)
    assert table.get("MOTOR") is None
    assert table.get("  motor   on ") is table.get("MOTOR ON")
    assert table.get("MOTOR STOP").words == ("MOTOR", "STOP")
    assert table.get("MOTOR STOP").wait == "M"


def test_multi_word_names_come_before_their_first_word(table: CommandTable) -> None:
    """C:3470 "POSA CURVEPOS", C:3424 "SET PID KPROP 1", C:2636 "ON ERROR GOSUB name"."""
    assert [c.name for c in table.starting_with("SET")] == ["SET PID", "SET"]
    assert [c.name for c in table.starting_with("posa")] == ["POSA CURVEPOS", "POSA"]
    on = table.starting_with("On")
    assert on[0].name == "ON ERROR GOSUB" and on[-1].name == "ON"
    assert all(c.kind == "interrupt" for c in on[:-1])
    assert table.starting_with("nosuchword") == []


def test_get_and_set(table: CommandTable) -> None:
    """C:1365 "Syntax res = GET par"; C:3889 "Syntax SET par v"; C:3424 "SET PID KPROP 1"."""
    get, set_ = table.get("GET"), table.get("set")
    assert get.returns == "long" and kinds(get) == ["param"] and not get.statement
    assert kinds(set_) == ["param", "expr"] and set_.returns == "none" and set_.statement
    assert kinds(table.get("SET PID")) == ["word:KPROP|KDER|KINT|KILIM|TIMER", "expr"]


def test_canin_writes_variables(table: CommandTable) -> None:
    """C:368 "Syntax status = CANIN objno time-out control varhi varlo"."""
    canin = table.get("CANIN")
    assert kinds(canin) == ["expr", "expr", "expr", "var", "var"] and canin.returns == "long"
    assert canin.wait == "T" and canin.since == "5.00"
    assert kinds(table.get("ENCPOSOFFS")) == ["var"] and kinds(table.get("SDOSTATE")) == ["expr", "var"]


def test_print_and_other_argument_shapes(table: CommandTable) -> None:
    """C:3516 PRINT items "separated by commas"; D:7121 "TESTSETINDEX svi1, svi2, ..."."""
    assert kinds(table.get("PRINT")) == ["print"]
    assert kinds(table.get("PRINTDEV")) == ["expr", "print?"]
    assert kinds(table.get("TESTSETINDEX")) == ["expr+"]
    assert kinds(table.get("SETCURVE")) == ["array"]
    assert kinds(table.get("LINKGPAR")) == ["expr", "string", "expr", "expr", "expr"]
    assert kinds(table.get("NOWAIT")) == ["word:ON|OFF"]
    assert table.get("WAITI").args[1] == ArgSpec("word", ("ON", "OFF"), optional=True, repeat=False)
    disable = table.get("DISABLE").args[0]
    assert disable.kind == "word" and {"ALL", "INT", "PERIOD", "MCPOS"} <= set(disable.words)


def test_readouts_and_functions(table: CommandTable) -> None:
    """C:211 "Syntax res = APOS"; D:6557 "y = sqrt(x) // returns the square root of x"."""
    apos = table.get("APOS")
    assert apos.kind == "sysvar" and apos.returns == "long" and apos.args == () and not apos.statement
    sqrt = table.get("sqrt")
    assert sqrt.kind == "function" and sqrt.returns == "double" and kinds(sqrt) == ["expr"]
    assert sqrt.since == "5.00" and not sqrt.statement
    assert table.get("PI").returns == "double"
    assert table.get("mod").kind == "operator" and table.get("IF").kind == "keyword"


def test_modifiers_and_words_are_parsed() -> None:
    assert ArgSpec.parse("expr*") == ArgSpec("expr", (), True, True)
    assert ArgSpec.parse("expr+") == ArgSpec("expr", (), False, True)
    assert str(ArgSpec.parse("word:ON|OFF?")) == "word:ON|OFF?"


def test_containment_and_iteration(table: CommandTable) -> None:
    assert "motor on" in table and "MOTOR" not in table and 42 not in table
    assert [c.name for c in table] == table.names()


# --- malformed tables ------------------------------------------------------------------------------

GOOD = {
    "name": '"POSA"', "group": '"ABS"', "kind": '"command"', "args": '["expr"]', "returns": '"none"',
    "statement": "true", "wait": '"M"', "since": '""', "syntax": '"POSA p"', "help": '"Moves."',
    "errors": "[111]", "src": '"D:7220"',
}


def write(tmp_path: Path, *entries: dict[str, str | None], version: str = "1") -> Path:
    text = f"version = {version}\n"
    for entry in entries:
        fields = {**GOOD, **entry}
        text += "[[command]]\n" + "".join(f"{k} = {v}\n" for k, v in fields.items() if v is not None)
    path = tmp_path / "commands.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_a_minimal_table_loads(tmp_path: Path) -> None:
    t = command_table(write(tmp_path, {}, {"name": '"MOTOR ON"', "args": "[]", "wait": '"-"'}))
    assert len(t) == 2 and t.get("motor on").args == () and t.get("POSA").errors == (111,)


@pytest.mark.parametrize(
    ("entry", "field"),
    [
        ({"help": None}, "help"),
        ({"kind": '"macro"'}, "kind"),
        ({"group": '"XYZ"'}, "group"),
        ({"returns": '"int"'}, "returns"),
        ({"wait": '"W"'}, "wait"),
        ({"since": '"5"'}, "since"),
        ({"statement": '"yes"'}, "statement"),
        ({"errors": '["111"]'}, "errors"),
        ({"args": '["number"]'}, "args"),
        ({"args": '["word:"]'}, "args"),
        ({"args": '["word:on|off"]'}, "args"),
        ({"args": '["expr?", "expr"]'}, "args"),
        ({"args": '["expr+", "var"]'}, "args"),
        ({"kind": '"sysvar"', "args": "[]"}, "returns"),
        ({"colour": '"red"'}, "colour"),
    ],
)
def test_a_malformed_entry_is_refused_naming_entry_and_field(
    tmp_path: Path, entry: dict[str, str | None], field: str
) -> None:
    path = write(tmp_path, {"name": '"ACC"'}, {**entry})
    with pytest.raises(CommandTableError, match=rf"command #2 'POSA': field '{field}'"):
        command_table(path)


@pytest.mark.parametrize("name", ['"posa"', '"MOTOR  ON"', '" POSA"', '"POS-A"', '""'])
def test_bad_names_are_refused(tmp_path: Path, name: str) -> None:
    with pytest.raises(CommandTableError, match=r"command #1 .*field 'name'"):
        command_table(write(tmp_path, {"name": name}))


def test_duplicate_names_are_refused(tmp_path: Path) -> None:
    with pytest.raises(CommandTableError, match=r"command #2 'POSA': field 'name': duplicate"):
        command_table(write(tmp_path, {}, {}))


@pytest.mark.parametrize("version", ["2", '"1"', "1.0", "true"])
def test_wrong_version_is_refused(tmp_path: Path, version: str) -> None:
    with pytest.raises(CommandTableError, match="version"):
        command_table(write(tmp_path, {}, version=version))


def test_broken_toml_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "commands.toml"
    path.write_text("version = 1\n[[command]\n", encoding="utf-8")
    with pytest.raises(CommandTableError, match="not valid TOML"):
        command_table(path)
