"""AposHighlighter: formats of keywords, comments, numbers, strings, parameters, multi-line comment state."""

from __future__ import annotations

from PySide6.QtGui import QColor, QFont, QTextDocument

from motiontool.ui.editor import AposHighlighter, EditorColors
from motiontool.ui.editor.highlighter import IN_COMMENT


def spans(doc: QTextDocument, line: int) -> dict[str, str]:
    """The text of each formatted range in `line` (0-based) → its foreground colour name."""
    block = doc.findBlockByNumber(line)
    text = block.text()
    ranges = block.layout().formats()
    return {text[r.start:r.start + r.length]: r.format.foreground().color().name() for r in ranges}


def highlighted(text: str, colors: EditorColors | None = None) -> tuple[QTextDocument, AposHighlighter]:
    doc = QTextDocument()
    doc.documentLayout()  # a document without a layout emits no contentsChange, so nothing re-highlights
    doc.setPlainText(text)
    hl = AposHighlighter(doc, colors)
    hl.rehighlight()
    return doc, hl


def test_keyword_comment_number_string_operator(qapp):
    c = EditorColors()
    doc, _ = highlighted('posa 0x1F + 2.5e3 // go\nPRINT "hi", 12')
    first = spans(doc, 0)
    assert first["posa"] == c.keyword  # case-insensitive
    assert first["0x1F"] == c.number and first["2.5e3"] == c.number
    assert first["+"] == c.operator
    assert first["// go"] == c.comment
    second = spans(doc, 1)
    assert second['"hi"'] == c.string and second["12"] == c.number and second["PRINT"] == c.keyword
    ranges = doc.firstBlock().layout().formats()  # keep the list alive while its formats are used
    assert next(r.format.fontWeight() for r in ranges if r.start == 0) == QFont.Weight.Bold


def test_multiword_names_parameters_and_plain_identifiers(qapp):
    c = EditorColors()
    doc, _ = highlighted("MOTOR ON\nSAVE ARRAYS\nSET KPROP arrays\n")
    assert spans(doc, 0) == {"MOTOR ON": c.keyword}
    assert spans(doc, 1) == {"SAVE ARRAYS": c.keyword}
    third = spans(doc, 2)
    assert third == {"SET": c.keyword, "KPROP": c.parameter}  # a lone 'arrays' is just a variable


def test_multiline_comment_uses_block_state(qapp):
    c = EditorColors()
    doc, _ = highlighted("x = 1 /* start\nPOSA 1\nend */ POSA 2\nPOSA 3")
    states = [doc.findBlockByNumber(i).userState() for i in range(4)]
    assert states[0] == IN_COMMENT and states[1] == IN_COMMENT and states[2] != IN_COMMENT
    assert spans(doc, 1) == {"POSA 1": c.comment}
    assert spans(doc, 2)["end */"] == c.comment and spans(doc, 2)["POSA"] == c.keyword
    assert spans(doc, 3)["POSA"] == c.keyword


def test_closing_a_comment_rehighlights_the_following_lines(qapp):
    doc, _ = highlighted("/* open\nPOSA 1\nPOSA 2")
    assert doc.findBlockByNumber(2).userState() == IN_COMMENT
    from PySide6.QtGui import QTextCursor

    cursor = QTextCursor(doc.findBlockByNumber(0))
    cursor.movePosition(QTextCursor.MoveOperation.EndOfBlock)
    cursor.insertText(" */")
    assert doc.findBlockByNumber(2).userState() != IN_COMMENT
    assert spans(doc, 2)["POSA"] == EditorColors().keyword


def test_preprocessor_lines_and_continuations(qapp):
    c = EditorColors()
    doc, _ = highlighted('#define MAX(a, b) \\\n  ((a) > (b)) // cmp\n#include "lib.m"\nx = 1')
    assert spans(doc, 0) == {"#define MAX(a, b) \\": c.preprocessor}
    assert spans(doc, 1)["  ((a) > (b)) "] == c.preprocessor and spans(doc, 1)["// cmp"] == c.comment
    assert spans(doc, 2) == {'#include "lib.m"': c.preprocessor}
    assert "x" not in spans(doc, 3)


def test_set_colors_rehighlights(qapp):
    doc, hl = highlighted("POSA 1")
    hl.set_colors(EditorColors(keyword="#ff0000"))
    assert spans(doc, 0)["POSA"] == QColor("#ff0000").name()
    assert hl.format_for("keyword").foreground().color().name() == "#ff0000"
