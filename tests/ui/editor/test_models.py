"""The Qt-free editor modules: outline, lang, textops, bookmarks (BookmarkStore), settings."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from motiontool.ui.editor import lang, textops
from motiontool.ui.editor.bookmarks import BookmarkStore, next_bookmark
from motiontool.ui.editor.outline import OutlineItem, outline, program_symbols, strip_code
from motiontool.ui.editor.settings import EditorColors, EditorSettings

PROGRAM = """\
// demo
DIM table[10], other[2][3]
long a, b
double speed
long f(long x) ; // prototype only
#define STEPS 4
start:
ON INT 5 GOSUB on_int
count = 0
/* old:
skipped: */
long f(long x)
{
    return(x * 2)
}
WHILE (1) DO
  CASE 1:
  GOTO start
ENDWHILE
SUBMAINPROG
SUBPROG on_int
  PRINT "label: not"
RETURN
ENDPROG
"""


def test_outline_lists_labels_subprogs_and_function_definitions():
    assert outline(PROGRAM) == [
        OutlineItem("label", "start", 7),
        OutlineItem("function", "f", 12),
        OutlineItem("subprog", "on_int", 21),
    ]


def test_strip_code_blanks_comments_and_strings_keeping_columns():
    lines = strip_code('a = "x // y" // c\n/* 1\n2 */ b = \'z\'')
    assert lines == ["a =              ", "    ", "     b =    "]


def test_program_symbols():
    symbols = program_symbols(PROGRAM)
    assert symbols["table"] == "array" and symbols["other"] == "array"
    assert symbols["a"] == symbols["b"] == symbols["speed"] == symbols["count"] == "variable"
    assert symbols["STEPS"] == "macro"
    assert symbols["start"] == "label" and symbols["on_int"] == "subprog" and symbols["f"] == "function"
    assert "skipped" not in symbols and "PRINT" not in symbols


def test_keywords_and_multiword_names():
    vocab = lang.vocabulary()
    assert {"POSA", "IF", "ENDWHILE", "MOD", "ON"} <= vocab.single
    assert "MOTOR" in vocab.multi_first and "ARRAYS" not in vocab.single
    assert vocab.multi_re.match("motor  on").group() == "motor  on"
    assert "KPROP" in vocab.params


def test_command_at_and_hover_text():
    assert lang.command_at("  POSA 100", 3).name == "POSA"
    assert lang.command_at("MOTOR ON", 6).name == "MOTOR ON"
    assert lang.command_at("SAVE ARRAYS", 8).name == "SAVE ARRAYS"
    assert lang.command_at("x = 1", 0) is None
    text = lang.hover_text("posa 1", 1)
    assert "POSA p" in text and "absolute position" in text
    assert "Proportional" in lang.hover_text("SET KPROP 3", 5)
    assert lang.hover_text("SET KPROP 3", 3) is None


def test_completion_items():
    items = {i.name: i for i in lang.completion_items("my_var = 1\nloop_here:\n")}
    assert items["POSA"].hint == "POSA p" and items["POSA"].kind == "command"
    assert items["KPROP"].kind == "parameter" and "32-60" in items["KPROP"].hint
    assert items["my_var"].kind == "variable" and items["loop_here"].kind == "label"


def test_textops():
    assert textops.expand_tabs("a\tb\n\tc", 4) == "a   b\n    c"
    assert textops.spaces_to_next_stop(5, 4) == 3
    assert textops.unindent("\tx", 4) == "x" and textops.unindent("      x", 4) == "  x"
    assert textops.unindent("  \tx", 4) == "x"
    text = "a(b[c]{d})"
    assert textops.matching_bracket(text, 1) == 9 and textops.matching_bracket(text, 9) == 1
    assert textops.matching_bracket(text, 10) == 1  # just after the bracket
    assert textops.matching_bracket("a(b", 1) is None and textops.matching_bracket("ab", 1) is None
    lines = ["a", "b", "", "c", "d", "", "e"]
    assert textops.next_blank_line(lines, 0) == 2 and textops.next_blank_line(lines, 5) == 6
    assert textops.previous_blank_line(lines, 4) == 2 and textops.previous_blank_line(lines, 1) == 0
    assert textops.paragraph_range(lines, 3) == (3, 4)
    umap = textops.Utf16Map("a\U0001F600b")
    assert umap.to_qt(2) == 3 and umap.from_qt(3) == 2


def test_next_bookmark_wraps():
    assert next_bookmark([5, 2, 9], 2) == 5
    assert next_bookmark([5, 2, 9], 9) == 2
    assert next_bookmark([5, 2, 9], 5, backward=True) == 2
    assert next_bookmark([5, 2, 9], 1, backward=True) == 9
    assert next_bookmark([], 3) is None


def test_bookmark_store_round_trip(tmp_path):
    """Bookmarks are kept OUTSIDE the program file, keyed by its absolute path (ide-spec 1.37 DECISION)."""
    program = tmp_path / "prog" / "print3.m"
    program.parent.mkdir()
    program.write_text("PRINT 1\n", encoding="utf-8")
    store = BookmarkStore(tmp_path / "config" / "bookmarks.json")
    assert store.load(program) == []
    store.save(program, [7, 3, 3])
    other = BookmarkStore(tmp_path / "config" / "bookmarks.json")
    assert other.load(program) == [3, 7]
    assert other.load(tmp_path / "prog" / ".." / "prog" / "print3.m") == [3, 7]  # same absolute path
    data = json.loads((tmp_path / "config" / "bookmarks.json").read_text(encoding="utf-8"))
    assert data["files"] == {str(program.resolve()): [3, 7]}
    assert program.read_text(encoding="utf-8") == "PRINT 1\n"  # the .m file is untouched
    store.save(program, [])
    assert store.load(program) == [] and store.programs() == []


def test_bookmark_store_tolerates_a_damaged_file(tmp_path):
    path = tmp_path / "b.json"
    path.write_text("{not json", encoding="utf-8")
    store = BookmarkStore(path)
    assert store.load("x.m") == []
    store.save("x.m", [1])
    assert store.load("x.m") == [1]


def test_settings_validation():
    assert EditorSettings().tab_size == 4
    with pytest.raises(ValueError):
        EditorSettings(tab_size=1)  # "This can be set to 2 or more" [DG L3146]
    with pytest.raises(ValueError):
        EditorColors(comment="green")
    colors = EditorColors.from_dict({"comment": "#00ff00", "unknown": "#000000"})
    assert colors.comment == "#00ff00" and colors.keyword == EditorColors().keyword
    assert EditorColors.from_dict(colors.to_dict()) == colors


def test_qt_free_modules_do_not_import_qt():
    code = ("import sys\nimport motiontool.ui.editor.search, motiontool.ui.editor.outline, motiontool.ui.editor.lang\n"
            "import motiontool.ui.editor.bookmarks, motiontool.ui.editor.textops, motiontool.ui.editor.settings\n"
            "assert 'PySide6' not in sys.modules, 'Qt imported'\n")
    subprocess.run([sys.executable, "-c", code], check=True)
