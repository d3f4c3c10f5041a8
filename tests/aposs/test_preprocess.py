"""The preprocessor (DG 6814-6994)."""

from pathlib import Path

import pytest

from motiontool.aposs.lexer import NEWLINE
from motiontool.aposs.preprocess import preprocess_file, preprocess_text
from motiontool.language.diagnostics import CompileError


def text_of(source: str, **kw) -> list[str]:
    """The preprocessed program as lines of token texts."""
    lines, line = [], []
    for t in preprocess_text(source, "p.m", **kw).tokens:
        if t.kind in (NEWLINE, "EOF"):
            if line:
                lines.append(" ".join(line))
            line = []
        else:
            line.append(t.text)
    return lines


def test_manual_define_example():
    """DG 6890-6902: PRINT "This is line ",__LINE__ on line 5 prints 5; DIM prm[ARRAY_LEN] → prm[100]."""
    src = ('#define ARRAY_LEN 100\n#define PRINT_MSG print " apos = ",apos," avel = ",avel\n'
           'DIM prm[ARRAY_LEN]\nPRINT_MSG\nPRINT "This is line ",__LINE__\n')
    assert text_of(src) == ["DIM prm [ 100 ]", 'print " apos = " , apos , " avel = " , avel',
                            'PRINT "This is line " , 5']


def test_macro_value_is_taken_at_the_point_of_use():
    """DG 6908-6917: redefining VALUE between two uses of PRINT_MSG prints 10 then 20."""
    src = ('#define VALUE 10\n#define PRINT_MSG print "VALUE = ",VALUE\nPRINT_MSG\n#define VALUE 20\n'
           'PRINT_MSG\n')
    assert text_of(src) == ['print "VALUE = " , 10', 'print "VALUE = " , 20']


def test_function_like_macros_nest():
    """DG 6927-6938: SUM_SQUARE(3,4) → (((3)*(3)) + ((4)*(4)))."""
    src = "#define SQUARE(x) ((x)*(x))\n#define SUM_SQUARE(x,y) (SQUARE(x) + SQUARE(y))\ni = SUM_SQUARE(3,4)\n"
    assert text_of(src) == ["i = ( ( ( 3 ) * ( 3 ) ) + ( ( 4 ) * ( 4 ) ) )"]


def test_no_replacement_inside_strings_and_self_reference_terminates():
    assert text_of('#define A A + 1\nx = A\nPRINT "A"\n') == ["x = A + 1", 'PRINT "A"']


def test_conditional_compilation():
    """DG 6943-6994: #ifdef, #ifndef, #if with comparisons, #elif, #else, #endif."""
    src = ("#define CUSTOMER_A 1\n#define CUSTOMER 1\n#define OPTION 3\n"
           "#if CUSTOMER == CUSTOMER_A\na = 1\n#elif CUSTOMER == 2\na = 2\n#else\na = 3\n#endif\n"
           "#ifdef INCLUDE_DEBUG\nb = 1\n#endif\n#ifndef INCLUDE_DEBUG\nb = 2\n#endif\n"
           "#if OPTION > 2\nc = 1\n#endif\n#if 0\n#if 1\nd = 1\n#endif\n#endif\n#if defined(OPTION)\ne = 1\n#endif\n")
    assert text_of(src) == ["a = 1", "b = 2", "c = 1", "e = 1"]


def test_locations_survive_macros_and_includes(tmp_path: Path):
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "inc.m").write_text("// library\nq = 1\n")
    main = tmp_path / "main.m"
    main.write_text('#define SET_Q(v) q = v\n#include "lib/inc.m"\n  SET_Q(5)\n')
    toks = [t for t in preprocess_file(main).tokens if t.kind not in (NEWLINE, "EOF")]
    q_inc, q_main = toks[0], toks[3]
    assert (Path(q_inc.loc.file).name, q_inc.loc.line, q_inc.loc.col) == ("inc.m", 2, 1)
    assert (q_main.loc.line, q_main.loc.col) == (3, 3)  # the macro's use site
    assert "SET_Q" in q_main.origin[0][0]


def test_system_include_and_backslash_paths(tmp_path: Path):
    """DG 6845-6858: <file> searches only the system include directory; '\\' or '/' in names."""
    system = tmp_path / "sys"
    (system / "Library").mkdir(parents=True)
    (system / "Library" / "Structures.m").write_text("s = 1\n")
    (tmp_path / "here.m").write_text("h = 1\n")
    src = '#include <Library\\Structures.m>\n'
    assert text_of(src, include_dirs=[system]) == ["s = 1"]
    with pytest.raises(CompileError, match="cannot find include file 'here.m'"):
        preprocess_text("#include <here.m>\n", str(tmp_path / "main.m"), include_dirs=[system])


def test_the_command_tables_include_form_is_read_with_warnings(tmp_path: Path):
    """DG 7061: "#INCLUDE	compiler directive: embedding further data	#INCLUDE file" - the spelling of programs before
    MCO 305 (DG 6864: "Before the statement contained no quotes"), which DG 6825 ("the preprocessor commands must
    be lower case only") would refuse: read as #include "file", with a warning for the case and one for the quotes
    (decision L16)."""
    (tmp_path / "defs.m").write_text("d = 7\n")
    result = preprocess_text("#INCLUDE defs.m\nx = d\n", str(tmp_path / "main.m"))
    assert [t.text for t in result.tokens if t.kind == "IDENT"][:2] == ["d", "x"]
    assert [w.message for w in result.warnings] == [
        "write #include: preprocessor directives are lower case (DG 6825)", 'write #include "defs.m"']


@pytest.mark.parametrize("src, message, line", [
    ("#DEFINE X 1\n", "must be lower case", 1),   # only #include has an upper-case form in the manual (L16)
    ("#if 1\nx = 1\n", "#if without #endif", 1),
    ("x = 1\n#endif\n", "#endif without #if", 2),
    ("#if 1\n#else\n#else\n#endif\n", "#else after #else", 3),
    ("#foo\n", "unknown preprocessor directive '#foo'", 1),
    ("#define F(a,b) a\nx = F(1)\n", "macro 'F' takes 2 argument(s), 1 given", 2),
    ("#define F(a) a\nx = F(1\n", "missing ')'", 2),
    ("#pragma FAST\n", "unknown pragma", 1),
    ('#include "missing.m"\n', "cannot find include file 'missing.m'", 1),
    ("#if X +\n#endif\n", "expected a value", 1),
])
def test_preprocessor_errors_name_the_line(src, message, line):
    with pytest.raises(CompileError) as e:
        preprocess_text(src, "p.m")
    assert message in e.value.diagnostic.message
    assert e.value.diagnostic.loc.line == line


def test_recursive_include_is_stopped(tmp_path: Path):
    loop = tmp_path / "loop.m"
    loop.write_text('#include "loop.m"\n')
    with pytest.raises(CompileError, match="nested more than 32 deep"):
        preprocess_file(loop)
